#include "render/renderer.h"

#include "render/film_output.h"
#include "render/integrator.h"
#include "render/wavefront.h"
#include "core/progress.h"
#include "render/scene.h"

#include "core/cancel.h"
#include "host/host.h"
#include "core/limits.h"
#include "core/output_transaction.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <array>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <optional>
#include <stdexcept>
#include <tuple>

#if defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace patina::render {

namespace fs = std::filesystem;

namespace {

    constexpr int kTileSize = 16;

    // Albedo AOV: the albedo spectrum as a reflectance under D65 of unit luminance, so a
    // white albedo gives XYZ of the working space's white.
    float unit_d65(float lambda_nm)
    {
        static const float k = static_cast<float>(1.0 / emission_to_xyz(d65)[1]);
        return d65(lambda_nm) * k;
    }

    // Per-pixel sums over sample passes, in double, each pixel's samples added in order.
    using Accumulator = FilmSums;

    // Camera rays go to Embree in batches of one tile row's pixels times up to
    // kBatchSamples samples each (64 rays, AVX2 packets of 2 pixels x 4 samples).
    constexpr int kBatchSamples = 4;
    constexpr size_t kBatchRays = static_cast<size_t>(kTileSize) * kBatchSamples;

    // A camera sample waiting for its ray's hit: its generator, ray and the number its
    // wavelengths come from (they are drawn after the hit, with their CIE values).
    struct CameraSample {
        Pcg32 rng;
        Ray ray;
        float u_wavelengths;
    };
    struct CameraBatch {
        std::array<CameraSample, kBatchRays> samples;
        std::array<RayQuery, kBatchRays> queries;
        std::array<std::optional<Hit>, kBatchRays> hits;
    };

    // Add one sample's colour to pixel i's sums (i indexes the region).
    void accumulate_xyz(Accumulator& acc, size_t i, const SampledSpectrum& L,
                        const CieAtWavelengths& cie, const SampledSpectrum& pdf)
    {
        const Xyz c = xyz_from_samples(L, cie, pdf);
        for (size_t k = 0; k < 3; ++k)
            if (std::isfinite(c[k]))
                acc.xyz[i * 3 + k] += c[k];
    }

    // The same and the sample's AOVs.
    void accumulate(Accumulator& acc, const FilmSettings& film, size_t i, const SampledSpectrum& L,
                    const PatinaWavelengths& wl, const CieAtWavelengths& cie,
                    const SampledSpectrum& pdf, const PathAovs& aov)
    {
        accumulate_xyz(acc, i, L, cie, pdf);
        if (!aov.hit)
            return;
        if (film.aov_albedo) {
            // The density the wavelengths were drawn with (pdf may have lost its secondary
            // wavelengths to dispersion after the first hit).
            const SampledSpectrum a = aov.albedo * SampledSpectrum::from_function(wl, unit_d65);
            const Xyz ax = xyz_from_samples(
                a, wl, SampledSpectrum::from_function(wl, tabulated_wavelength_pdf));
            for (size_t k = 0; k < 3; ++k)
                acc.albedo[i * 3 + k] += ax[k];
        }
        if (film.aov_normal)
            for (size_t k = 0; k < 3; ++k)
                acc.normal[i * 3 + k] += aov.normal[static_cast<int>(k)];
        if (film.aov_depth)
            acc.depth[i] += aov.depth;
    }

    // Flush-to-zero and denormals-are-zero for the scope (Embree's manual asks for both:
    // its traversal slows down badly on denormal numbers), the caller's mode restored after.
    // Per tile, since MXCSR is per thread and TBB's workers keep theirs.
    class DenormalsAreZero {
    public:
#if defined(__SSE__)
        DenormalsAreZero() : saved_(_mm_getcsr()) { _mm_setcsr(saved_ | kFtz | kDaz); }
        ~DenormalsAreZero() { _mm_setcsr(saved_); }
#endif
        DenormalsAreZero(const DenormalsAreZero&) = delete;
        DenormalsAreZero& operator=(const DenormalsAreZero&) = delete;

    private:
#if defined(__SSE__)
        static constexpr unsigned kFtz = 0x8000, kDaz = 0x0040;
        unsigned saved_;
#endif
    };

    bool per_path_forced()
    {
        const char* v = std::getenv("PATINA_RENDER_PER_PATH");
        return v && v[0] == '1';
    }

    int parse_int(std::string_view text, const char* what)
    {
        int v = 0;
        const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
        if (ec != std::errc() || ptr != text.data() + text.size())
            throw std::invalid_argument(fmt::format("{}: '{}' is not an integer", what, text));
        return v;
    }

    // A wavefront holds one tile row's pixels times up to this many samples (256 paths);
    // a multiple of kBatchSamples, so that the camera batches are the per-path loop's.
    constexpr int kWaveSamples = 16;

    // Everything a tile needs to render in wavefront form, reused from row to row.
    struct WaveTile {
        CameraBatch batch;  // its queries and hits (the paths hold the rest)
        std::array<float, kBatchRays> u_wavelengths;
        std::array<SpectralSetUp, kBatchRays> set_up;  // where each sample's wavelengths go
        std::vector<WavefrontPath> paths;
        std::vector<uint32_t> pixel;  // the region's pixel index of each path
        WavefrontScratch scratch;
    };

    // Samples [s0, s1) of the tile row's pixels [tx0, tx1) x {ly} in wavefront form: the
    // camera rays in the per-path loop's batches (the same generators, rays and hits), then
    // every path at once, then the film sums in the per-path loop's order (per pixel by
    // sample index), so the pixels are bitwise the per-path loop's.
    void render_row_wavefront(const Scene& scene, const Region& region, int tx0, int tx1, int ly,
                              int s0, int s1, const Camera::Raster& raster, bool want_aovs,
                              Accumulator& acc, WaveTile& wt)
    {
        const FilmSettings& film = scene.film;
        const bool pinhole = scene.camera.is_pinhole();
        const int w = region.width();
        const int y = region.y0 + ly;
        std::array<uint64_t, kTileSize> streams;  // each pixel's hash, taken once
        for (int lx = tx0; lx < tx1; ++lx)
            streams[static_cast<size_t>(lx - tx0)] = pixel_stream(film.seed, region.x0 + lx, y);
        CameraBatch& batch = wt.batch;
        for (int c0 = s0, c1 = 0; c0 < s1; c0 = c1) {
            if (cancel_requested())
                return;  // the pass is thrown away (render_region)
            c1 = std::min(s1, (c0 / kWaveSamples + 1) * kWaveSamples);
            wt.paths.resize(static_cast<size_t>(tx1 - tx0) * static_cast<size_t>(c1 - c0));
            wt.pixel.resize(wt.paths.size());
            size_t np = 0;
            for (int g0 = c0, g1 = 0; g0 < c1; g0 = g1) {
                g1 = std::min(c1, (g0 / kBatchSamples + 1) * kBatchSamples);
                // The batch's paths are written in place: generator and camera ray first,
                // the hit and the wavelengths after the batch is traced.
                size_t n = 0;
                for (int lx = tx0; lx < tx1; ++lx) {
                    const int x = region.x0 + lx;
                    for (int s = g0; s < g1; ++s, ++n) {
                        WavefrontPath& p = wt.paths[np + n];
                        p.rng = sample_rng(streams[static_cast<size_t>(lx - tx0)], film.seed,
                                           static_cast<uint64_t>(s));
                        const float px = static_cast<float>(x) + p.rng.uniform_float();
                        const float py = static_cast<float>(y) + p.rng.uniform_float();
                        if (pinhole) {
                            p.ray = raster.ray(px, py);
                        } else {
                            const Imath::V2f lens{p.rng.uniform_float(), p.rng.uniform_float()};
                            p.ray = scene.camera.generate(px / static_cast<float>(film.width),
                                                          py / static_cast<float>(film.height),
                                                          lens);
                        }
                        wt.u_wavelengths[n] = p.rng.uniform_float();
                        batch.queries[n] = {p.ray.origin, p.ray.dir};
                    }
                }
                scene.geometry->intersect_coherent(std::span(batch.queries.data(), n),
                                                   std::span(batch.hits.data(), n));
                // The batch's wavelengths: for 4 (the usual count) in one call for all its
                // samples, whose look-ups then overlap.
                const size_t first = np;
                n = 0;
                for (int lx = tx0; lx < tx1; ++lx) {
                    for (int s = g0; s < g1; ++s, ++n, ++np) {
                        WavefrontPath& p = wt.paths[np];
                        p.hit = batch.hits[n];
                        wt.set_up[n] = {&p.wl, &p.pdf, &p.cie};
                        wt.pixel[np] = static_cast<uint32_t>(ly * w + lx);
                    }
                }
                if (film.wavelengths == 4) {
                    sample_wavelengths_tabulated4(std::span(wt.u_wavelengths.data(), n),
                                                  std::span(wt.set_up.data(), n));
                } else {
                    for (size_t k = 0; k < n; ++k) {
                        WavefrontPath& p = wt.paths[first + k];
                        sample_wavelengths_tabulated(wt.u_wavelengths[k], film.wavelengths, p.wl,
                                                     p.pdf, p.cie);
                    }
                }
            }
            trace_wavefront(scene, std::span(wt.paths.data(), np), want_aovs, wt.scratch);
            // Per pixel the paths stand in sample order (group by group), as the per-path
            // loop adds them.
            for (size_t k = 0; k < np; ++k) {
                const WavefrontPath& p = wt.paths[k];
                if (want_aovs)
                    accumulate(acc, film, wt.pixel[k], p.L, p.wl, p.cie, p.pdf, p.aov);
                else
                    accumulate_xyz(acc, wt.pixel[k], p.L, p.cie, p.pdf);
            }
        }
    }

}  // namespace

Region tile_region(int index, int count, int width, int height)
{
    if (count < 1 || index < 0 || index >= count)
        throw std::invalid_argument(fmt::format("--tile {}/{}: need 0 <= i < n", index, count));
    if (count > height)
        throw std::invalid_argument(fmt::format("--tile {}/{}: more tiles than the {} rows", index,
                                                count, height));
    const int base = height / count, extra = height % count;
    const int y0 = index * base + std::min(index, extra);
    const int y1 = y0 + base + (index < extra ? 1 : 0);
    return {0, y0, width, y1};
}

std::pair<int, int> parse_tile(const std::string& text)
{
    const size_t slash = text.find('/');
    if (slash == std::string::npos)
        throw std::invalid_argument(fmt::format("--tile '{}': expected i/n, e.g. 0/4", text));
    return {parse_int(std::string_view(text).substr(0, slash), "--tile"),
            parse_int(std::string_view(text).substr(slash + 1), "--tile")};
}

std::pair<int, int> parse_frames(const std::string& text)
{
    const size_t dash = text.find('-', 1);
    const std::pair<int, int> range =
        dash == std::string::npos
            ? std::pair{parse_int(text, "--frames"), parse_int(text, "--frames")}
            : std::pair{parse_int(std::string_view(text).substr(0, dash), "--frames"),
                        parse_int(std::string_view(text).substr(dash + 1), "--frames")};
    if (range.second < range.first)
        throw std::invalid_argument(fmt::format("--frames '{}': last frame before first", text));
    return range;
}

std::pair<int, int> parse_samples(const std::string& text)
{
    const size_t dash = text.find('-', 1);
    if (dash == std::string::npos)
        throw std::invalid_argument(fmt::format(
            "--samples '{}': expected A-B, the samples A to B - 1 of every pixel", text));
    const std::pair<int, int> range{
        parse_int(std::string_view(text).substr(0, dash), "--samples"),
        parse_int(std::string_view(text).substr(dash + 1), "--samples")};
    if (range.first < 0 || range.second <= range.first)
        throw std::invalid_argument(fmt::format(
            "--samples '{}': expected 0 <= A < B (samples A to B - 1)", text));
    if (range.second > 1 << 20)
        throw std::invalid_argument(fmt::format(
            "--samples '{}': B is at most {} (the samples per pixel a scene may ask for)", text,
            1 << 20));
    return range;
}

std::string substitute_frame(const std::string& pattern, int frame)
{
    const size_t first = pattern.find('#');
    if (first == std::string::npos)
        return pattern;
    size_t last = first;
    while (last < pattern.size() && pattern[last] == '#')
        ++last;
    return pattern.substr(0, first) +
           fmt::format("{:0{}d}", frame, static_cast<int>(last - first)) + pattern.substr(last);
}

FilmResult render_region(const Scene& scene, const Region& region, const RenderControl& control)
{
    const FilmSettings& film = scene.film;
    const int w = region.width(), h = region.height();
    const size_t npix = static_cast<size_t>(w) * static_cast<size_t>(h);
    Accumulator acc;
    acc.xyz.assign(npix * 3, 0.0);
    if (film.aov_albedo)
        acc.albedo.assign(npix * 3, 0.0);
    if (film.aov_normal)
        acc.normal.assign(npix * 3, 0.0);
    if (film.aov_depth)
        acc.depth.assign(npix, 0.0);
    const bool want_aovs = film.aov_albedo || film.aov_normal || film.aov_depth;
    if (control.resume) {
        const FilmSums& r = *control.resume;
        if (r.xyz.size() != acc.xyz.size() || r.albedo.size() != acc.albedo.size() ||
            r.normal.size() != acc.normal.size() || r.depth.size() != acc.depth.size())
            throw std::invalid_argument(
                "the checkpoint's sums do not fit this render's region and AOVs");
        acc = r;
    }

    const int tiles_x = (w + kTileSize - 1) / kTileSize;
    const int tiles_y = (h + kTileSize - 1) / kTileSize;
    // With a time limit the samples come in passes, checked between passes; the sums per
    // pixel are taken in sample order either way, so a pass split does not change bits.
    // Samples [begin, end) of every pixel: the whole render, or a farm's sample range.
    const int begin = control.sample_begin;
    const int end = control.sample_end > 0 ? control.sample_end : film.spp;
    const int count = end - begin;
    if (begin < 0 || count <= 0)
        throw std::invalid_argument(fmt::format("samples {}-{}: an empty or negative range",
                                                begin, end));
    // With a time limit, or sums kept for a checkpoint (a signal then stops the render
    // after its last whole pass), the samples come in passes of 4.
    const bool in_passes = control.time_limit || control.keep_sums;
    const int pass_spp = in_passes ? std::max(1, std::min(count, 4)) : count;
    const int passes = (count + pass_spp - 1) / pass_spp;
    Progress progress(static_cast<size_t>(tiles_x) * tiles_y * passes, control.quiet);

    std::unique_ptr<tbb::global_control> limit;
    if (control.threads > 0)
        limit = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, static_cast<size_t>(control.threads));

    // Pinhole camera rays from per-frame terms (the lens numbers are not drawn then).
    const bool pinhole = scene.camera.is_pinhole();
    const Camera::Raster raster = scene.camera.raster(film.width, film.height);
    // Surface-only scenes take the wavefront loop (the same bits as the per-path loop);
    // scenes with media the per-path loop. PATINA_RENDER_PER_PATH=1 forces the latter
    // (for comparisons).
    const bool wavefront = wavefront_supported(scene) && !per_path_forced();

    int spp_done = 0;
    bool interrupted = false;
    FilmSums before_pass;  // with keep_sums: the sums of the whole passes, for a signal
    for (int pass = 0; pass < passes; ++pass) {
        const int s0 = begin + pass * pass_spp, s1 = std::min(end, s0 + pass_spp);
        if (control.keep_sums)
            before_pass = acc;
        tbb::parallel_for(0, tiles_x * tiles_y, [&](int tile) {
            const DenormalsAreZero daz;
            const int tx0 = (tile % tiles_x) * kTileSize, ty0 = (tile / tiles_x) * kTileSize;
            const int tx1 = std::min(tx0 + kTileSize, w);
            if (wavefront) {
                // One per thread, kept from tile to tile: every field a row reads is
                // written for it first, so reuse cannot change a pixel.
                static thread_local WaveTile wt;
                for (int ly = ty0; ly < std::min(ty0 + kTileSize, h); ++ly)
                    render_row_wavefront(scene, region, tx0, tx1, ly, s0, s1, raster, want_aovs,
                                         acc, wt);
                progress.step();
                return;
            }
            CameraBatch batch;
            // Every lane of these is rewritten for each sample: made once per tile, not
            // zeroed per sample.
            SampledSpectrum pdf;
            CieAtWavelengths cie;
            for (int ly = ty0; ly < std::min(ty0 + kTileSize, h); ++ly) {
                const int y = region.y0 + ly;
                std::array<uint64_t, kTileSize> streams;  // each pixel's hash, taken once
                for (int lx = tx0; lx < tx1; ++lx)
                    streams[static_cast<size_t>(lx - tx0)] = pixel_stream(film.seed, region.x0 + lx, y);
                // Samples in groups aligned to multiples of kBatchSamples, whatever the pass
                // size, so that a batch holds the same rays in every render of the pixel.
                for (int g0 = s0; g0 < s1; g0 = std::min(s1, (g0 / kBatchSamples + 1) * kBatchSamples)) {
                    if (cancel_requested())
                        return;  // a signal: the pass is thrown away below
                    const int g1 = std::min(s1, (g0 / kBatchSamples + 1) * kBatchSamples);
                    // The camera rays of the row's pixels and these samples, traced as one
                    // coherent stream; each sample keeps its own generator for its path.
                    size_t n = 0;
                    for (int lx = tx0; lx < tx1; ++lx) {
                        const int x = region.x0 + lx;
                        for (int s = g0; s < g1; ++s, ++n) {
                            CameraSample& cs = batch.samples[n];
                            // pixel_sample_rng(seed, x, y, s), with the pixel's hash taken once.
                            cs.rng = sample_rng(streams[static_cast<size_t>(lx - tx0)], film.seed,
                                                static_cast<uint64_t>(s));
                            const float px = static_cast<float>(x) + cs.rng.uniform_float();
                            const float py = static_cast<float>(y) + cs.rng.uniform_float();
                            if (pinhole) {
                                cs.ray = raster.ray(px, py);
                            } else {
                                const Imath::V2f lens{cs.rng.uniform_float(), cs.rng.uniform_float()};
                                cs.ray = scene.camera.generate(px / static_cast<float>(film.width),
                                                               py / static_cast<float>(film.height),
                                                               lens);
                            }
                            cs.u_wavelengths = cs.rng.uniform_float();
                            batch.queries[n] = {cs.ray.origin, cs.ray.dir};
                        }
                    }
                    scene.geometry->intersect_coherent(std::span(batch.queries.data(), n),
                                                       std::span(batch.hits.data(), n));
                    n = 0;
                    for (int lx = tx0; lx < tx1; ++lx) {
                        const size_t i = static_cast<size_t>(ly) * w + lx;
                        for (int s = g0; s < g1; ++s, ++n) {
                            CameraSample& cs = batch.samples[n];
                            const PatinaWavelengths wl = sample_wavelengths_tabulated(
                                cs.u_wavelengths, film.wavelengths, pdf, cie);
                            if (!want_aovs) {
                                const SampledSpectrum L =
                                    trace_path(scene, cs.ray, batch.hits[n], wl, cie, pdf, cs.rng);
                                accumulate_xyz(acc, i, L, cie, pdf);
                                continue;
                            }
                            PathAovs aov;
                            const SampledSpectrum L = trace_path(scene, cs.ray, batch.hits[n], wl,
                                                                 cie, pdf, cs.rng, &aov);
                            accumulate(acc, film, i, L, wl, cie, pdf, aov);
                        }
                    }
                }
            }
            progress.step();
        });
        const int kept = spp_done + (control.resume ? control.resume_samples : 0);
        if (control.keep_sums && cancel_requested() && kept > 0) {
            // A signal: the pass it cut is dropped, the whole passes are kept for --resume.
            acc = std::move(before_pass);
            interrupted = true;
            break;
        }
        throw_if_cancelled();
        spp_done = s1 - begin;
        if (control.time_limit && progress.seconds() > *control.time_limit)
            break;
    }
    progress.finish();

    FilmResult out;
    out.region = region;
    out.interrupted = interrupted;
    // With a checkpoint, the samples before `begin` are in the sums too.
    const int prior = control.resume ? control.resume_samples : 0;
    out.spp = prior + spp_done;
    out.sample_begin = begin - prior;
    auto mean = [&](const std::vector<double>& sums) {
        std::vector<float> v(sums.size());
        for (size_t i = 0; i < sums.size(); ++i)
            v[i] = static_cast<float>(sums[i] / out.spp);
        return v;
    };
    out.xyz = mean(acc.xyz);
    out.albedo_xyz = mean(acc.albedo);
    out.normal = mean(acc.normal);
    out.depth = mean(acc.depth);
    if (control.keep_sums)
        out.sums = std::move(acc);
    return out;
}

std::vector<float> render_xyz(const Scene& scene, int threads, bool quiet)
{
    const Region full{0, 0, scene.film.width, scene.film.height};
    return render_region(scene, full, {threads, quiet, std::nullopt}).xyz;
}

namespace {

    Region region_for(const Scene& scene, const RenderOptions& options)
    {
        Region r{0, 0, scene.film.width, scene.film.height};
        if (options.crop.size() == 4) {
            const Region c{options.crop[0], options.crop[1], options.crop[2], options.crop[3]};
            if (c.x0 < 0 || c.y0 < 0 || c.x1 > r.x1 || c.y1 > r.y1 || c.width() <= 0 ||
                c.height() <= 0)
                throw std::invalid_argument(fmt::format(
                    "--crop {} {} {} {}: must lie inside the {}x{} frame with x0 < x1, y0 < y1",
                    c.x0, c.y0, c.x1, c.y1, r.x1, r.y1));
            r = c;
        }
        if (!options.tile.empty()) {
            if (options.crop.size() == 4)
                throw std::invalid_argument("--tile and --crop cannot be combined");
            const auto [i, n] = parse_tile(options.tile);
            r = tile_region(i, n, scene.film.width, scene.film.height);
        }
        return r;
    }

    void render_frame(const fs::path& scene_file, PluginSearch search, const RenderOptions& options,
                      const fs::path& output)
    {
        Host& host = default_host();
        const SceneFile file = parse_scene_file(scene_file);
        check_scene_plugins(file.plugin_dirs, file.plugins_where, search);
        search.scene = file.plugin_dirs;
        PluginRegistry registry(host.c_host());
        load_plugins(registry, search);
        Scene scene = build_scene(file, registry, host);

        // Command-line overrides.
        if (options.spp)
            scene.film.spp = *options.spp;
        if (options.seed)
            scene.film.seed = *options.seed;
        if (options.resolution.size() == 2) {
            scene.film.width = options.resolution[0];
            scene.film.height = options.resolution[1];
            scene.camera.set_aspect(static_cast<float>(scene.film.width) / scene.film.height);
        }
        {
            // The film's sums (doubles) and the written pixels, before they are allocated.
            const FilmSettings& f = scene.film;
            const double per_pixel = 8.0 * (3 + 3 * f.aov_albedo + 3 * f.aov_normal + f.aov_depth) +
                                     4.0 * (3 + 3 * f.aov_albedo + 3 * f.aov_normal + f.aov_depth) +
                                     4.0 * 9;  // working-space, display and albedo copies
            check_memory(options.resolution.size() == 2
                             ? std::string("--resolution")
                             : scene_file.string() + ": [film] width and height",
                         per_pixel * f.width * f.height,
                         fmt::format("a {}x{} film", f.width, f.height));
        }
        fs::path exr = output.empty() ? scene.output.exr : output;
        if (exr.empty())
            throw std::runtime_error(fmt::format(
                "{}: no output file: set [output] file or pass --output", scene_file.string()));
        check_output_path(exr);
        // The EXR and the PNG move into place together, after both are complete; their
        // locations are checked before the render starts.
        OutputTransaction outputs;
        const CurrentOutputs current(outputs);
        for (const fs::path& file : film_files(scene, exr))
            outputs.reserve(file);

        const Region region = region_for(scene, options);
        RenderControl control{options.threads, options.quiet, options.time_limit};
        control.keep_sums = options.checkpoint;
        if (!options.samples.empty()) {
            if (options.spp)
                throw std::invalid_argument("--samples and --spp exclude each other: --samples "
                                            "A-B takes samples A to B - 1");
            if (!options.resume.empty())
                throw std::invalid_argument("--samples and --resume exclude each other");
            std::tie(control.sample_begin, control.sample_end) = parse_samples(options.samples);
        }
        std::optional<Checkpoint> checkpoint;
        if (!options.resume.empty()) {
            // Continue the checkpoint's render: its sums, then the samples after its last.
            checkpoint = read_checkpoint(options.resume);
            const Checkpoint& c = *checkpoint;
            auto refuse = [&](const std::string& why) {
                return std::invalid_argument(
                    fmt::format("--resume '{}': {}", options.resume.string(), why));
            };
            if (c.scene_hash != scene_hash(scene_file))
                throw refuse(fmt::format("a render of another scene (hash {}, {} has {})",
                                         c.scene_hash, scene_file.string(),
                                         scene_hash(scene_file)));
            if (c.seed != static_cast<int>(scene.film.seed))
                throw refuse(fmt::format("rendered with seed {}, this render has seed {}", c.seed,
                                         scene.film.seed));
            if (c.full_width != scene.film.width || c.full_height != scene.film.height ||
                c.region.x0 != region.x0 || c.region.y0 != region.y0 ||
                c.region.x1 != region.x1 || c.region.y1 != region.y1)
                throw refuse("other pixels: give the same resolution, --crop or --tile");
            if (scene.film.spp <= c.sample_end)
                throw refuse(fmt::format("it has samples {}-{} already; ask for more with --spp",
                                         c.sample_begin, c.sample_end));
            control.sample_begin = c.sample_end;
            control.sample_end = scene.film.spp;
            control.resume = &c.sums;
            control.resume_samples = c.sample_end - c.sample_begin;
        }
        const FilmResult film = render_region(scene, region, control);
        // A render stopped by a signal with --checkpoint is written all the same: its whole
        // passes are a checkpoint (the flag is cleared so that the outputs commit; a second
        // signal still ends the process at once).
        if (film.interrupted)
            reset_cancel();
        write_film(scene, film, exr, scene_file, scene_plugin_set(file.root, registry),
                   host.colors());
        outputs.commit();
        if (film.interrupted)
            throw CheckpointWritten(fmt::format(
                "interrupted after {} samples per pixel, written with its sums; continue "
                "with --resume {}", film.spp, exr.string()));
    }

}  // namespace

void render_scene_file(const fs::path& scene_file, PluginSearch search, const RenderOptions& options)
{
    if (options.frames.empty()) {
        render_frame(scene_file, search, options, options.output);
        return;
    }
    const auto [first, last] = parse_frames(options.frames);
    for (int frame = first; frame <= last; ++frame) {
        const fs::path scene_path = substitute_frame(scene_file.string(), frame);
        const fs::path out = options.output.empty() ? fs::path()
                                                    : fs::path(substitute_frame(options.output.string(), frame));
        if (!options.quiet)
            std::fprintf(stderr, "frame %d: %s\n", frame, scene_path.string().c_str());
        if (!fs::exists(scene_path))
            throw std::runtime_error(fmt::format("frame {}: scene file '{}' does not exist", frame,
                                                 scene_path.string()));
        try {
            render_frame(scene_path, search, options, out);
        } catch (const Cancelled&) {
            // Each frame is committed on its own: say which ones are complete.
            if (frame > first)
                std::fprintf(stderr, "patina-render: frames %d-%d were written before the "
                                     "stop; frame %d was not\n", first, frame - 1, frame);
            throw;
        }
    }
}

}  // namespace patina::render
