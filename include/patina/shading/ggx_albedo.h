// The directional albedo E(F0, μ) of a GGX reflection lobe with a dielectric's exact
// Fresnel, tabulated over cos θ and F0: what the layered_km shader keeps per material (its
// lobe selection, the energy coupling of its interfaces and its albedo) and what flatten
// and export use to compute the same stack's albedo. Written once for both.
//
//   E(F0, μo) = ∫ F(wo · wm) G2(wo, wi) / G1(wo) dwm  over the visible normals of wo,
//
// by stratified sampling of the visible normals (Heitz 2014, 2018: the estimator of E is
// the mean of F G2 / G1), F the Fresnel reflectance of the index η whose normal reflectance
// is F0 (Born & Wolf §1.5.2). Header-only and free of the renderer: plugins include it.
#pragma once

#include <patina/shading/fresnel.h>
#include <patina/shading/frame.h>
#include <patina/shading/microfacet.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace patina::shading {

/// Nodes of the tables over cos θ in [0, 1] and over F0 in [0, 1].
inline constexpr int kAlbedoNodes = 32;
inline constexpr int kF0Nodes = 24;
/// The F0 rows are uniform in x = √F0 over [kF0MinSqrt, kF0MaxSqrt]: E(F0, μ) is smooth in
/// x there, but jumps near F0 = 0 at grazing angles (any index > 1 reflects grazing light);
/// below kF0MinSqrt E is scaled down linearly in x to 0 at F0 = 0.
inline constexpr float kF0MinSqrt = 0.05f;
inline constexpr float kF0MaxSqrt = 0.99f;

/// 8-point Gauss-Legendre nodes and weights over μ in [0, 1], and the weights 2 μ w of the
/// cosine-weighted mean over the hemisphere (ḡ = 2 ∫ g(μ) μ dμ = Σ kGaussMeanWeight g(μ)).
inline constexpr int kGaussNodes = 8;
inline constexpr float kGaussMu[kGaussNodes] = {0.0198550718f, 0.1016667613f, 0.2372337950f,
                                                0.4082826788f, 0.5917173212f, 0.7627662050f,
                                                0.8983332387f, 0.9801449282f};
inline constexpr float kGaussWeight[kGaussNodes] = {0.0506142681f, 0.1111905172f, 0.1568533229f,
                                                    0.1813418917f, 0.1813418917f, 0.1568533229f,
                                                    0.1111905172f, 0.0506142681f};
inline constexpr float kGaussMeanWeight[kGaussNodes] = {
    2.0f * kGaussMu[0] * kGaussWeight[0], 2.0f * kGaussMu[1] * kGaussWeight[1],
    2.0f * kGaussMu[2] * kGaussWeight[2], 2.0f * kGaussMu[3] * kGaussWeight[3],
    2.0f * kGaussMu[4] * kGaussWeight[4], 2.0f * kGaussMu[5] * kGaussWeight[5],
    2.0f * kGaussMu[6] * kGaussWeight[6], 2.0f * kGaussMu[7] * kGaussWeight[7]};

/// The relative index whose normal-incidence Fresnel reflectance is F0 (Born & Wolf §1.5.2
/// inverted: η = (1 + √F0) / (1 - √F0)); 1 for F0 = 0, capped for F0 -> 1.
inline float eta_of_f0(float f0)
{
    const float s = std::sqrt(std::clamp(f0, 0.0f, 0.99f));
    return (1.0f + s) / (1.0f - s);
}

/// Dielectric Fresnel reflectance for the index of eta_of_f0 (exactly 0 when F0 = 0).
inline float dielectric_fresnel(float cos_theta, float f0, float eta)
{
    if (!(f0 > 0.0f))
        return 0.0f;  // index-matched: no reflection at any angle
    return fresnel_dielectric(cos_theta, eta);
}

/// E(F0, μ) of `distribution` into `albedo` (row q: F0 = x², x = kF0MinSqrt + (kF0MaxSqrt −
/// kF0MinSqrt) q / (kF0Nodes − 1); column i: μ = i / (kAlbedoNodes − 1), at least 1e−3),
/// and the row F = 1 into `albedo_one`; 32 × 32 strata per node.
inline void tabulate_ggx_albedo(const TrowbridgeReitz& distribution,
                                std::array<float, kF0Nodes * kAlbedoNodes>& albedo,
                                std::array<float, kAlbedoNodes>& albedo_one)
{
    constexpr int kStrata = 32;
    std::array<float, kF0Nodes> f0, eta;
    for (int q = 0; q < kF0Nodes; ++q) {
        const float x = kF0MinSqrt + (kF0MaxSqrt - kF0MinSqrt) * q / (kF0Nodes - 1);
        f0[q] = x * x;
        eta[q] = eta_of_f0(f0[q]);
    }
    for (int node = 0; node < kAlbedoNodes; ++node) {
        const float mu = std::max(1e-3f, static_cast<float>(node) / (kAlbedoNodes - 1));
        const Vec3 wo(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
        std::array<double, kF0Nodes> e{};
        double one = 0.0;
        for (int i = 0; i < kStrata; ++i)
            for (int j = 0; j < kStrata; ++j) {
                const Vec2 u((i + 0.5f) / kStrata, (j + 0.5f) / kStrata);
                const Vec3 wm = distribution.sample_wm(wo, u);
                const Vec3 wi = reflect(wo, wm);
                if (wi.z <= 0.0f)
                    continue;
                const float w = distribution.g(wo, wi) / distribution.g1(wo);
                const float c = std::clamp(dot(wo, wm), 0.0f, 1.0f);
                one += w;
                for (int q = 0; q < kF0Nodes; ++q)
                    e[q] += w * dielectric_fresnel(c, f0[q], eta[q]);
            }
        constexpr double kInvCount = 1.0 / (kStrata * kStrata);
        albedo_one[node] = static_cast<float>(one * kInvCount);
        for (int q = 0; q < kF0Nodes; ++q)
            albedo[q * kAlbedoNodes + node] = static_cast<float>(e[q] * kInvCount);
    }
}

/// Linear interpolation in a kAlbedoNodes table over μ in [0, 1].
inline float albedo_at(const std::array<float, kAlbedoNodes>& table, float mu)
{
    const float x = std::clamp(mu, 0.0f, 1.0f) * (kAlbedoNodes - 1);
    const int i = std::min(static_cast<int>(x), kAlbedoNodes - 2);
    const float t = x - static_cast<float>(i);
    return table[i] + t * (table[i + 1] - table[i]);
}

/// The table of tabulate_ggx_albedo at (F0, μ): bilinear in (√F0, μ), scaled to 0 at F0 = 0.
inline float albedo_at(const std::array<float, kF0Nodes * kAlbedoNodes>& albedo, float f0,
                       float mu)
{
    const float x = std::clamp(mu, 0.0f, 1.0f) * (kAlbedoNodes - 1);
    const int i = std::min(static_cast<int>(x), kAlbedoNodes - 2);
    const float t = x - static_cast<float>(i);
    if (!(f0 > 0.0f))
        return 0.0f;
    const float sqrt_f0 = std::sqrt(std::min(f0, 1.0f));
    const float y = std::clamp((sqrt_f0 - kF0MinSqrt) / (kF0MaxSqrt - kF0MinSqrt), 0.0f, 1.0f) *
                    (kF0Nodes - 1);
    const int q = std::min(static_cast<int>(y), kF0Nodes - 2);
    const float s = y - static_cast<float>(q);
    const float* row0 = &albedo[q * kAlbedoNodes];
    const float* row1 = row0 + kAlbedoNodes;
    const float e0 = row0[i] + t * (row0[i + 1] - row0[i]);
    const float e1 = row1[i] + t * (row1[i + 1] - row1[i]);
    const float e = e0 + s * (e1 - e0);
    return sqrt_f0 < kF0MinSqrt ? e * sqrt_f0 / kF0MinSqrt : e;
}

}  // namespace patina::shading
