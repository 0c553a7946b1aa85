// Choosing a light for next-event estimation: in proportion to each light's power, so that
// a bright sun is sampled more often than a dim lamp. Also the two look-ups the integrator
// needs when a BSDF-sampled ray finds a light by itself: the infinite lights (for escaped
// rays) and the area light behind an emissive mesh (for the MIS weight of the hit).
//
// A constant environment (the uniform sky) is left out of the choice by default and found
// by BSDF sampling alone, as pbrt-v4's UniformInfiniteLight does under MIS (§12.5.1:
// SampleLi with allowIncompletePDF returns no sample, PDF_Li 0). Sampling it over the whole
// sphere cannot beat a BSDF's own sampling of a constant radiance, and half of its
// directions fall below an opaque surface. Unlike pbrt-v4, which still spends the light
// choice on it, its probability goes to the other lights.
#pragma once

#include "render/light.h"

#include "core/sampling.h"

#include <memory>
#include <unordered_map>
#include <vector>

namespace patina::render {

class AreaLight;
class EnvironmentLight;

/// Fixed wavelengths (8, evenly spaced over 400-700 nm) at which lights estimate power().
PatinaWavelengths power_wavelengths();
/// ȳ-weighted mean of a radiance sampled at power_wavelengths(): a luminance-like number
/// (a D65 spectrum of luminance 1 gives about 1) that makes powers of lights comparable.
float power_luminance(const SampledSpectrum& L);

/// What LightSampler::sample() gives: the light and the probability of having chosen it.
struct SampledLight {
    const Light* light = nullptr;
    float pmf = 0;
};

class LightSampler {
public:
    LightSampler() = default;
    /// Takes ownership of the lights; AreaLights are indexed by their mesh id. Constant
    /// environments take part in the choice only with `sample_uniform_sky` ([render]
    /// sample_uniform_sky in a scene).
    explicit LightSampler(std::vector<std::unique_ptr<Light>> lights,
                          bool sample_uniform_sky = false);

    /// A light with probability proportional to its power() (uniform when every power is 0)
    /// among the lights that are sampled; nothing when there are none.
    std::optional<SampledLight> sample(float u) const
    {
        // One light is chosen with probability 1 (what the distribution gives, without its
        // search); inline for that common case.
        if (sampled_.size() == 1)
            return SampledLight{sampled_[0], 1.0f};
        return sample_distribution(u);
    }
    /// Whether sample() can give a light: false when there are no lights or only a uniform
    /// sky left to BSDF sampling (the integrator then skips next-event estimation, and
    /// draws no numbers for it).
    bool has_sampled_lights() const { return !sampled_.empty(); }
    /// Probability with which sample() chooses `light` (0 for a light not held here and for
    /// one left to BSDF sampling).
    float pmf(const Light* light) const;

    const std::vector<std::unique_ptr<Light>>& lights() const { return lights_; }
    /// Lights that rays escaping the scene see (environment, sun).
    const std::vector<const Light*>& infinite_lights() const { return infinite_; }
    /// The area light of an emissive mesh, or nullptr when the mesh does not emit.
    const AreaLight* area_light_for_mesh(int mesh_id) const;
    /// A constant environment among the lights (the first), or nullptr: its radiance is the
    /// same for every direction, so the integrator evaluates it once per path.
    const EnvironmentLight* uniform_sky() const { return uniform_sky_; }
    /// pmf(uniform_sky()), looked up once at construction (0 without a uniform sky, and
    /// when it is left to BSDF sampling).
    float uniform_sky_pmf() const { return uniform_sky_pmf_; }

private:
    std::optional<SampledLight> sample_distribution(float u) const;

    std::vector<std::unique_ptr<Light>> lights_;
    std::vector<const Light*> sampled_;  // the lights sample() chooses from, in lights_ order
    std::vector<const Light*> infinite_;
    std::unordered_map<const Light*, int> index_;
    std::unordered_map<int, const AreaLight*> by_mesh_;
    const EnvironmentLight* uniform_sky_ = nullptr;
    float uniform_sky_pmf_ = 0.0f;
    Distribution1D distribution_;
};

} // namespace patina::render
