#include "texgen/export/presets.h"

#include "formats/texture_stack/texture_stack.h"

#include <fmt/format.h>

#include <stdexcept>

namespace patina::texgen {

namespace {

    const FlatMap& map_of(const FlattenedStack& flat, const std::string& name)
    {
        for (const FlatMap& m : flat.maps)
            if (m.name == name)
                return m;
        throw std::logic_error("flatten made no map '" + name + "'");
    }

    /// New texels of `channels` channels, each filled by `texel(t, out)`.
    template <class F>
    std::vector<float> build(size_t texels, int channels, F&& texel)
    {
        std::vector<float> out(texels * channels);
        for (size_t t = 0; t < texels; ++t)
            texel(t, &out[t * channels]);
        return out;
    }

}  // namespace

const std::vector<std::string>& preset_names()
{
    static const std::vector<std::string> names = {"gltf", "unreal", "unity-hdrp", "exr"};
    return names;
}

bool preset_writes_textures(const std::string& preset)
{
    return preset != "gltf";
}

void check_preset(const std::string& preset)
{
    for (const std::string& p : preset_names())
        if (p == preset)
            return;
    std::string known;
    for (const std::string& p : preset_names())
        known += (known.empty() ? "" : ", ") + p;
    throw std::runtime_error(fmt::format("--preset '{}': expected one of {}", preset, known));
}

std::vector<PresetMap> preset_maps(const std::string& preset, const FlattenedStack& flat,
                                   size_t tile, double height_range_um,
                                   const ColorManager& colors)
{
    check_preset(preset);
    const size_t texels = static_cast<size_t>(flat.width) * flat.height;
    const std::vector<float>& base = map_of(flat, formats::kGltfBaseColorMap).tiles[tile];
    const std::vector<float>& mr = map_of(flat, formats::kGltfMetallicRoughnessMap).tiles[tile];
    const std::vector<float>& coat = map_of(flat, formats::kGltfClearcoatMap).tiles[tile];
    const std::vector<float>& normal = map_of(flat, formats::kNormalMap).tiles[tile];
    const std::vector<float>& height = map_of(flat, formats::kHeightMap).tiles[tile];
    // flatten's packings: metallicRoughness R occlusion, G roughness, B metallic; clearcoat
    // R weight, G roughness; normal OpenGL (+Y = +v, green up), n * 0.5 + 0.5.
    auto roughness = [&](size_t t) { return mr[t * 3 + 1]; };
    auto metallic = [&](size_t t) { return mr[t * 3 + 2]; };
    auto occlusion = [&](size_t t) { return mr[t * 3 + 0]; };

    auto srgb_base = [&] {
        std::vector<float> v = base;
        colors.convert("lin_rec709", "srgb_texture", v.data(), texels);
        return v;
    };
    auto height01 = [&] {
        const double scale = height_range_um > 0.0 ? 1.0 / height_range_um : 0.0;
        return build(texels, 1, [&](size_t t, float* o) {
            o[0] = static_cast<float>(height[t] * scale);
        });
    };
    auto directx_normal = [&] {
        return build(texels, 3, [&](size_t t, float* o) {
            o[0] = normal[t * 3];
            o[1] = 1.0f - normal[t * 3 + 1];  // DirectX: green down
            o[2] = normal[t * 3 + 2];
        });
    };

    std::vector<PresetMap> maps;
    if (preset == "gltf") {
        maps.push_back({"base_color", {"R", "G", "B"}, srgb_base(), true, 8});
        maps.push_back({"metallic_roughness", {"R", "G", "B"}, mr, false, 8});
        maps.push_back({"normal", {"R", "G", "B"}, normal, false, 8});
        // A tile with no coat anywhere (bare metal, a faded page) has no clearcoat map, so
        // that its material carries no KHR_materials_clearcoat that does nothing.
        bool has_coat = false;
        for (size_t t = 0; t < texels && !has_coat; ++t)
            has_coat = coat[t * 3] > 0.0f;
        if (has_coat)
            maps.push_back({kGltfPresetCoat, {"R", "G", "B"}, coat, false, 8});
    } else if (preset == "unreal") {
        maps.push_back({"BaseColor", {"R", "G", "B"}, srgb_base(), true, 8});
        // ORM: R ambient occlusion, G roughness, B metallic (Unreal's packed mask).
        maps.push_back({"OcclusionRoughnessMetallic", {"R", "G", "B"},
                        build(texels, 3, [&](size_t t, float* o) {
                            o[0] = occlusion(t);
                            o[1] = roughness(t);
                            o[2] = metallic(t);
                        }),
                        false, 8});
        maps.push_back({"Normal", {"R", "G", "B"}, directx_normal(), false, 8});
        maps.push_back({"ClearCoat", {"R", "G", "B"},
                        build(texels, 3, [&](size_t t, float* o) {
                            o[0] = coat[t * 3];      // Clear Coat
                            o[1] = coat[t * 3 + 1];  // Clear Coat Roughness
                            o[2] = 0.0f;
                        }),
                        false, 8});
        maps.push_back({"Height", {"R"}, height01(), false, 16});
    } else if (preset == "unity-hdrp") {
        maps.push_back({"BaseMap", {"R", "G", "B"}, srgb_base(), true, 8});
        // HDRP Lit mask map: R metallic, G occlusion, B detail mask, A smoothness.
        maps.push_back({"MaskMap", {"R", "G", "B", "A"},
                        build(texels, 4, [&](size_t t, float* o) {
                            o[0] = metallic(t);
                            o[1] = occlusion(t);
                            o[2] = 1.0f;  // detail mask: details everywhere
                            o[3] = 1.0f - roughness(t);
                        }),
                        false, 8});
        maps.push_back({"Normal", {"R", "G", "B"}, normal, false, 8});  // OpenGL, as Unity
        maps.push_back({"CoatMask", {"R"},
                        build(texels, 1, [&](size_t t, float* o) { o[0] = coat[t * 3]; }),
                        false, 8});
        maps.push_back({"Height", {"R"}, height01(), false, 16});
    } else {  // "exr"
        // Standard-Surface-like inputs (Autodesk Standard Surface names), linear floats.
        maps.push_back({"base_color", {"R", "G", "B"}, base, false, 32});
        maps.push_back({"metalness", {"Y"},
                        build(texels, 1, [&](size_t t, float* o) { o[0] = metallic(t); }),
                        false, 32});
        maps.push_back({"specular_roughness", {"Y"},
                        build(texels, 1, [&](size_t t, float* o) { o[0] = roughness(t); }),
                        false, 32});
        maps.push_back({"coat", {"Y"},
                        build(texels, 1, [&](size_t t, float* o) { o[0] = coat[t * 3]; }),
                        false, 32});
        maps.push_back({"coat_roughness", {"Y"},
                        build(texels, 1, [&](size_t t, float* o) { o[0] = coat[t * 3 + 1]; }),
                        false, 32});
        maps.push_back({"normal", {"R", "G", "B"}, normal, false, 32});
        maps.push_back({"displacement", {"Y"},
                        build(texels, 1, [&](size_t t, float* o) {
                            o[0] = static_cast<float>(height[t] * 1e-6);  // metres
                        }),
                        false, 32});
    }
    return maps;
}

}  // namespace patina::texgen
