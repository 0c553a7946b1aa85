#include "texgen/flatten/flatten_stack.h"

#include "formats/texture_stack/texture_stack.h"

#include "core/image_io.h"
#include "texgen/flatten/flat_texel.h"
#include "texgen/flatten/normal_map.h"

#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <map>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

    /// Channel `channel` of one tile's map (`image`, read from `file`), resampled to width x
    /// height if needed.
    std::vector<float> read_thickness(const ImageData& image, const fs::path& file,
                                      const std::string& channel, int width, int height)
    {
        const int c = image.channel(channel);
        if (c < 0)
            throw std::runtime_error(fmt::format("thickness map '{}': no channel '{}'",
                                                 file.string(), channel));
        std::vector<float> t(static_cast<size_t>(image.width) * image.height);
        size_t bad = 0, first = 0;
        for (size_t i = 0; i < t.size(); ++i) {
            t[i] = image.pixels[i * image.channels + c];
            if (!std::isfinite(t[i]) || t[i] < 0.0f)
                if (bad++ == 0)
                    first = i;
        }
        if (bad)
            throw std::runtime_error(fmt::format(
                "thickness map '{}': texel ({}, {}) is {} ({} bad texels); thicknesses must be "
                "finite and >= 0", file.string(), first % image.width, first / image.width,
                t[first], bad));
        if (image.width == width && image.height == height)
            return t;
        // Resample with OIIO (the thickness is the linear quantity; a filtered lookup of it
        // is what a renderer would see).
        const OIIO::ImageSpec in_spec(image.width, image.height, 1, OIIO::TypeDesc::FLOAT);
        OIIO::ImageBuf in(in_spec, t.data());
        OIIO::ImageBuf out(OIIO::ImageSpec(width, height, 1, OIIO::TypeDesc::FLOAT));
        if (!OIIO::ImageBufAlgo::resize(out, in))
            throw std::runtime_error(fmt::format("thickness map '{}': cannot resample: {}",
                                                 file.string(), out.geterror()));
        std::vector<float> r(static_cast<size_t>(width) * height);
        out.get_pixels(OIIO::ROI(0, width, 0, height, 0, 1, 0, 1), OIIO::TypeDesc::FLOAT,
                       r.data());
        for (float& v : r)
            v = std::max(v, 0.0f);  // a sharp filter may ring below 0
        return r;
    }

}  // namespace

std::string flatten_colorspace(const std::string& option)
{
    if (option == "srgb")
        return "srgb_texture";
    if (option == "acescg")
        return "ACEScg";
    throw std::runtime_error(fmt::format("--color-space '{}': expected srgb or acescg", option));
}

void check_finite_maps(const FlattenedStack& flat, const fs::path& manifest, const char* command)
{
    for (const FlatMap& map : flat.maps)
        for (size_t tile = 0; tile < map.tiles.size(); ++tile)
            for (size_t i = 0; i < map.tiles[tile].size(); ++i)
                if (!std::isfinite(map.tiles[tile][i])) {
                    const size_t texel = i / map.channels.size();
                    throw std::runtime_error(fmt::format(
                        "{} of '{}': map '{}' texel ({}, {}) of tile {} channel '{}' is not "
                        "finite; nothing was written",
                        command, manifest.string(), map.name, texel % flat.width,
                        texel / flat.width, flat.udims[tile],
                        map.channels[i % map.channels.size()]));
                }
}

FlattenedStack flatten_stack(const PatinaStackFiles& stack, const ColorManager& colors,
                             const FlattenOptions& options)
{
    const size_t n = stack.layers.size();
    BandStack materials = band_stack(stack);
    const BandsToRgb to_rgb(colors);
    // The glTF maps fitted for the target renderer, when they are asked for.
    GltfFitting fitting;
    auto wanted = [&](const char* map) {
        return options.only.empty() ||
               std::find(options.only.begin(), options.only.end(), map) != options.only.end();
    };
    if (wanted(formats::kGltfBaseColorMap)) {
        tabulate_lobe_albedos(materials, to_rgb);
        fitting.model = &gltf_albedo_model();
        fitting.target = options.target;
    }

    FlattenedStack flat;
    flat.udims = stack.udims;
    // Tile size: the stack's (its maps' resolution, or the first map's own size).
    int in_w = stack.width, in_h = stack.height;
    if (in_w <= 0 || in_h <= 0) {
        const fs::path& first = n ? stack.layers[0].files[0] : fs::path();
        if (first.empty())
            throw std::runtime_error(fmt::format("patina stack '{}': maps have no resolution",
                                                 stack.manifest.string()));
        const ImageData image = read_image(first);
        in_w = image.width;
        in_h = image.height;
    }
    flat.width = options.resolution > 0 ? options.resolution : in_w;
    flat.height = options.resolution > 0
                      ? std::max(1, static_cast<int>(std::lround(
                                        static_cast<double>(options.resolution) * in_h / in_w)))
                      : in_h;
    flat.texel_size_m = options.texel_size_m > 0.0 ? options.texel_size_m
                        : stack.strip_size_m > 0.0 ? stack.strip_size_m / flat.width
                                                   : 0.0;
    if (!(flat.texel_size_m > 0.0))
        throw std::runtime_error(fmt::format(
            "patina stack '{}' was made on a mesh: pass --texel-size (metres per texel) for "
            "the normal map's slope", stack.manifest.string()));

    // The maps, in the order they are written.
    auto add = [&](std::string name, std::vector<std::string> channels, std::string units,
                   std::string description, bool is_color) {
        flat.maps.push_back({std::move(name), std::move(channels), std::move(units),
                             std::move(description), is_color, {}});
    };
    add(formats::kDiffuseAlbedoMap, {"R", "G", "B"}, "1",
        "Kubelka-Munk diffuse reflectance of the layers over the base (D&H 1996 §4.1-4.2); "
        "over a metal base without the metal's once-through reflection, which is "
        "interface 0's glossy lobe",
        true);
    for (size_t k = 0; k <= n; ++k) {
        const BandMaterial& below = k == 0 ? *materials.base : *materials.layers[k - 1];
        const std::string stem = fmt::format("interface{:02}_{}", k, formats::name_part(below.name));
        const std::string where =
            k == 0 ? fmt::format("the top of the base ({})", below.name)
                   : fmt::format("the top of layer {} ({})", k, below.name);
        add(stem + "_specular", {"R", "G", "B"}, "1",
            fmt::format("specular colour of the glossy lobe at {}, attenuated by the square of "
                        "the KM diffuse transmittance of the layers above it (D&H 1996 §4.3); "
                        "0 where that layer is absent", where),
            true);
        add(stem + "_roughness", {"roughness"}, "1",
            fmt::format("perceptual GGX roughness (alpha = r^2) of the glossy lobe at {}", where),
            false);
    }
    add(formats::kHeightMap, {"height"}, "um",
        "total thickness of the layers over the base in micrometres (D&H 1996 §4.3)", false);
    add(formats::kNormalMap, {"R", "G", "B"}, "1",
        fmt::format("tangent-space normal of the height map, OpenGL convention (+X = +u, +Y = "
                    "+v, green up), encoded n * 0.5 + 0.5; texel {} m, heights x {}",
                    flat.texel_size_m, options.normal_scale),
        false);
    add(formats::kGltfBaseColorMap, {"R", "G", "B"}, "1",
        "glTF 2.0 baseColor of the two-lobe reduction: diffuse albedo + the F0 of the "
        "lobes under the coat over a metal base", true);
    add(formats::kGltfMetallicRoughnessMap, {"R", "G", "B"}, "1",
        "glTF 2.0 metallicRoughness texture: R occlusion (1), G roughness, B metallic", false);
    add(formats::kGltfClearcoatMap, {"R", "G", "B"}, "1",
        "KHR_materials_clearcoat: R clearcoat (exposed layer's specular / 0.04), G clearcoat "
        "roughness, B unused (0)", false);

    const size_t texels = static_cast<size_t>(flat.width) * flat.height;
    for (FlatMap& map : flat.maps)
        map.tiles.resize(stack.udims.size());
    for (size_t tile = 0; tile < stack.udims.size(); ++tile) {
        // Layers reading channels of one file (thickness.exr) read it once.
        std::vector<std::vector<float>> thickness(n);
        std::map<fs::path, ImageData> images;
        for (size_t l = 0; l < n; ++l) {
            const fs::path& file = stack.layers[l].files[tile];
            auto it = images.find(file);
            if (it == images.end())
                it = images.emplace(file, read_image(file)).first;
            thickness[l] = read_thickness(it->second, file, stack.layers[l].channel, flat.width,
                                          flat.height);
        }
        for (FlatMap& map : flat.maps)
            if (options.only.empty() ||
                std::find(options.only.begin(), options.only.end(), map.name) !=
                    options.only.end() ||
                (map.name == formats::kHeightMap &&  // the normal map is made from it
                 std::find(options.only.begin(), options.only.end(), formats::kNormalMap) !=
                     options.only.end()))
                map.tiles[tile].assign(texels * map.channels.size(), 0.0f);

        tbb::parallel_for(tbb::blocked_range<size_t>(0, texels, 1024),
                          [&](const tbb::blocked_range<size_t>& range) {
            std::vector<float> d(n);
            FlatTexel f;
            for (size_t t = range.begin(); t != range.end(); ++t) {
                for (size_t l = 0; l < n; ++l)
                    d[l] = thickness[l][t];
                flatten_texel(materials, d, to_rgb, fitting, f);
                size_t m = 0;
                auto put3 = [&](const Imath::V3f& v) {
                    std::vector<float>& texels_of = flat.maps[m++].tiles[tile];
                    if (texels_of.empty())
                        return;  // a map not asked for
                    float* p = &texels_of[t * 3];
                    p[0] = v.x;
                    p[1] = v.y;
                    p[2] = v.z;
                };
                auto put1 = [&](float v) {
                    std::vector<float>& texels_of = flat.maps[m++].tiles[tile];
                    if (!texels_of.empty())
                        texels_of[t] = v;
                };
                put3(f.diffuse);
                for (const InterfaceLobe& lobe : f.interfaces) {
                    put3(lobe.specular);
                    put1(lobe.roughness);
                }
                put1(f.height_um);
                ++m;  // normal: from the whole height map below
                put3(f.two_lobe.base_color);
                put3({1.0f, f.two_lobe.roughness, f.two_lobe.metallic});
                put3({f.two_lobe.coat_weight, f.two_lobe.coat_roughness, 0.0f});
            }
        });
        const size_t height_map = 1 + 2 * (n + 1);
        if (!flat.maps[height_map + 1].tiles[tile].empty())
            flat.maps[height_map + 1].tiles[tile] =
                normal_map_from_height(flat.maps[height_map].tiles[tile], flat.width,
                                       flat.height, flat.texel_size_m * 1e6,
                                       options.normal_scale);
    }
    return flat;
}

}  // namespace patina::texgen
