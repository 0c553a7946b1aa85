#include "render/film_output.h"

#include "core/image_io.h"

#include <fmt/format.h>

#include <cstdint>
#include <fstream>
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
    std::ifstream in(scene_file, std::ios::binary);
    if (!in)
        throw std::runtime_error(fmt::format("cannot read scene '{}'", scene_file.string()));
    // FNV-1a, 64 bits (Fowler, Noll, Vo): a fingerprint that tells parts of different
    // scenes apart, not a defence against anyone.
    uint64_t h = 0xcbf29ce484222325ull;
    char buffer[65536];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
        for (std::streamsize i = 0; i < in.gcount(); ++i) {
            h ^= static_cast<unsigned char>(buffer[i]);
            h *= 0x100000001b3ull;
        }
    }
    return fmt::format("{:016x}", h);
}

void write_film(const Scene& scene, const FilmResult& film, const fs::path& exr,
                const fs::path& scene_file, const ColorManager& colors)
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

    const Metadata meta = {
        {"patina:scene", fs::absolute(scene_file).string()},
        {"patina:spp", film.spp},
        {"patina:sample_begin", film.sample_begin},
        {"patina:sample_end", film.sample_begin + film.spp},
        {"patina:scene_hash", scene_hash(scene_file)},
        {"patina:seed", static_cast<int>(scene.film.seed)},
        {"patina:wavelengths", scene.film.wavelengths},
        {"patina:max_depth", scene.film.max_depth},
        {"oiio:ColorSpace", colors.working_space()},
        {"patina:colorspace", colors.working_space()},
    };
    const ImageWindow window{film.region.x0, film.region.y0, scene.film.width, scene.film.height};
    // The display image is computed before anything is written, so a bad view name leaves
    // no EXR behind either.
    std::vector<float> display;
    if (scene.output.png) {
        display = rgb;
        colors.convert_display(colors.working_space(), scene.output.display, scene.output.view,
                               display.data(), npix);
    }
    write_image_atomic(exr, pixels.data(), film.region.width(), film.region.height(),
                       static_cast<int>(nc), names,
                       scene.output.half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT, meta,
                       &window);
    if (scene.output.png)
        write_image_atomic(film_files(scene, exr).back(), display.data(), film.region.width(),
                           film.region.height(), 3, {}, OIIO::TypeDesc::UINT8);
}

}  // namespace patina::render
