// patina/shading/fresnel.h — Fresnel reflectance of smooth dielectric and conductor interfaces.
//
// Both functions return the reflectance of unpolarised light, the mean of the s- and
// p-polarised reflectances |r⊥|² and |r∥|², at one wavelength. They are exact (no
// Schlick approximation) and never return NaN.
//
// fresnel_dielectric(cos_theta_i, eta)
//     eta = η_t / η_i, the index below the interface over the index above it (for a glass
//     surface in air, 1.5). cos_theta_i is the cosine between the incident direction and
//     the normal; a negative cosine means the direction arrives from below, and the
//     interface is flipped (η → 1/η). Returns 1 on total internal reflection.
//
// fresnel_conductor(cos_theta_i, eta, k)
//     the metal's complex index relative to the medium above, η + ik (copper in air at
//     550 nm: 1.02 + 2.58i). Light always arrives from the dielectric side; the sign of
//     cos_theta_i is ignored. k = 0 gives fresnel_dielectric. Computed in double precision
//     with complex arithmetic, which stays accurate for n → 0 (a perfect reflector) and for
//     large k.
//
// fresnel_conductor_real(cos_theta_i, eta, k)
//     the same reflectance to float rounding in real double arithmetic (no complex
//     division or square root; faster where it is called per wavelength and lobe).
//
// fresnel_dielectric_normal / fresnel_conductor_normal are the closed forms at normal
// incidence, ((η−1)² + k²) / ((η+1)² + k²), for tests and albedo estimates.
#pragma once

#include <patina/shading/vec.h>

#include <complex>

namespace patina::shading {

/// Unpolarised Fresnel reflectance of a smooth dielectric interface with relative index eta.
inline float fresnel_dielectric(float cos_theta_i, float eta)
{
    cos_theta_i = std::clamp(cos_theta_i, -1.0f, 1.0f);
    // Flip the interface orientation when the light arrives from below
    if (cos_theta_i < 0.0f) {
        eta = 1.0f / eta;
        cos_theta_i = -cos_theta_i;
    }
    // Snell's law for cos θt; total internal reflection when sin θt >= 1: pbrt-v4 §9.3
    const float sin2_theta_i = 1.0f - sqr(cos_theta_i);
    const float sin2_theta_t = sin2_theta_i / sqr(eta);
    if (sin2_theta_t >= 1.0f)
        return 1.0f;
    const float cos_theta_t = safe_sqrt(1.0f - sin2_theta_t);
    // Fresnel equations for r∥ and r⊥: Born & Wolf, Principles of Optics, 7th ed., §1.5.2
    // ("Fresnel formulae"), written with relative index η as in pbrt-v4 §9.3
    const float r_parl = (eta * cos_theta_i - cos_theta_t) / (eta * cos_theta_i + cos_theta_t);
    const float r_perp = (cos_theta_i - eta * cos_theta_t) / (cos_theta_i + eta * cos_theta_t);
    return 0.5f * (sqr(r_parl) + sqr(r_perp));
}

/// Fresnel reflectance of a dielectric at normal incidence: ((η−1)/(η+1))².
inline float fresnel_dielectric_normal(float eta)
{
    // Limit cos θ = 1 of the Fresnel equations: Born & Wolf, 7th ed., §1.5.2
    return sqr((eta - 1.0f) / (eta + 1.0f));
}

/// Unpolarised Fresnel reflectance of a smooth conductor with complex relative index
/// eta + i k, light arriving from the dielectric side at |cos_theta_i|.
inline float fresnel_conductor(float cos_theta_i, float eta, float k)
{
    using Complex = std::complex<double>;
    const double cos_i = std::min(1.0, std::abs(static_cast<double>(cos_theta_i)));
    const Complex n(eta, k);
    if (n == Complex(0.0, 0.0))
        return 1.0f; // infinite optical density mirrors everything
    // Complex Snell's law, cos θt = sqrt(1 − sin²θi / η²) on the principal branch:
    // pbrt-v4 §9.3 ("The Fresnel Equations for Conductors")
    const double sin2_i = 1.0 - cos_i * cos_i;
    const Complex cos_t = std::sqrt(1.0 - sin2_i / (n * n));
    // Fresnel equations with the complex index η + ik: Born & Wolf, 7th ed., §14.2
    // ("Refraction and reflection at a metal surface"); pbrt-v4 §9.3, FrComplex
    const Complex r_parl = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    const Complex r_perp = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    const double r = 0.5 * (std::norm(r_parl) + std::norm(r_perp));
    // r is in [0, 1] in exact arithmetic; 0/0 at grazing incidence on a vacuum-like metal
    if (!std::isfinite(r))
        return 1.0f;
    return static_cast<float>(std::clamp(r, 0.0, 1.0));
}

/// fresnel_conductor in real arithmetic: Born & Wolf §14.2 written with a² + b² = |η² − sin²θ|
/// (K. D. Möller, Optics, 1988; Lagarde 2013, "Memo on Fresnel equations"):
/// Rs = (t1 − t2) / (t1 + t2), Rp = Rs (t3 − t4) / (t3 + t4), R = (Rs + Rp) / 2.
inline float fresnel_conductor_real(float cos_theta_i, float eta, float k)
{
    if (eta == 0.0f && k == 0.0f)
        return 1.0f; // infinite optical density mirrors everything
    const double c = std::min(1.0, std::abs(static_cast<double>(cos_theta_i)));
    const double n = eta, kk = k;
    const double c2 = c * c, s2 = 1.0 - c2;
    const double t0 = n * n - kk * kk - s2;
    const double a2b2 = std::sqrt(t0 * t0 + 4.0 * n * n * kk * kk);
    const double a = std::sqrt(std::max(0.0, 0.5 * (a2b2 + t0)));
    const double t1 = a2b2 + c2, t2 = 2.0 * a * c;
    const double rs = (t1 - t2) / (t1 + t2);
    const double t3 = c2 * a2b2 + s2 * s2, t4 = t2 * s2;
    const double r = 0.5 * (rs + rs * (t3 - t4) / (t3 + t4));
    if (!std::isfinite(r))
        return 1.0f; // 0/0 at grazing incidence on a vacuum-like metal
    return static_cast<float>(std::clamp(r, 0.0, 1.0));
}

/// Fresnel reflectance of a conductor at normal incidence: ((η−1)² + k²) / ((η+1)² + k²).
inline float fresnel_conductor_normal(float eta, float k)
{
    // |(n − 1)/(n + 1)|² with n = η + ik: Born & Wolf, 7th ed., §14.2 (normal incidence)
    const double e = eta, kk = k;
    const double den = sqr(e + 1.0) + sqr(kk);
    return den > 0.0 ? static_cast<float>((sqr(e - 1.0) + sqr(kk)) / den) : 1.0f;
}

} // namespace patina::shading
