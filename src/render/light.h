// Lights as the integrator sees them: sample an incident direction at a point (for next-event
// estimation), give the pdf of a direction found by BSDF sampling (for MIS), and the
// radiance of rays that escape the scene. Radiance is spectral at the path's wavelengths.
#pragma once

#include "core/spectrum.h"

#include <Imath/ImathVec.h>

#include <optional>

namespace patina::render {

/// What a light sample gives the integrator.
struct LightSample {
    Imath::V3f wi;       ///< unit direction from the shading point towards the light
    float distance = 0;  ///< to the sampled point; +infinity for infinite and distant lights
    SampledSpectrum L;   ///< radiance arriving along -wi (before occlusion)
    float pdf = 0;       ///< solid-angle density of wi (for a delta light: 1, see is_delta)
    bool is_delta = false;  ///< a single direction: no MIS, BSDF sampling cannot find it
};

/// A point where a BSDF-sampled ray met an area light (for pdf()).
struct LightHit {
    Imath::V3f P;   ///< the point on the light
    Imath::V3f Ng;  ///< its geometric normal
    int prim_id = -1;
};

class Light {
public:
    virtual ~Light() = default;

    /// Sample an incident direction at `p` with uniform numbers `u`; nothing when the light
    /// cannot illuminate `p` (e.g. behind a one-sided emitter) or the sample is degenerate.
    virtual std::optional<LightSample> sample(const Imath::V3f& p, Imath::V2f u,
                                              const PatinaWavelengths& wl) const = 0;

    /// Solid-angle density with which sample() would choose `wi` at `p`. For area lights
    /// `hit` is where the ray met the light; infinite lights ignore it. 0 for delta lights.
    virtual float pdf(const Imath::V3f& p, const Imath::V3f& wi,
                      const LightHit* hit = nullptr) const = 0;

    /// True for lights at infinity (environment, sun): rays that escape the scene see them.
    virtual bool is_infinite() const = 0;

    /// Radiance seen along direction `dir` by a ray that escapes the scene (infinite lights;
    /// 0 for the others and outside a sun's disc).
    virtual SampledSpectrum escaped_radiance(const Imath::V3f& dir,
                                             const PatinaWavelengths& wl) const = 0;

    /// A rough measure of emitted power (any consistent unit), to choose lights by.
    virtual float power() const = 0;
};

}  // namespace patina::render
