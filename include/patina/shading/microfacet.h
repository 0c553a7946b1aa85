// patina/shading/microfacet.h — microfacet normal distributions, Smith masking-shadowing and
// the sampling of visible normals.
//
// Two distributions with the same interface, so a BSDF can be written once as a template:
//
//     TrowbridgeReitz  the Trowbridge-Reitz ("GGX") distribution, isotropic or anisotropic
//     Beckmann         the Beckmann distribution, isotropic or anisotropic
//
// Both are built from their widths (alpha_x, alpha_y) along the local x and y axes. A
// perceptual roughness r in [0, 1] maps to alpha = r² (roughness_to_alpha(); Burley 2012,
// "Physically-Based Shading at Disney", "Specular D"), which spreads the visually useful
// range of highlight sizes evenly over [0, 1].
//
// Members, for a microfacet normal wm (unit, wm.z > 0) and directions w, wo, wi (unit,
// either hemisphere; masking is symmetric in z):
//
//     d(wm)                normal distribution D(wm); ∫ D(wm) cos θm dωm = 1 over the
//                          upper hemisphere; 0 for wm.z <= 0
//     lambda(w)            Smith's auxiliary function Λ(w); +infinity at the horizon
//     g1(w)                Smith masking G1(w) = 1 / (1 + Λ(w))
//     g(wo, wi)            height-correlated masking-shadowing G2 = 1 / (1 + Λ(wo) + Λ(wi))
//     d_visible(w, wm)     distribution of normals visible from w (flipped above the
//                          surface if w.z < 0, as w' = −w):
//                          D_w(wm) = G1(w) max(0, w'·wm) D(wm) / |cos θ(w)|; integrates to 1
//     sample_wm(w, u)      a normal wm distributed by D_w' (w' = w flipped above the surface)
//     pdf(w, wm)           density of sample_wm in solid angle of wm: exactly d_visible(w, wm)
//
// Beckmann also offers sample_wm_distribution(u) with density pdf_distribution(wm) =
// D(wm) cos θm (the classic, non-visible sampling of Walter et al. 2007).
//
// A BSDF turns the normal density into a direction density with the Jacobian of the
// reflection or refraction that maps wm to wi: 1 / (4 |wo·wm|) for reflection, and
// η_i² |wi·wm| / (η_i wi·wm + η_o wo·wm)² for refraction, η_i and η_o the indices on the
// sides of wi and wo (Walter et al. 2007, Eqs. 14, 17).
//
// Everything is allocation-free and reentrant; no member returns NaN for unit inputs, and
// widths as small as 1e-7 stay finite (a width of 0 is a delta lobe: handle it in the BSDF).
//
// Sources:
//   Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction through Rough
//     Surfaces", EGSR — GGX and Beckmann D, Smith G1, sampling.
//   Heitz 2014, "Understanding the Masking-Shadowing Function in Microfacet-Based BRDFs",
//     JCGT 3(2) — anisotropic D and Λ, height-correlated G2, visible normals.
//   Heitz 2018, "Sampling the GGX Distribution of Visible Normals", JCGT 7(4).
//   Jakob 2014, "An Improved Visible Normal Sampling Routine for the Beckmann Distribution"
//     (technical note; numerically stable inversion as in Mitsuba).
#pragma once

#include <patina/shading/frame.h>
#include <patina/shading/sampling.h>
#include <patina/shading/vec.h>

#include <algorithm>
#include <limits>

namespace patina::shading {

namespace detail {

    inline constexpr double kSqrtPi = 1.77245385090551602730;
    inline constexpr double kInvSqrtPi = 0.56418958354775628695;

    /// Inverse error function on (-1, 1), to double precision; ±infinity at ±1.
    inline double erfinv(double x)
    {
        if (!(x > -1.0))
            return -std::numeric_limits<double>::infinity();
        if (!(x < 1.0))
            return std::numeric_limits<double>::infinity();
        // Starting value: Giles 2010, "Approximating the erfinv function", GPU Computing Gems,
        // single-precision polynomial (relative error < 4e-7)
        double w = -std::log((1.0 - x) * (1.0 + x));
        double p;
        if (w < 5.0) {
            w -= 2.5;
            p = 2.81022636e-08;
            p = 3.43273939e-07 + p * w;
            p = -3.5233877e-06 + p * w;
            p = -4.39150654e-06 + p * w;
            p = 0.00021858087 + p * w;
            p = -0.00125372503 + p * w;
            p = -0.00417768164 + p * w;
            p = 0.246640727 + p * w;
            p = 1.50140941 + p * w;
        } else {
            w = std::sqrt(w) - 3.0;
            p = -0.000200214257;
            p = 0.000100950558 + p * w;
            p = 0.00134934322 + p * w;
            p = -0.00367342844 + p * w;
            p = 0.00573950773 + p * w;
            p = -0.0076224613 + p * w;
            p = 0.00943887047 + p * w;
            p = 1.00167406 + p * w;
            p = 2.83297682 + p * w;
        }
        double y = p * x;
        // Two Newton steps on erf(y) = x, erf'(y) = 2/√π exp(−y²), reach double precision
        for (int i = 0; i < 2; ++i) {
            const double slope = 2.0 * kInvSqrtPi * std::exp(-y * y);
            if (!(slope > 0.0))
                break;
            y -= (std::erf(y) - x) / slope;
        }
        return y;
    }

    /// Unit normal of the microsurface with slopes (sx, sy): m ∝ (−sx, −sy, 1).
    inline Vec3 slope_to_normal(double sx, double sy)
    {
        const double inv = 1.0 / std::sqrt(sx * sx + sy * sy + 1.0);
        return Vec3(static_cast<float>(-sx * inv), static_cast<float>(-sy * inv),
                    static_cast<float>(inv));
    }

    /// D_w(wm) of any distribution with d() and g1(); w is flipped above the surface first, so
    /// only normals facing it (w'·wm > 0) are visible.
    template <typename Distribution>
    float d_visible(const Distribution& distribution, Vec3 w, Vec3 wm)
    {
        const float cos_w = std::abs(w.z);
        if (cos_w == 0.0f)
            return 0.0f;
        const float w_dot_wm = w.z < 0.0f ? -dot(w, wm) : dot(w, wm);
        if (w_dot_wm <= 0.0f)
            return 0.0f;
        return distribution.g1(w) / cos_w * distribution.d(wm) * w_dot_wm;
    }

} // namespace detail

// ---------------------------------------------------------------------------------------
// Widths shared by both distributions
// ---------------------------------------------------------------------------------------

/// The anisotropic widths (alpha_x along the tangent, alpha_y along the bitangent) that
/// GGX and Beckmann are both parametrised by.
class MicrofacetWidths {
public:
    MicrofacetWidths() = default;
    MicrofacetWidths(float alpha_x, float alpha_y) : alpha_x_(alpha_x), alpha_y_(alpha_y) {}

    /// alpha = roughness²: Burley 2012, "Physically-Based Shading at Disney", "Specular D"
    static float roughness_to_alpha(float roughness) { return roughness * roughness; }

    float alpha_x() const { return alpha_x_; }
    float alpha_y() const { return alpha_y_; }
    /// True when both widths are below `alpha_threshold`: treat the surface as smooth.
    bool effectively_smooth(float alpha_threshold) const
    {
        return std::max(alpha_x_, alpha_y_) < alpha_threshold;
    }

protected:
    float alpha_x_ = 1.0f;
    float alpha_y_ = 1.0f;
};

// ---------------------------------------------------------------------------------------
// Trowbridge-Reitz (GGX)
// ---------------------------------------------------------------------------------------

class TrowbridgeReitz : public MicrofacetWidths {
public:
    using MicrofacetWidths::MicrofacetWidths;

    /// D(wm), zero below the surface.
    float d(Vec3 wm) const
    {
        if (wm.z <= 0.0f)
            return 0.0f;
        // Anisotropic GGX, D = 1 / (π αx αy (x²/αx² + y²/αy² + z²)²), the vector form of
        // Walter et al. 2007 Eq. 33, made anisotropic as in Heitz 2014
        // ("Anisotropic distributions")
        const float e = sqr(wm.x / alpha_x_) + sqr(wm.y / alpha_y_) + sqr(wm.z);
        const float denom = kPi * alpha_x_ * alpha_y_ * e * e;
        return denom > 0.0f && is_finite(denom) ? 1.0f / denom : 0.0f;
    }

    /// Smith Λ(w).
    float lambda(Vec3 w) const
    {
        // α(φ)² tan²θ = (αx² x² + αy² y²) / z²
        const float z2 = sqr(w.z);
        const float a2_tan2 = (sqr(alpha_x_ * w.x) + sqr(alpha_y_ * w.y)) / z2;
        if (!is_finite(a2_tan2))
            return std::numeric_limits<float>::infinity();
        // GGX Λ = (−1 + sqrt(1 + α² tan²θ)) / 2: Heitz 2014 (Λ of GGX, anisotropic α(φ)); as
        // x / (2 (1 + sqrt(1 + x))) to keep precision when α tan θ is tiny
        return a2_tan2 / (2.0f * (1.0f + std::sqrt(1.0f + a2_tan2)));
    }

    /// Smith masking G1(w) = 1 / (1 + Λ(w)): Heitz 2014 ("The Smith masking function")
    float g1(Vec3 w) const { return 1.0f / (1.0f + lambda(w)); }

    /// Height-correlated masking-shadowing 1 / (1 + Λ(wo) + Λ(wi)): Heitz 2014
    /// (height-correlated form)
    float g(Vec3 wo, Vec3 wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }

    /// Visible normal density D_w(wm) = G1(w) max(0, w·wm) D(wm) / cos θ(w), with w
    /// flipped above the surface: Heitz 2014 (distribution of visible normals)
    float d_visible(Vec3 w, Vec3 wm) const { return detail::d_visible(*this, w, wm); }

    /// Solid-angle density of sample_wm(w, ·) at wm.
    float pdf(Vec3 w, Vec3 wm) const { return d_visible(w, wm); }

    /// Normal wm (wm.z > 0) distributed by the visible normals of w (flipped above the
    /// surface if w.z < 0), from uniform u in [0,1)².
    Vec3 sample_wm(Vec3 w, Vec2 u) const
    {
        // Transform w to the hemispherical configuration (unit roughness): Heitz 2018, Listing 1
        Vec3 wh = normalize(Vec3(alpha_x_ * w.x, alpha_y_ * w.y, w.z));
        if (wh.z < 0.0f)
            wh = -wh;
        // Orthonormal basis (T1, T2, wh) around the stretched direction
        const float lensq = sqr(wh.x) + sqr(wh.y);
        const Vec3 t1 =
            lensq > 0.0f ? Vec3(-wh.y, wh.x, 0.0f) / std::sqrt(lensq) : Vec3(1.0f, 0.0f, 0.0f);
        const Vec3 t2 = cross(wh, t1);
        // Uniform point on the disk, warped onto the projected visible hemisphere
        const Vec2 p = sample_uniform_disk_polar(u);
        const float s = 0.5f * (1.0f + wh.z);
        const float p1 = p.x;
        const float p2 = (1.0f - s) * safe_sqrt(1.0f - sqr(p.x)) + s * p.y;
        // Reproject onto the hemisphere, then unstretch back to the ellipsoid configuration
        const Vec3 nh = p1 * t1 + p2 * t2 + safe_sqrt(1.0f - sqr(p1) - sqr(p2)) * wh;
        return normalize(Vec3(alpha_x_ * nh.x, alpha_y_ * nh.y, std::max(1e-6f, nh.z)));
    }

};

// ---------------------------------------------------------------------------------------
// Beckmann
// ---------------------------------------------------------------------------------------

class Beckmann : public MicrofacetWidths {
public:
    using MicrofacetWidths::MicrofacetWidths;

    /// D(wm), zero below the surface.
    float d(Vec3 wm) const
    {
        if (wm.z <= 0.0f)
            return 0.0f;
        // Anisotropic Beckmann, D = exp(−(x²/αx² + y²/αy²)/z²) / (π αx αy z⁴):
        // Walter et al. 2007 Eq. 25, made anisotropic as in Heitz 2014
        // ("Anisotropic distributions")
        const double z2 = static_cast<double>(wm.z) * wm.z;
        const double e = (sqr(static_cast<double>(wm.x) / alpha_x_) +
                          sqr(static_cast<double>(wm.y) / alpha_y_)) /
                         z2;
        const double v = std::exp(-e) / (static_cast<double>(kPi) * alpha_x_ * alpha_y_ * z2 * z2);
        return std::isfinite(v) ? static_cast<float>(v) : 0.0f;
    }

    /// Smith Λ(w).
    float lambda(Vec3 w) const
    {
        // a = 1 / (α(φ) tan θ) = z / sqrt(αx² x² + αy² y²)
        const double t = std::sqrt(sqr(static_cast<double>(alpha_x_) * w.x) +
                                   sqr(static_cast<double>(alpha_y_) * w.y));
        const double z = std::abs(static_cast<double>(w.z));
        if (t == 0.0)
            return 0.0f;
        if (z == 0.0)
            return std::numeric_limits<float>::infinity();
        const double a = z / t;
        // Beckmann Λ(a) = (erf(a) − 1)/2 + exp(−a²) / (2 a √π): Walter et al. 2007 Eq. 27,
        // Heitz 2014 (Λ of Beckmann); erfc avoids cancelling 1 − erf(a) for large a
        const double l = -0.5 * std::erfc(a) + std::exp(-a * a) / (2.0 * a * detail::kSqrtPi);
        return static_cast<float>(std::max(l, 0.0));
    }

    /// Smith masking G1(w) = 1 / (1 + Λ(w)): Heitz 2014 ("The Smith masking function")
    float g1(Vec3 w) const { return 1.0f / (1.0f + lambda(w)); }

    /// Height-correlated masking-shadowing 1 / (1 + Λ(wo) + Λ(wi)): Heitz 2014
    /// (height-correlated form)
    float g(Vec3 wo, Vec3 wi) const { return 1.0f / (1.0f + lambda(wo) + lambda(wi)); }

    /// Visible normal density D_w(wm) = G1(w) max(0, w·wm) D(wm) / cos θ(w), with w
    /// flipped above the surface: Heitz 2014 (distribution of visible normals)
    float d_visible(Vec3 w, Vec3 wm) const { return detail::d_visible(*this, w, wm); }

    /// Solid-angle density of sample_wm(w, ·) at wm.
    float pdf(Vec3 w, Vec3 wm) const { return d_visible(w, wm); }

    /// Normal wm (wm.z > 0) distributed by the visible normals of w (flipped above the
    /// surface if w.z < 0), from uniform u in [0,1)².
    Vec3 sample_wm(Vec3 w, Vec2 u) const
    {
        // Stretch w to the unit-roughness configuration: Heitz & d'Eon 2014, "Importance
        // Sampling Microfacet-Based BSDFs using the Distribution of Visible Normals", EGSR
        // (stretch, sample slopes, rotate, unstretch)
        const Vec3 wf = w.z < 0.0f ? -w : w;
        Vec3 ws = normalize(Vec3(alpha_x_ * wf.x, alpha_y_ * wf.y, wf.z));
        if (length_squared(ws) == 0.0f)
            ws = Vec3(0.0f, 0.0f, 1.0f);
        const double wsx = ws.x, wsy = ws.y;
        const double sin_theta = std::sqrt(wsx * wsx + wsy * wsy);
        const double cos_phi = sin_theta > 0.0 ? wsx / sin_theta : 1.0;
        const double sin_phi = sin_theta > 0.0 ? wsy / sin_theta : 0.0;
        // Sample the slopes of visible normals for unit roughness, incidence along +x
        double sx, sy;
        sample_visible_slopes_11(ws.z, u, &sx, &sy);
        // Rotate to the azimuth of w, then unstretch the slopes
        const double rx = (cos_phi * sx - sin_phi * sy) * alpha_x_;
        const double ry = (sin_phi * sx + cos_phi * sy) * alpha_y_;
        return detail::slope_to_normal(rx, ry);
    }

    /// Normal wm distributed by D(wm) cos θm (not only the visible ones): the slopes of a
    /// Beckmann surface are Gaussian with standard deviations αx/√2, αy/√2.
    Vec3 sample_wm_distribution(Vec2 u) const
    {
        // Gaussian slope sampling, tan²θm = −α² log(1 − u): Walter et al. 2007 Eqs. 28-29,
        // anisotropic by stretching the unit-roughness slope (Heitz 2014, slope-space stretching)
        const double r = std::sqrt(-std::log1p(-static_cast<double>(u.x)));
        const double phi = static_cast<double>(kTwoPi) * u.y;
        return detail::slope_to_normal(alpha_x_ * r * std::cos(phi), alpha_y_ * r * std::sin(phi));
    }

    /// Solid-angle density of sample_wm_distribution: D(wm) cos θm.
    float pdf_distribution(Vec3 wm) const { return wm.z > 0.0f ? d(wm) * wm.z : 0.0f; }

private:
    /// Slopes (sx, sy) of visible normals of the unit-roughness Beckmann surface seen from
    /// the direction with cos θ = cos_theta_i and φ = 0.
    static void sample_visible_slopes_11(double cos_theta_i, Vec2 u, double* sx, double* sy)
    {
        const double ux = std::clamp(static_cast<double>(u.x), 1e-9, 1.0 - 1e-9);
        const double uy = std::clamp(static_cast<double>(u.y), 1e-9, 1.0 - 1e-9);
        // Normal incidence: every normal is visible in proportion to cos θm, the Gaussian slopes
        if (cos_theta_i > 0.9999999) {
            const double r = std::sqrt(-std::log1p(-ux));
            const double phi = 2.0 * static_cast<double>(kPi) * uy;
            *sx = r * std::cos(phi);
            *sy = r * std::sin(phi);
            return;
        }
        const double sin_theta_i = std::sqrt(std::max(0.0, 1.0 - cos_theta_i * cos_theta_i));
        const double tan_theta_i = sin_theta_i / cos_theta_i;
        const double cot_theta_i = cos_theta_i / sin_theta_i;
        // Invert the cdf of the x slope, (1 + erf(x) + tanθ exp(−x²)/√π) / (1 + erf(cotθ) +
        // tanθ exp(−cot²θ)/√π), by Newton steps in the erf domain b = erf(x), safeguarded by
        // bisection on [−1, erf(cotθ)]: Jakob 2014, as implemented in Mitsuba
        double lo = -1.0, hi = std::erf(cot_theta_i);
        const double theta_i = std::acos(std::clamp(cos_theta_i, -1.0, 1.0));
        // Initial guess from a fit of the inverse cdf (Jakob 2014)
        const double fit = 1.0 + theta_i * (-0.876 + theta_i * (0.4265 - 0.0594 * theta_i));
        double b = hi - (1.0 + hi) * std::pow(1.0 - ux, fit);
        const double normalization =
            1.0 / (1.0 + hi + detail::kInvSqrtPi * tan_theta_i * std::exp(-sqr(cot_theta_i)));
        for (int it = 0; it < 64; ++it) {
            if (!(b >= lo && b <= hi))
                b = 0.5 * (lo + hi);
            const double x = detail::erfinv(b);
            const double cdf =
                normalization * (1.0 + b + detail::kInvSqrtPi * tan_theta_i * std::exp(-x * x));
            const double value = cdf - ux;
            const double derivative = normalization * (1.0 - x * tan_theta_i);
            if (std::abs(value) < 1e-10)
                break;
            if (value > 0.0)
                hi = b;
            else
                lo = b;
            b -= value / derivative;
        }
        *sx = detail::erfinv(b);
        // The y slope is independent of the incidence: a Gaussian
        *sy = detail::erfinv(2.0 * uy - 1.0);
        if (!std::isfinite(*sx))
            *sx = 0.0;
        if (!std::isfinite(*sy))
            *sy = 0.0;
    }

};

} // namespace patina::shading
