// patina/volume/schlick_phase.h — Schlick's phase function and its two-lobe mixture.
//
// Dorsey et al. 1999 §5.1 scatter light in stone with "the two-lobed Schlick-approximation
// of the empirical Henyey-Greenstein phase-function": a weighted sum of a forward and a
// backward Schlick lobe (Blasi, Le Saëc, Schlick 1993). One lobe, for cos θ = dot(wo, wi)
// with both directions pointing away from the scattering point (phase.h's convention):
//
//     p_k(cos θ) = (1 − k²) / (4π (1 + k cos θ)²),      k in (−1, 1)
//
// k > 0 scatters forward (peak at wi = −wo), k < 0 backward, k = 0 is isotropic. Each lobe
// integrates to 1 over the sphere and inverts in closed form, so sampling is exact:
//
//     P(C <= c) = (1 − k²)/(2k) · (1/(1 − k) − 1/(1 + k c))          (the cdf)
//     c(u)      = (2u − 1 − k) / (1 + k − 2k u)                      (its inverse)
//
// The two-lobe function p = w p_kf + (1 − w) p_kb picks the forward lobe with probability
// w, samples it, and returns the mixture density, so pdf == p exactly.
#pragma once

#include <patina/shading/frame.h>
#include <patina/shading/vec.h>

#include <algorithm>
#include <cmath>

namespace patina::volume {

using shading::Vec2;
using shading::Vec3;

/// One Schlick lobe at cos θ = dot(wo, wi): Blasi, Le Saëc, Schlick 1993, with cos θ
/// measured between the outgoing directions (hence + k cos θ). Per steradian.
inline double schlick_phase(double cos_theta, double k)
{
    const double c = std::clamp(cos_theta, -1.0, 1.0);
    const double d = 1.0 + k * c;
    if (!(d > 0.0))
        return 0.0;
    return (1.0 - k * k) / (4.0 * 3.14159265358979323846 * d * d);
}

/// P(dot(wo, wi) <= cos_theta) for one Schlick lobe: 2π ∫_{−1}^{c} p_k(x) dx.
inline double schlick_cdf(double cos_theta, double k)
{
    const double c = std::clamp(cos_theta, -1.0, 1.0);
    if (k == 0.0)
        return 0.5 * (1.0 + c);
    return (1.0 - k * k) / (2.0 * k) * (1.0 / (1.0 - k) - 1.0 / (1.0 + k * c));
}

/// The inverse of schlick_cdf at u in [0, 1]: cos θ = (2u − 1 − k)/(1 + k − 2ku), which has
/// no cancellation as k → 0 (it becomes 2u − 1).
inline double sample_schlick_cos_theta(double k, double u)
{
    const double uc = std::clamp(u, 0.0, 1.0);
    return std::clamp((2.0 * uc - 1.0 - k) / (1.0 + k - 2.0 * k * uc), -1.0, 1.0);
}

/// The two-lobe Schlick phase function of Dorsey et al. 1999 §5.1.
struct TwoLobeSchlick {
    double k_forward = 0.6;  ///< forward lobe, in [0, 1)
    double k_backward = -0.3; ///< backward lobe, in (−1, 0]
    double w_forward = 0.8;   ///< weight of the forward lobe, in [0, 1]

    /// p(cos θ), cos θ = dot(wo, wi).
    double eval(double cos_theta) const
    {
        return w_forward * schlick_phase(cos_theta, k_forward) +
               (1.0 - w_forward) * schlick_phase(cos_theta, k_backward);
    }
    double cdf(double cos_theta) const
    {
        return w_forward * schlick_cdf(cos_theta, k_forward) +
               (1.0 - w_forward) * schlick_cdf(cos_theta, k_backward);
    }

    /// Samples wi about the unit direction wo from u in [0, 1)² and writes p(wo, wi) (the
    /// sampling density) to *pdf. u.x chooses the lobe and, rescaled, its cos θ.
    Vec3 sample(Vec3 wo, Vec2 u, float* pdf) const
    {
        // Lobe choice by its weight; the remainder of u.x stays uniform for the lobe
        double ux = std::clamp(static_cast<double>(u.x), 0.0, 1.0);
        double k = k_forward;
        if (ux < w_forward) {
            ux = w_forward > 0.0 ? ux / w_forward : 0.0;
        } else {
            k = k_backward;
            ux = w_forward < 1.0 ? (ux - w_forward) / (1.0 - w_forward) : 0.0;
        }
        const float cos_theta = static_cast<float>(sample_schlick_cos_theta(k, ux));
        const float sin_theta = shading::safe_sqrt(1.0f - cos_theta * cos_theta);
        const float phi = shading::kTwoPi * u.y;
        const shading::Frame frame = shading::Frame::from_z(wo);
        const Vec3 wi = shading::normalize(
            frame.from_local(shading::spherical_direction(sin_theta, cos_theta, phi)));
        if (pdf)
            *pdf = static_cast<float>(eval(dot(wo, wi)));
        return wi;
    }
};

} // namespace patina::volume
