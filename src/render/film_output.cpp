#include "render/film_output.h"

#include "formats/render_part/render_part.h"

#include "core/file_fingerprint.h"
#include "core/image_io.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <cstdint>
#include <stdexcept>

namespace patina::render {

namespace fs = std::filesystem;

void check_output_path(const fs::path& exr)
{
    if (exr.extension() != ".exr")
        throw std::runtime_error(fmt::format("output '{}' must be an .exr file", exr.string()));
    if (!exr.parent_path().empty() && !fs::is_directory(exr.parent_path()))
        throw std::runtime_error(
            fmt::format("output folder '{}' does not exist", exr.parent_path().string()));
}

std::vector<fs::path> film_files(const Scene& scene, const fs::path& exr)
{
    std::vector<fs::path> files{exr};
    if (scene.output.png)
        files.push_back(fs::path(exr).replace_extension(".png"));
    return files;
}

std::string scene_hash(const fs::path& scene_file)
{
    return file_fingerprint(scene_file);
}

Checkpoint read_checkpoint(const fs::path& exr)
{
    auto fail = [&](const std::string& what) {
        return std::runtime_error(fmt::format("--resume '{}': {}", exr.string(), what));
    };
    auto in = OIIO::ImageInput::open(exr.string());
    if (!in)
        throw fail(OIIO::geterror());
    Checkpoint c;
    const OIIO::ImageSpec beauty = in->spec();
    formats::RenderHeader header;
    try {
        header = formats::read_render_header(metadata_of(beauty));
    } catch (const std::exception& e) {
        throw fail(fmt::format("{}: not a render Patina can continue", e.what()));
    }
    c.scene_hash = header.scene_hash;
    c.seed = header.seed;
    c.sample_begin = header.sample_begin;
    c.sample_end = header.sample_end;
    c.full_width = beauty.full_width;
    c.full_height = beauty.full_height;
    c.region = {beauty.x, beauty.y, beauty.x + beauty.width, beauty.y + beauty.height};
    int part = -1;
    for (int sub = 1; in->seek_subimage(sub, 0); ++sub)
        if (in->spec().get_string_attribute("name") == "sums")
            part = sub;
    if (part < 0)
        throw fail("it holds no sums (part \"sums\"): render with --checkpoint to continue later");
    in->seek_subimage(part, 0);
    const OIIO::ImageSpec spec = in->spec();
    const size_t npix = static_cast<size_t>(beauty.width) * beauty.height;
    // The layout the header names: xyz, then the AOVs the render kept.
    const std::string& layout = header.sums_layout;
    const bool with_albedo = layout.find("albedo") != std::string::npos;
    const bool with_normal = layout.find("normal") != std::string::npos;
    const bool with_depth = layout.find("depth") != std::string::npos;
    const int doubles = 3 + (with_albedo ? 3 : 0) + (with_normal ? 3 : 0) + (with_depth ? 1 : 0);
    if (spec.width != beauty.width || spec.height != beauty.height ||
        spec.nchannels != 2 * doubles)
        throw fail(fmt::format("part \"sums\" is {}x{} pixels of {} channels, not {}x{} of {} "
                               "(patina:sums_layout '{}')",
                               spec.width, spec.height, spec.nchannels, beauty.width,
                               beauty.height, 2 * doubles, layout));
    std::vector<uint32_t> bits(npix * static_cast<size_t>(spec.nchannels));
    if (!in->read_image(part, 0, 0, spec.nchannels, OIIO::TypeDesc::UINT32, bits.data()))
        throw fail(in->geterror());
    c.sums.xyz.resize(npix * 3);
    if (with_albedo)
        c.sums.albedo.resize(npix * 3);
    if (with_normal)
        c.sums.normal.resize(npix * 3);
    if (with_depth)
        c.sums.depth.resize(npix);
    size_t at = 0;
    auto take = [&](std::vector<double>& v, size_t i, size_t n) {
        for (size_t k = 0; k < n; ++k, at += 2)
            v[i * n + k] = std::bit_cast<double>((uint64_t(bits[at]) << 32) | bits[at + 1]);
    };
    for (size_t i = 0; i < npix; ++i) {
        take(c.sums.xyz, i, 3);
        if (with_albedo)
            take(c.sums.albedo, i, 3);
        if (with_normal)
            take(c.sums.normal, i, 3);
        if (with_depth)
            take(c.sums.depth, i, 1);
    }
    return c;
}

void write_film(const Scene& scene, const FilmResult& film, const fs::path& exr,
                const fs::path& scene_file, const std::string& plugins,
                const ColorManager& colors)
{
    const size_t npix = static_cast<size_t>(film.region.width()) * film.region.height();
    // XYZ -> working space (OCIO) for the beauty and the albedo.
    std::vector<float> rgb = film.xyz;
    colors.convert("CIE-XYZ-D65", colors.working_space(), rgb.data(), npix);
    std::vector<float> albedo = film.albedo_xyz;
    if (!albedo.empty())
        colors.convert("CIE-XYZ-D65", colors.working_space(), albedo.data(), npix);

    // Interleave the channels the scene asked for.
    std::vector<std::string> names = {"R", "G", "B"};
    if (!albedo.empty())
        names.insert(names.end(), {"albedo.R", "albedo.G", "albedo.B"});
    if (!film.normal.empty())
        names.insert(names.end(), {"N.X", "N.Y", "N.Z"});
    if (!film.depth.empty())
        names.push_back("Z");
    const size_t nc = names.size();
    std::vector<float> pixels(npix * nc);
    for (size_t i = 0; i < npix; ++i) {
        float* p = &pixels[i * nc];
        for (size_t k = 0; k < 3; ++k)
            *p++ = rgb[i * 3 + k];
        if (!albedo.empty())
            for (size_t k = 0; k < 3; ++k)
                *p++ = albedo[i * 3 + k];
        if (!film.normal.empty())
            for (size_t k = 0; k < 3; ++k)
                *p++ = film.normal[i * 3 + k];
        if (!film.depth.empty())
            *p++ = film.depth[i];
    }

    formats::RenderHeader header;
    header.scene = fs::absolute(scene_file).string();
    header.spp = film.spp;
    header.sample_begin = film.sample_begin;
    header.sample_end = film.sample_begin + film.spp;
    header.scene_hash = scene_hash(scene_file);
    header.plugins = plugins;
    header.sums_layout = film.sums.xyz.empty()
                             ? std::string()
                             : fmt::format("xyz{}{}{}", film.sums.albedo.empty() ? "" : " albedo",
                                           film.sums.normal.empty() ? "" : " normal",
                                           film.sums.depth.empty() ? "" : " depth");
    header.seed = static_cast<int>(scene.film.seed);
    header.wavelengths = scene.film.wavelengths;
    header.max_depth = scene.film.max_depth;
    header.colorspace = colors.working_space();
    if (scene.output.png) {
        header.display = scene.output.display;
        header.view = scene.output.view;
    }
    const Metadata meta = formats::render_header_attributes(header);
    const ImageWindow window{film.region.x0, film.region.y0, scene.film.width, scene.film.height};
    // The display image is computed before anything is written, so a bad view name leaves
    // no EXR behind either.
    std::vector<float> display;
    if (scene.output.png) {
        display = rgb;
        colors.convert_display(colors.working_space(), scene.output.display, scene.output.view,
                               display.data(), npix);
    }
    // The sums, exactly: every double as the two 32-bit halves of its bits.
    std::vector<uint32_t> bits;
    UintPart sums_part;
    const FilmSums& sums = film.sums;
    const size_t per_pixel = (sums.xyz.size() + sums.albedo.size() + sums.normal.size() +
                              sums.depth.size()) / std::max<size_t>(npix, 1);
    if (!sums.xyz.empty()) {
        bits.reserve(2 * per_pixel * npix);
        for (size_t i = 0; i < npix; ++i) {
            auto put = [&](const std::vector<double>& v, size_t n) {
                for (size_t k = 0; k < n; ++k) {
                    const uint64_t b = std::bit_cast<uint64_t>(v[i * n + k]);
                    bits.push_back(static_cast<uint32_t>(b >> 32));
                    bits.push_back(static_cast<uint32_t>(b));
                }
            };
            put(sums.xyz, 3);
            put(sums.albedo, sums.albedo.empty() ? 0 : 3);
            put(sums.normal, sums.normal.empty() ? 0 : 3);
            put(sums.depth, sums.depth.empty() ? 0 : 1);
        }
        sums_part.name = "sums";
        for (size_t d = 0; d < per_pixel; ++d) {
            sums_part.channels.push_back(fmt::format("d{:02}.hi", d));
            sums_part.channels.push_back(fmt::format("d{:02}.lo", d));
        }
        sums_part.pixels = bits.data();
    }
    write_image_atomic(exr, pixels.data(), film.region.width(), film.region.height(),
                       static_cast<int>(nc), names,
                       scene.output.half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT, meta,
                       &window, bits.empty() ? nullptr : &sums_part);
    if (scene.output.png)
        write_image_atomic(film_files(scene, exr).back(), display.data(), film.region.width(),
                           film.region.height(), 3, {}, OIIO::TypeDesc::UINT8);
}

}  // namespace patina::render
