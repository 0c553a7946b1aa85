// patina/shading/phase.h — the Henyey-Greenstein phase function and its exact sampling.
//
// Direction convention (pbrt-v4 §11.3, the one every Patina medium follows): both
// directions point *away* from the scattering point,
//
//     wo   towards the previous vertex of the path (the camera side; where light leaves to),
//     wi   towards the next vertex (the light side; where light arrives from),
//
// so light arriving along −wi and leaving along wo has been deflected by the angle θ_s with
// cos θ_s = dot(−wi, wo). The functions below take cos θ = dot(wo, wi) = −cos θ_s, exactly
// as pbrt-v4's HenyeyGreenstein(Dot(wo, wi), g) does, which puts +2g cos θ in the
// denominator:
//
//     p(cos θ) = 1/(4π) · (1 − g²) / (1 + g² + 2 g cos θ)^(3/2).
//
// Forward scattering (g > 0) therefore peaks at wi = −wo (cos θ = −1: light keeps going
// the way it went), backward scattering (g < 0) at wi = wo. p depends only on dot(wo, wi),
// so p(wo, wi) = p(wi, wo) exactly (reciprocity), and ∫ p dω = 1 for every g in (−1, 1).
//
//     float pdf;
//     Vec3 wi = sample_henyey_greenstein(wo, g, u, &pdf);   // pdf == p(dot(wo, wi))
//
// Sampling inverts the cumulative distribution of cos θ exactly (no rejection, no fit), so
// the returned pdf is the density of the returned direction. Allocation-free, reentrant.
#pragma once

#include <patina/shading/frame.h>
#include <patina/shading/vec.h>

namespace patina::shading {

/// Henyey-Greenstein phase function for cos θ = dot(wo, wi), both pointing away from the
/// scattering point (pbrt-v4 convention, see above); g in (−1, 1). Per steradian.
inline float henyey_greenstein(float cos_theta, float g)
{
    // p_HG = (1 − g²) / (4π (1 + g² + 2g cos θ)^{3/2}): Henyey & Greenstein 1941; pbrt-v4
    // §11.3.1 Eq. 11.12 (cos θ measured between wo and wi, hence + 2g cos θ)
    const double c = std::clamp(static_cast<double>(cos_theta), -1.0, 1.0);
    const double gd = static_cast<double>(g);
    const double denom = 1.0 + gd * gd + 2.0 * gd * c;
    if (!(denom > 0.0))
        return 0.0f;
    return static_cast<float>(0.25 / 3.14159265358979323846 * (1.0 - gd * gd) /
                              (denom * std::sqrt(denom)));
}

/// Probability that a Henyey-Greenstein sample has dot(wo, wi) <= cos_theta: the exact
/// cumulative distribution 2π ∫_{−1}^{cos θ} p(c) dc (used to check the sampling).
inline double henyey_greenstein_cdf(double cos_theta, double g)
{
    const double c = std::clamp(cos_theta, -1.0, 1.0);
    if (g == 0.0)
        return 0.5 * (1.0 + c);
    // 2π (1 − g²)/(4π) · [(1 + g² + 2gc)^{−1/2} / −g] from −1 to c, with
    // (1 + g² − 2g)^{1/2} = 1 − g
    return (1.0 - g * g) / (2.0 * g) *
           (1.0 / (1.0 - g) - 1.0 / std::sqrt(std::max(1.0 + g * g + 2.0 * g * c, 0.0)));
}

/// cos θ = dot(wo, wi) of a Henyey-Greenstein sample: the inverse of
/// henyey_greenstein_cdf at u in [0, 1] (u = 0 gives −1, u = 1 gives +1).
inline float sample_henyey_greenstein_cos_theta(float g, float u)
{
    const double gd = static_cast<double>(g);
    const double ud = std::clamp(static_cast<double>(u), 0.0, 1.0);
    // Isotropic limit: below |g| = 1e-6 the HG density differs from 1/(4π) by < 4e-6
    // relative, beneath float resolution of the pdf, while the formula below would cancel
    if (std::abs(gd) < 1e-6)
        return static_cast<float>(std::clamp(2.0 * ud - 1.0, -1.0, 1.0));
    // Inverse cdf of cos θ: pbrt-v4 §11.3.1 (SampleHenyeyGreenstein), which solves
    // henyey_greenstein_cdf(cos θ) = u; in double precision, since 1 + g² − s² cancels
    const double s = (1.0 - gd * gd) / (1.0 + gd - 2.0 * gd * ud);
    const double cos_theta = -1.0 / (2.0 * gd) * (1.0 + gd * gd - s * s);
    return static_cast<float>(std::clamp(cos_theta, -1.0, 1.0));
}

/// Samples wi for the unit direction wo with density henyey_greenstein(dot(wo, wi), g),
/// from u in [0, 1)²; writes that density to *pdf (when not null), evaluated at the returned
/// pair so that it equals henyey_greenstein(dot(wo, wi), g) bit for bit. φ about wo is 2π u.y.
inline Vec3 sample_henyey_greenstein(Vec3 wo, float g, Vec2 u, float* pdf)
{
    const float cos_theta = sample_henyey_greenstein_cos_theta(g, u.x);
    const float sin_theta = safe_sqrt(1.0f - cos_theta * cos_theta);
    const float phi = kTwoPi * u.y;
    // The sampled angle is measured from wo: build a frame about it
    const Frame frame = Frame::from_z(wo);
    const Vec3 wi = normalize(frame.from_local(spherical_direction(sin_theta, cos_theta, phi)));
    if (pdf)
        *pdf = henyey_greenstein(dot(wo, wi), g);
    return wi;
}

} // namespace patina::shading
