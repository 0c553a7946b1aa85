#include "texgen/export/source_material.h"

#include "core/image_io.h"
#include "texgen/export/png_encode.h"

#include <algorithm>
#include <filesystem>
#include <vector>

namespace patina::texgen {

int add_source_material(gltf::Document& doc, const std::string& name, const Imath::V4f& colour,
                        const MaterialTexture& texture)
{
    nlohmann::json pbr = {{"baseColorFactor", {colour.x, colour.y, colour.z, colour.w}},
                          {"metallicFactor", 0.0}};
    if (!texture.empty()) {
        const ImageData image = read_material_texture(texture);
        const int channels = std::min(image.channels, 4);
        std::vector<float> pixels(static_cast<size_t>(image.width) * image.height * channels);
        for (size_t i = 0; i < static_cast<size_t>(image.width) * image.height; ++i)
            for (int k = 0; k < channels; ++k)
                pixels[i * channels + k] = image.pixels[i * image.channels + k];
        // Written beside a .gltf under the image's own name; Assimp's "*N" of an unnamed
        // embedded image is no file name: the material's then.
        const std::string file_stem = texture.name.empty() || texture.name[0] == '*'
                                          ? name + "_base_color"
                                          : std::filesystem::path(texture.name).stem().string();
        const int png = doc.add_png(name, file_stem + ".png",
                                    encode_png(pixels.data(), image.width, image.height, channels, 8));
        pbr["baseColorTexture"] = {{"index", doc.add_texture(png, doc.add_sampler(gltf::kRepeat))}};
    }
    return doc.add("materials", {{"name", name}, {"pbrMetallicRoughness", pbr}});
}

}  // namespace patina::texgen
