// Choosing a light for next-event estimation: in proportion to each light's power, so that
// a bright sun is sampled more often than a dim lamp. Also the two look-ups the integrator
// needs when a BSDF-sampled ray finds a light by itself: the infinite lights (for escaped
// rays) and the area light behind an emissive mesh (for the MIS weight of the hit).
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
    /// Takes ownership of the lights; AreaLights are indexed by their mesh id.
    explicit LightSampler(std::vector<std::unique_ptr<Light>> lights);

    /// A light with probability proportional to its power() (uniform when every power is 0);
    /// nothing when there are no lights.
    std::optional<SampledLight> sample(float u) const
    {
        // One light is chosen with probability 1 (what the distribution gives, without its
        // search); inline for that common case.
        if (lights_.size() == 1)
            return SampledLight{lights_[0].get(), 1.0f};
        return sample_distribution(u);
    }
    /// Probability with which sample() chooses `light` (0 for a light not held here).
    float pmf(const Light* light) const;

    const std::vector<std::unique_ptr<Light>>& lights() const { return lights_; }
    /// Lights that rays escaping the scene see (environment, sun).
    const std::vector<const Light*>& infinite_lights() const { return infinite_; }
    /// The area light of an emissive mesh, or nullptr when the mesh does not emit.
    const AreaLight* area_light_for_mesh(int mesh_id) const;
    /// A constant environment among the lights (the first), or nullptr: its radiance is the
    /// same for every direction, so the integrator evaluates it once per path.
    const EnvironmentLight* uniform_sky() const { return uniform_sky_; }
    /// pmf(uniform_sky()), looked up once at construction (0 without a uniform sky).
    float uniform_sky_pmf() const { return uniform_sky_pmf_; }

private:
    std::optional<SampledLight> sample_distribution(float u) const;

    std::vector<std::unique_ptr<Light>> lights_;
    std::vector<const Light*> infinite_;
    std::unordered_map<const Light*, int> index_;
    std::unordered_map<int, const AreaLight*> by_mesh_;
    const EnvironmentLight* uniform_sky_ = nullptr;
    float uniform_sky_pmf_ = 0.0f;
    Distribution1D distribution_;
};

} // namespace patina::render
