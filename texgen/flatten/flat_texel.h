// One texel of a patina stack flattened into the parameters of an ordinary BRDF: the
// layered BRDF of Dorsey & Hanrahan 1996 §4 (a Kubelka-Munk diffuse term and one glossy
// lobe per interface), and its reduction to two lobes in glTF 2.0 conventions
// (metallic-roughness + KHR_materials_clearcoat) for renderers without layered shading.
//
// The model is evaluated at the band wavelengths on the optics the stack records
// (band_optics.h), as layered_km evaluates it at its wavelengths; its colours are taken to
// linear Rec.709 under D65 there. Roughness is perceptual (GGX alpha = r², as glTF and the
// plugins use it).
#pragma once

#include "texgen/flatten/band_optics.h"
#include "texgen/flatten/gltf_albedo.h"
#include "texgen/flatten/gltf_fit.h"

#include <Imath/ImathVec.h>

#include <span>
#include <vector>

namespace patina::texgen {

/// The glossy lobe of one interface (§4.3): "each interface inherits properties from the
/// material below it". Interface 0 is the top of the base, interface i the top of layer i.
struct InterfaceLobe {
    /// The material's specular reflectance times the squared KM diffuse transmittance of the
    /// layers above the interface (§4.3: "multiplied twice by diffuse transmittance of the
    /// intervening layers"), faded in over the first shading::kInterfaceFadeUm of the layer
    /// under it (patina/shading/layer_stack.h); 0 where that layer is absent or continues
    /// the layer above it (the same material: no interface between them).
    Imath::V3f specular{0.0f};
    float roughness = 0.5f;  ///< the material's roughness (constant per interface)
    /// fade T_above² as a colour (what the lobe's reflection keeps on its way out), and the
    /// material below the interface; both 0 / null where the interface is absent.
    Imath::V3f attenuation{0.0f};
    const BandMaterial* material = nullptr;
};

/// The two-lobe reduction, glTF 2.0 metallic-roughness + KHR_materials_clearcoat.
struct TwoLobe {
    Imath::V3f base_color{0.0f};  ///< glTF baseColor (linear here; encoded on output)
    float metallic = 0.0f;        ///< glTF metallic
    float roughness = 0.5f;       ///< glTF roughness (base specular lobe)
    float coat_weight = 0.0f;     ///< KHR_materials_clearcoat clearcoatFactor
    float coat_roughness = 0.5f;  ///< KHR_materials_clearcoat clearcoatRoughnessFactor
};

struct FlatTexel {
    /// KM diffuse reflectance of the stack over the base (§4.1-4.2). Over a metal base the
    /// once-through reflection by the metal, T_above² R_base, is the base interface's glossy
    /// lobe and is not counted again here (a bare metal has no diffuse part).
    Imath::V3f diffuse{0.0f};
    std::vector<InterfaceLobe> interfaces;  ///< n + 1: the base's, then each layer's top
    float height_um = 0.0f;                 ///< total thickness over the base (§4.3, last ¶)
    TwoLobe two_lobe;
};

/// Normal-incidence reflectance of glTF's clearcoat (IOR 1.5: ((1.5 - 1) / (1.5 + 1))² =
/// 0.04, KHR_materials_clearcoat): the coat weight is the exposed layer's specular over it.
inline constexpr float kClearcoatF0 = 0.04f;

/// How flatten makes the glTF material of a texel: the two-lobe reduction alone, or with
/// its base colour fitted to the texel's albedo for a target renderer (gltf_fit.h; the
/// stack's lobe albedos must be tabulated: tabulate_lobe_albedos).
struct GltfFitting {
    const GltfAlbedo* model = nullptr;  ///< null: the reduction alone
    GltfTarget target = GltfTarget::khronos;
};

/// Flatten one texel of `stack`, its layers' thickness here (µm, >= 0, bottom to top;
/// thickness_um.size() == stack.layers.size()), colours through `to_rgb`.
FlatTexel flatten_texel(const BandStack& stack, std::span<const float> thickness_um,
                        const BandsToRgb& to_rgb, const GltfFitting& fitting = {});
/// The same into `out`, whose memory a loop over texels reuses.
void flatten_texel(const BandStack& stack, std::span<const float> thickness_um,
                   const BandsToRgb& to_rgb, const GltfFitting& fitting, FlatTexel& out);

/// The directional albedo of a flattened texel's layered BRDF at the Gauss cosines of
/// patina/shading/ggx_albedo.h, as layered_km computes it (LayeredModel::albedo: each
/// interface's lobe, coupled to those above it, and the diffuse lobe under them all,
/// D&H 1996 §4.3 with the shader's energy coupling), per colour channel: the lobes' albedos
/// are the materials' (tabulate_lobe_albedos) times the interfaces' attenuation colours.
AlbedoParts texel_albedo(const FlatTexel& texel);

/// The diffuse reflectance alone at the bands (FlatTexel::diffuse before its conversion to
/// colour), over a metal base with (`keep_metal_reflection`, what a preview shows) or
/// without the metal's once-through reflection.
Bands stack_diffuse(const BandStack& stack, std::span<const float> thickness_um,
                    bool keep_metal_reflection);

/// Reduce a flattened texel to two lobes (called by flatten_texel; exposed for tests).
/// The coat is the top interface where a layer is exposed (weight = its specular luminance
/// over kClearcoatF0, at most 1; 0 where the base is bare); every lower lobe is summed
/// into the base's specular F0, read as a metal's colour over a metal base, its roughness
/// the F0-weighted mean of their GGX alphas; glTF's metallic blend
/// (base = mix(dielectric diffuse, metal F0, metallic)) then carries the diffuse albedo D
/// and that F0 M as base_color = D + M, metallic = lum(M) / (lum(M) + lum(D)), which keeps
/// the luminance of both parts exactly and mixes their hues.
TwoLobe reduce_to_two_lobes(bool metal_base, const Imath::V3f& diffuse,
                            std::span<const InterfaceLobe> interfaces, int top_interface);

/// Rec.709 luminance (the Y row of the Rec.709 → XYZ matrix, ITU-R BT.709-6).
inline float luminance(const Imath::V3f& c)
{
    return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z;
}

}  // namespace patina::texgen
