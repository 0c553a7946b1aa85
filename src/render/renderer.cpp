#include "render/renderer.h"

#include "render/integrator.h"
#include "render/scene.h"

#include "core/color_management.h"
#include "core/host.h"
#include "core/image_io.h"

#include <fmt/format.h>
#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <chrono>
#include <cstdio>
#include <mutex>

namespace patina::render {

namespace fs = std::filesystem;

namespace {

    constexpr int kTileSize = 16;

    // A per-pixel random stream that depends only on the seed, the pixel and the sample
    // index, so the image is the same for any thread count or tile order.
    Pcg32 pixel_rng(uint64_t seed, int x, int y, int width, int sample)
    {
        const uint64_t pixel = static_cast<uint64_t>(y) * static_cast<uint64_t>(width) + static_cast<uint64_t>(x);
        return Pcg32(mix_bits(seed * 0x9E3779B97F4A7C15ULL + pixel),
                     mix_bits((seed << 32) ^ static_cast<uint64_t>(sample)));
    }

    class Progress {
    public:
        Progress(size_t total, bool quiet) : total_(total), quiet_(quiet), start_(clock::now()) {}

        void step()
        {
            const size_t done = ++done_;
            if (quiet_)
                return;
            std::lock_guard lock(mutex_);
            const double elapsed = seconds();
            if (done != total_ && elapsed - last_ < 0.5)
                return;
            last_ = elapsed;
            const double eta = elapsed / static_cast<double>(done) * static_cast<double>(total_ - done);
            std::fprintf(stderr, "\rrender: %5.1f%%  elapsed %.1fs  ETA %.1fs   ",
                         100.0 * static_cast<double>(done) / static_cast<double>(total_), elapsed, eta);
            if (done == total_)
                std::fputc('\n', stderr);
        }

        double seconds() const
        {
            return std::chrono::duration<double>(clock::now() - start_).count();
        }

    private:
        using clock = std::chrono::steady_clock;
        size_t total_;
        bool quiet_;
        clock::time_point start_;
        std::atomic<size_t> done_{0};
        std::mutex mutex_;
        double last_ = -1.0;
    };

}  // namespace

std::vector<float> render_xyz(const Scene& scene, int threads, bool quiet)
{
    const FilmSettings& film = scene.film;
    std::vector<float> xyz(static_cast<size_t>(film.width) * film.height * 3, 0.0f);
    const int tiles_x = (film.width + kTileSize - 1) / kTileSize;
    const int tiles_y = (film.height + kTileSize - 1) / kTileSize;
    Progress progress(static_cast<size_t>(tiles_x) * tiles_y, quiet);

    std::unique_ptr<tbb::global_control> limit;
    if (threads > 0)
        limit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism,
                                                      static_cast<size_t>(threads));
    tbb::parallel_for(0, tiles_x * tiles_y, [&](int tile) {
        const int x0 = (tile % tiles_x) * kTileSize, y0 = (tile / tiles_x) * kTileSize;
        for (int y = y0; y < std::min(y0 + kTileSize, film.height); ++y)
            for (int x = x0; x < std::min(x0 + kTileSize, film.width); ++x) {
                double sum[3] = {0, 0, 0};
                for (int s = 0; s < film.spp; ++s) {
                    Pcg32 rng = pixel_rng(film.seed, x, y, film.width, s);
                    const float fx = (static_cast<float>(x) + rng.uniform_float()) / static_cast<float>(film.width);
                    const float fy = (static_cast<float>(y) + rng.uniform_float()) / static_cast<float>(film.height);
                    const PatinaWavelengths wl = sample_wavelengths_visible(rng.uniform_float(), film.wavelengths);
                    SampledSpectrum pdf = visible_wavelength_pdf(wl);
                    const SampledSpectrum L = trace_path(scene, scene.camera.generate(fx, fy), wl, pdf, rng);
                    const Xyz c = xyz_from_samples(L, wl, pdf);
                    for (int k = 0; k < 3; ++k)
                        if (std::isfinite(c[static_cast<size_t>(k)]))
                            sum[k] += c[static_cast<size_t>(k)];
                }
                float* out = &xyz[(static_cast<size_t>(y) * film.width + x) * 3];
                for (int k = 0; k < 3; ++k)
                    out[k] = static_cast<float>(sum[k] / film.spp);
            }
        progress.step();
    });
    return xyz;
}

void render_scene_file(const fs::path& scene_file, PluginSearch search, const RenderOptions& options)
{
    Host& host = default_host();
    const SceneFile file = parse_scene_file(scene_file);
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
    }
    fs::path exr = options.output.empty() ? scene.output.exr : options.output;
    if (exr.empty())
        throw std::runtime_error(fmt::format(
            "{}: no output file: set [output] file or pass --output", scene_file.string()));
    if (exr.extension() != ".exr")
        throw std::runtime_error(fmt::format("output '{}' must be an .exr file", exr.string()));
    if (!exr.parent_path().empty() && !fs::is_directory(exr.parent_path()))
        throw std::runtime_error(fmt::format("output folder '{}' does not exist",
                                             exr.parent_path().string()));

    const std::vector<float> xyz = render_xyz(scene, options.threads, options.quiet);

    // XYZ -> working space (OCIO), then the display image through the chosen view.
    const ColorManager& colors = host.colors();
    const size_t npix = static_cast<size_t>(scene.film.width) * scene.film.height;
    std::vector<float> rgb = xyz;
    colors.convert("CIE-XYZ-D65", colors.working_space(), rgb.data(), npix);
    const Metadata meta = {
        {"patina:scene", fs::absolute(scene_file).string()},
        {"patina:spp", scene.film.spp},
        {"patina:seed", static_cast<int>(scene.film.seed)},
        {"patina:wavelengths", scene.film.wavelengths},
        {"oiio:ColorSpace", colors.working_space()},
    };
    std::vector<float> display;
    if (scene.output.png) {
        display = rgb;
        colors.convert_display(colors.working_space(), scene.output.display, scene.output.view,
                               display.data(), npix);
    }
    write_image_atomic(exr, rgb.data(), scene.film.width, scene.film.height, 3, {"R", "G", "B"},
                       OIIO::TypeDesc::FLOAT, meta);
    if (scene.output.png) {
        fs::path png = exr;
        png.replace_extension(".png");
        write_image_atomic(png, display.data(), scene.film.width, scene.film.height, 3, {},
                           OIIO::TypeDesc::UINT8);
    }
}

}  // namespace patina::render
