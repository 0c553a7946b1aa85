// The coat's lobe and its directional albedo table (see coat.h).
#include "coat.h"

#include <algorithm>
#include <cmath>

namespace patina::spectral_km {

using namespace patina::shading;

Coat::Coat(float weight, float roughness, float ior)
    : weight_(weight), ior_(ior)
{
    const float alpha = std::max(MicrofacetWidths::roughness_to_alpha(roughness), 1e-4f);
    ggx_ = TrowbridgeReitz(alpha, alpha);

    // E(μ) by stratified visible-normal sampling: the estimator F G2 / G1(wo) has no
    // variance from D, so 48 x 48 strata give E to about 1e-4 (Heitz 2018, §4)
    constexpr int kStrata = 48;
    for (int k = 0; k < kNodes; ++k) {
        const float mu = std::max(static_cast<float>(k) / (kNodes - 1), 1e-3f);
        const Vec3 wo(std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu);
        double sum = 0.0;
        for (int i = 0; i < kStrata; ++i)
            for (int j = 0; j < kStrata; ++j) {
                const Vec2 u((i + 0.5f) / kStrata, (j + 0.5f) / kStrata);
                const Vec3 m = ggx_.sample_wm(wo, u);
                const Vec3 wi = reflect(wo, m);
                if (wi.z <= 0.0f)
                    continue;
                sum += fresnel_dielectric(dot(wo, m), ior_) * ggx_.g(wo, wi) / ggx_.g1(wo);
            }
        e_[k] = static_cast<float>(sum / (kStrata * kStrata));
    }
    // E_avg = 2 ∫ E μ dμ over the piecewise-linear E: per interval [a, b] of width h,
    // ∫ E μ = h (E_a (2a + b) + E_b (a + 2b)) / 6
    double integral = 0.0;
    const double h = 1.0 / (kNodes - 1);
    for (int k = 0; k + 1 < kNodes; ++k) {
        const double a = k * h, b = (k + 1) * h;
        integral += h * (e_[k] * (2.0 * a + b) + e_[k + 1] * (a + 2.0 * b)) / 6.0;
    }
    average_ = static_cast<float>(2.0 * integral);
}

float Coat::albedo(float cos_theta) const
{
    const float x = std::clamp(std::abs(cos_theta), 0.0f, 1.0f) * (kNodes - 1);
    const int k = std::min(static_cast<int>(x), kNodes - 2);
    const float t = x - static_cast<float>(k);
    return e_[k] + t * (e_[k + 1] - e_[k]);
}

float Coat::eval(Vec3 wo, Vec3 wi) const
{
    if (wo.z <= 0.0f || wi.z <= 0.0f)
        return 0.0f;
    Vec3 m = wo + wi;
    if (length_squared(m) == 0.0f)
        return 0.0f;
    m = normalize(m);
    // Microfacet reflection: Walter et al. 2007 Eq. 20
    const float f = fresnel_dielectric(dot(wo, m), ior_) * ggx_.d(m) * ggx_.g(wo, wi) /
                    (4.0f * wo.z * wi.z);
    return is_finite(f) ? f : 0.0f;
}

float Coat::pdf(Vec3 wo, Vec3 wi) const
{
    if (wo.z <= 0.0f || wi.z <= 0.0f)
        return 0.0f;
    Vec3 m = wo + wi;
    if (length_squared(m) == 0.0f)
        return 0.0f;
    m = normalize(m);
    const float wo_m = dot(wo, m);
    if (wo_m <= 0.0f)
        return 0.0f;
    // Visible normals mapped through the reflection Jacobian 1 / (4 |wo·m|)
    const float p = ggx_.pdf(wo, m) / (4.0f * wo_m);
    return is_finite(p) ? p : 0.0f;
}

bool Coat::sample(Vec3 wo, Vec2 u, Vec3* wi) const
{
    if (wo.z <= 0.0f)
        return false;
    const Vec3 m = ggx_.sample_wm(wo, u);
    *wi = reflect(wo, m);
    return wi->z > 0.0f;
}

float Coat::base_factor(float cos_o, float cos_i) const
{
    if (weight_ <= 0.0f)
        return 1.0f;
    const float denom = 1.0f - weight_ * average_;
    return (1.0f - weight_ * albedo(cos_o)) * (1.0f - weight_ * albedo(cos_i)) / denom;
}

}  // namespace patina::spectral_km
