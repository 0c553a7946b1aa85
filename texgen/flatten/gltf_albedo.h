// The directional albedo of glTF 2.0's metallic-roughness material with
// KHR_materials_clearcoat, as the renderers that open Patina's exports evaluate it, at the
// 8 Gauss-Legendre cosines of patina/shading/ggx_albedo.h. Two targets:
//
//  - khronos: the reference model of the glTF 2.0 specification (Appendix B) and
//    KHR_materials_clearcoat, which three.js, Babylon.js and the Khronos sample viewer
//    implement. With base colour c, metallic m, roughness r (α = r²), coat weight w and
//    coat roughness r_c, Fs(c0, h) = c0 + (1 − c0)(1 − v·h)⁵ (Schlick) and
//    S = V·D (height-correlated Smith GGX, no Fresnel: "specular_brdf"):
//      dielectric = (1 − Fs(0.04)) c / π + Fs(0.04) S      ("fresnel_mix", ior 1.5)
//      metal      = Fs(c) S                                 ("conductor_fresnel")
//      base       = (1 − m) dielectric + m metal
//      coated     = (1 − w Fc(n·v)) base + w Fc(n·v) S(r_c), Fc(x) = 0.04 + 0.96 (1 − x)⁵
//  - blender: Blender 3.4's Principled BSDF in Cycles, which Blender's glTF importer makes of
//    the material: Disney's diffuse with retro-reflection (Burley 2015, PRINCIPLED_DIFFUSE_FULL)
//    weighted by (1 − m) and never reduced by the lobes above it, a GGX specular lobe of
//    F0 0.04 (Specular 0.5) or c (metal) added on top, and a clearcoat lobe of weight
//    0.25 w (Disney's constant), also added.
//
// Integrated once per roughness node by stratified sampling of GGX's visible normals (the
// specular terms) and a midpoint rule over the hemisphere (the diffuse terms). Both are
// linear in c: A(μ) = c P(μ) + Q(μ), which is what the fit (gltf_fit.h) solves for.
#pragma once

#include <patina/shading/ggx_albedo.h>

#include <array>
#include <string>

namespace patina::texgen {

enum class GltfTarget { khronos, blender };

/// "khronos" or "blender"; throws std::runtime_error naming the option for another.
GltfTarget gltf_target(const std::string& name);
const char* gltf_target_name(GltfTarget target);

class GltfAlbedo {
public:
    /// Builds the tables (a few tens of milliseconds).
    GltfAlbedo();

    /// The albedo's terms at the Gauss cosines, split as the fit matches them: the diffuse
    /// lobe's, c Pd(μ), and the glossy lobes', c Ps(μ) + Q(μ) (c the base colour), for
    /// roughness r, metallic m, coat weight w and coat roughness rc (all in [0, 1]).
    struct Terms {
        std::array<float, shading::kGaussNodes> Pd, Ps, Q;
    };
    Terms terms(GltfTarget target, float r, float m, float w, float rc) const;
    /// The same terms as affine functions of the coat weight: X(w) = X0 + w dX.
    struct AffineTerms {
        Terms at0, per_w;
    };
    AffineTerms affine_terms(GltfTarget target, float r, float m, float rc) const;

    /// The roughness nodes (uniform in r over [kMinRoughness, 1]) and the integrals there,
    /// for tests: E1 = ∫ S cos, E5 = ∫ S (1 − v·h)⁵ cos, Kd = ∫ (1 − Fs(0.04)) cos / π,
    /// Kb = Cycles' principled diffuse albedo.
    static constexpr int kRoughnessNodes = 33;
    static constexpr float kMinRoughness = 0.03f;
    float e1(float r, int g) const { return at(e1_, r, g); }
    float e5(float r, int g) const { return at(e5_, r, g); }
    float kd(int g) const { return kd_[g]; }
    float kb(float r, int g) const { return at(kb_, r, g); }

private:
    using Table = std::array<std::array<float, shading::kGaussNodes>, kRoughnessNodes>;
    static float at(const Table& t, float r, int g);
    /// Where r falls between the roughness nodes: node k and weight s.
    static void locate(float r, int* k, float* s);
    Table e1_{}, e5_{}, eb_{}, kb_{};  ///< eb: Blender's Fresnel shape in place of (1 − v·h)⁵
    std::array<float, shading::kGaussNodes> kd_{};
};

/// The tables, built once per process (thread-safe).
const GltfAlbedo& gltf_albedo_model();

}  // namespace patina::texgen
