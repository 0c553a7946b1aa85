#include "render/distant_light.h"

#include "render/light_sampler.h"

#include "core/rgb_spectrum.h"

#include <cmath>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace patina::render {

namespace {

    constexpr double kPi = std::numbers::pi;

    // Directions built by sample() carry float rounding of about 1e-7 in sin θ, which for
    // the real sun (θmax ≈ 0.0046 rad) is a few 1e-5 of sin² θmax: accept that much beyond
    // the rim so that every sampled direction is seen as inside the disc.
    constexpr float kRimSlack = 1e-4f;

    // Orthonormal basis around a unit vector: Duff et al. 2017, "Building an Orthonormal
    // Basis, Revisited" (pbrt-v4 CoordinateSystem, §3.3.3).
    void coordinate_system(const Imath::V3f& n, Imath::V3f& s, Imath::V3f& t)
    {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z);
        const float b = n.x * n.y * a;
        s = Imath::V3f(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
        t = Imath::V3f(b, sign + n.y * n.y * a, -n.y);
    }

} // namespace

DistantLight::DistantLight(const Imath::V3f& direction, float angular_diameter_deg,
                           const PatinaRgbSpectrum& spectrum, float irradiance)
    : spectrum_(spectrum), irradiance_(irradiance)
{
    const float len = direction.length();
    if (!(std::isfinite(len) && len > 0.0f))
        throw std::invalid_argument("distant light: the direction towards the sun must be a "
                                    "finite, non-zero vector");
    if (!(angular_diameter_deg >= 0.0f && angular_diameter_deg < 180.0f))
        throw std::invalid_argument("distant light: angular diameter " +
                                    std::to_string(angular_diameter_deg) +
                                    " degrees is outside [0, 180)");
    if (!(irradiance >= 0.0f && std::isfinite(irradiance)))
        throw std::invalid_argument("distant light: irradiance " + std::to_string(irradiance) +
                                    " must be finite and >= 0");
    direction_ = direction / len;
    coordinate_system(direction_, s_, t_);
    if (angular_diameter_deg == 0.0f)
        return;

    const double theta_max = 0.5 * angular_diameter_deg * kPi / 180.0;
    const double sin_max = std::sin(theta_max);
    // 1 − cos θmax = 2 sin²(θmax/2): exact for small discs, where 1 − cos loses all digits
    const double half = std::sin(0.5 * theta_max);
    cos_max_ = static_cast<float>(std::cos(theta_max));
    one_minus_cos_max_ = static_cast<float>(2.0 * half * half);
    sin2_max_ = static_cast<float>(sin_max * sin_max);
    // A disc of uniform radiance L and half-angle θmax gives a perpendicular surface
    // E = ∫ L cos θ dω = 2π L ∫0^θmax cos θ sin θ dθ = π L sin² θmax (an integral over
    // spherical coordinates, pbrt-v4 §4.2.2), so L = E / (π sin² θmax).
    radiance_scale_ = static_cast<float>(irradiance / (kPi * sin_max * sin_max));
    // Uniform cone density 1 / (2π (1 − cos θmax)): pbrt-v4 §A.5.4 UniformConePDF
    cone_pdf_ = static_cast<float>(1.0 / (2.0 * kPi * (2.0 * half * half)));
}

SampledSpectrum DistantLight::spectrum(const PatinaWavelengths& wl) const
{
    return SampledSpectrum::from_function(
        wl, [&](float lambda) { return RgbToSpectrum::eval(spectrum_, lambda); });
}

bool DistantLight::in_disc(const Imath::V3f& w) const
{
    if (is_delta())
        return false;
    const float len2 = w.length2();
    const float c = w.dot(direction_);
    if (!(len2 > 0.0f) || c <= 0.0f)
        return false;
    if (cos_max_ > 0.5f) {
        // Small disc: sin² θ = |w × d|² / |w|² keeps its digits where cos θ ≈ 1 does not
        return w.cross(direction_).length2() <= sin2_max_ * (1.0f + kRimSlack) * len2;
    }
    return c * c >= cos_max_ * cos_max_ * (1.0f - kRimSlack) * len2;
}

std::optional<LightSample> DistantLight::sample(const Imath::V3f&, Imath::V2f u,
                                                const PatinaWavelengths& wl) const
{
    LightSample ls;
    ls.distance = std::numeric_limits<float>::infinity();
    if (is_delta()) {
        // A single direction carries the irradiance itself (pbrt-v4 DistantLight::SampleLi)
        ls.wi = direction_;
        ls.L = irradiance_ * spectrum(wl);
        ls.pdf = 1.0f;
        ls.is_delta = true;
        return ls;
    }
    // Uniform direction in the cone: pbrt-v4 §A.5.4 SampleUniformCone, written with
    // 1 − cos θ = u (1 − cos θmax) so that sin² θ = (1 − cos θ)(1 + cos θ) stays exact
    const float one_minus_cos = u.x * one_minus_cos_max_;
    const float cos_theta = 1.0f - one_minus_cos;
    const float sin_theta = std::sqrt(std::max(0.0f, one_minus_cos * (2.0f - one_minus_cos)));
    const float phi = 2.0f * static_cast<float>(kPi) * u.y;
    const Imath::V3f w =
        sin_theta * std::cos(phi) * s_ + sin_theta * std::sin(phi) * t_ + cos_theta * direction_;
    ls.wi = w.normalized();
    ls.L = radiance_scale_ * spectrum(wl);
    ls.pdf = cone_pdf_;
    return ls;
}

float DistantLight::pdf(const Imath::V3f&, const Imath::V3f& wi, const LightHit*) const
{
    return in_disc(wi) ? cone_pdf_ : 0.0f;
}

SampledSpectrum DistantLight::escaped_radiance(const Imath::V3f& dir,
                                               const PatinaWavelengths& wl) const
{
    if (!in_disc(dir))
        return SampledSpectrum(wl.count, 0.0f);
    return radiance_scale_ * spectrum(wl);
}

float DistantLight::power() const
{
    const PatinaWavelengths wl = power_wavelengths();
    return static_cast<float>(kPi) * scene_radius_ * scene_radius_ * irradiance_ *
           power_luminance(spectrum(wl));
}

} // namespace patina::render
