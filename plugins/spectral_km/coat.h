// A clear glossy coat (varnish, lacquer, glaze) over a diffuse base: a GGX reflection lobe
// with the dielectric Fresnel reflectance of the coat's index, and the energy it reflects
// taken away from the diffuse light that enters and leaves, so that the sum never creates
// energy and stays reciprocal:
//
//     f(wo, wi) = w f_s(wo, wi) + (R / π) (1 − w E(wo)) (1 − w E(wi)) / (1 − w E_avg)
//
// f_s = F(wo·m) D(m) G2(wo, wi) / (4 cos θo cos θi) (Walter et al. 2007), E(μ) the
// directional albedo of f_s (precomputed over μ = cos θ), E_avg = 2 ∫ E(μ) μ dμ. The
// diffuse part's albedo is R (1 − w E(wo)) because ∫ (1 − w E(wi)) cos θi / π dωi =
// 1 − w E_avg, so the directional albedo is w E(wo) + R (1 − w E(wo)) <= 1 for R <= 1
// (the energy-compensation form of Kelemen & Szirmay-Kalos 2001 and Kulla & Conty 2017,
// applied to the light the coat passes to the base).
#pragma once

#include <patina/shading/fresnel.h>
#include <patina/shading/frame.h>
#include <patina/shading/microfacet.h>

#include <array>

namespace patina::spectral_km {

using shading::Vec2;
using shading::Vec3;

class Coat {
public:
    Coat() = default;
    /// weight in [0, 1]; roughness r (GGX alpha = r²) > 0; ior > 1.
    Coat(float weight, float roughness, float ior);

    float weight() const { return weight_; }
    /// E(μ): the specular lobe's directional albedo, linear in μ between table nodes.
    float albedo(float cos_theta) const;
    /// E_avg = 2 ∫ E(μ) μ dμ, exact for the piecewise-linear E.
    float average_albedo() const { return average_; }

    /// f_s(wo, wi) for wo, wi above the surface (0 otherwise); unweighted.
    float eval(Vec3 wo, Vec3 wi) const;
    /// Solid-angle density of sample(wo, ·) at wi.
    float pdf(Vec3 wo, Vec3 wi) const;
    /// wi by the visible normals of wo (Heitz 2018); false below the surface.
    bool sample(Vec3 wo, Vec2 u, Vec3* wi) const;

    /// The factor that scales the diffuse base: (1 − w E(wo)) (1 − w E(wi)) / (1 − w E_avg).
    float base_factor(float cos_o, float cos_i) const;

private:
    static constexpr int kNodes = 33;  // μ = 0, 1/32, ..., 1
    float weight_ = 0.0f;
    float ior_ = 1.5f;
    shading::TrowbridgeReitz ggx_{0.1f, 0.1f};
    std::array<float, kNodes> e_{};
    float average_ = 0.0f;
};

}  // namespace patina::spectral_km
