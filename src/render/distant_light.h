// The sun: a distant light seen as a disc of uniform radiance and small angular diameter, or
// as a single direction (a delta light) when the diameter is 0. It is specified, as a
// weather file or a solar table gives it, by the irradiance E on a surface facing it.
#pragma once

#include "render/light.h"

#include <patina/abi.h>

namespace patina::render {

class DistantLight : public Light {
public:
    /// `direction` points towards the sun (normalised here); `angular_diameter_deg` in
    /// [0, 180), 0 for a delta light; `spectrum` is an emission colour uplifted by the host
    /// (illuminant = 1: white is D65 of luminance 1); `irradiance` = E >= 0 scales it to the
    /// irradiance on a surface perpendicular to the sun. Throws std::invalid_argument for a
    /// zero or non-finite direction, a diameter out of range or a negative irradiance.
    DistantLight(const Imath::V3f& direction, float angular_diameter_deg,
                 const PatinaRgbSpectrum& spectrum, float irradiance);

    std::optional<LightSample> sample(const Imath::V3f& p, Imath::V2f u,
                                      const PatinaWavelengths& wl) const override;
    float pdf(const Imath::V3f& p, const Imath::V3f& wi,
              const LightHit* hit = nullptr) const override;
    bool is_infinite() const override { return true; }
    SampledSpectrum escaped_radiance(const Imath::V3f& dir,
                                     const PatinaWavelengths& wl) const override;
    /// π r² E × the spectrum's luminance: the flux through the scene's bounding disc
    /// (pbrt-v4 DistantLight::Phi); r is set by set_scene_radius (default 1).
    float power() const override;

    /// True when the sun is a single direction (angular diameter 0).
    bool is_delta() const { return one_minus_cos_max_ == 0.0f; }
    const Imath::V3f& direction() const { return direction_; }
    /// Radiance of the disc per unit of the spectrum: E / (π sin² θmax); 0 for a delta sun.
    float radiance_scale() const { return radiance_scale_; }
    /// True when unit-ish direction `w` lies inside the sun's disc (false for a delta sun).
    bool in_disc(const Imath::V3f& w) const;

    /// Radius of a sphere bounding the scene; only power() uses it.
    void set_scene_radius(float radius) { scene_radius_ = radius; }

private:
    SampledSpectrum spectrum(const PatinaWavelengths& wl) const;

    Imath::V3f direction_, s_, t_; // orthonormal frame about the sun's direction
    PatinaRgbSpectrum spectrum_;
    float irradiance_ = 0;
    float cos_max_ = 1, one_minus_cos_max_ = 0, sin2_max_ = 0;
    float radiance_scale_ = 0, cone_pdf_ = 0;
    float scene_radius_ = 1;
};

} // namespace patina::render
