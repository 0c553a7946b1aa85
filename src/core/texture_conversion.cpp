#include "core/texture_conversion.h"

#include "core/image_io.h"

#include <fmt/format.h>

#include <cstdlib>
#include <stdexcept>
#include <unistd.h>

namespace patina {

namespace fs = std::filesystem;

fs::path texture_cache_dir()
{
    if (const char* dir = std::getenv("PATINA_TEXTURE_CACHE"); dir && *dir)
        return dir;
    if (const char* xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg)
        return fs::path(xdg) / "patina" / "textures";
    if (const char* home = std::getenv("HOME"); home && *home)
        return fs::path(home) / ".cache" / "patina" / "textures";
    return fs::temp_directory_path() / fmt::format("patina-textures-{}", getuid());
}

namespace {

    // FNV-1a, 64 bits: a stable name for the cache entry (not a security boundary).
    uint64_t fnv1a(std::string_view text)
    {
        uint64_t h = 0xcbf29ce484222325ULL;
        for (unsigned char c : text) {
            h ^= c;
            h *= 0x100000001b3ULL;
        }
        return h;
    }

}  // namespace

fs::path converted_texture(const fs::path& file, std::string_view colorspace,
                           const ColorManager& colors)
{
    std::error_code ec;
    const fs::path source = fs::weakly_canonical(file, ec);
    const auto size = fs::file_size(source, ec);
    const auto mtime = fs::last_write_time(source, ec).time_since_epoch().count();
    const std::string key = fmt::format("{}|{}|{}|{}|{}|{}", source.string(), size, mtime,
                                        colorspace, colors.working_space(),
                                        colors.config_path().string());
    const fs::path dir = texture_cache_dir();
    const fs::path cached =
        dir / fmt::format("{}.{:016x}.exr", source.stem().string(), fnv1a(key));
    if (fs::exists(cached, ec))
        return cached;
    fs::create_directories(dir, ec);
    if (ec)
        throw std::runtime_error(fmt::format("texture '{}': cannot create the texture cache '{}': {}",
                                             file.string(), dir.string(), ec.message()));

    ImageData image = read_image(file);
    const ColorConversion to_working = colors.conversion(colorspace, colors.working_space());
    const size_t npix = static_cast<size_t>(image.width) * image.height;
    const size_t nc = static_cast<size_t>(image.channels);
    std::vector<float> rgb(npix * 3);
    for (size_t i = 0; i < npix; ++i)
        for (size_t k = 0; k < 3; ++k)
            rgb[i * 3 + k] = image.pixels[i * nc + (nc >= 3 ? k : 0)];
    to_working.apply(rgb.data(), npix);
    // Back into the colour channels only: RGB, or the grey channel of a map with fewer
    // than three (whose second channel may be a baked map's coverage, which stays as is).
    const size_t colour = nc >= 3 ? 3 : 1;
    for (size_t i = 0; i < npix; ++i)
        for (size_t k = 0; k < colour; ++k)
            image.pixels[i * nc + k] = rgb[i * 3 + k];
    TextureOptions opt;
    opt.format = OIIO::TypeDesc::FLOAT;  // half would round converted 8-bit values by ~5e-4
    opt.outside_the_run = true;           // read back by its name below, in this run
    opt.metadata = {{"patina:source", source.string()},
                    {"patina:source_colorspace", std::string(colorspace)},
                    {"oiio:ColorSpace", colors.working_space()}};
    make_texture_atomic(cached, image.pixels.data(), image.width, image.height, image.channels,
                        image.channel_names, opt);
    return cached;
}

}  // namespace patina
