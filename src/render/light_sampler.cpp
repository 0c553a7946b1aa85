#include "render/light_sampler.h"

#include "render/area_light.h"
#include "render/environment_light.h"

#include <cmath>

namespace patina::render {

PatinaWavelengths power_wavelengths()
{
    PatinaWavelengths wl{};
    wl.count = PATINA_MAX_WAVELENGTHS;
    for (int i = 0; i < wl.count; ++i)
        wl.lambda_nm[i] = 400.0f + 300.0f * (static_cast<float>(i) + 0.5f) / wl.count;
    return wl;
}

float power_luminance(const SampledSpectrum& L)
{
    const PatinaWavelengths wl = power_wavelengths();
    double sum = 0.0, weight = 0.0;
    for (int i = 0; i < wl.count && i < L.count; ++i) {
        const double y = cie_y(wl.lambda_nm[i]);
        sum += y * L[i];
        weight += y;
    }
    const double l = weight > 0.0 ? sum / weight : 0.0;
    return std::isfinite(l) && l > 0.0 ? static_cast<float>(l) : 0.0f;
}

LightSampler::LightSampler(std::vector<std::unique_ptr<Light>> lights, bool sample_uniform_sky)
    : lights_(std::move(lights))
{
    std::vector<float> power;
    power.reserve(lights_.size());
    for (size_t i = 0; i < lights_.size(); ++i) {
        const Light* light = lights_[i].get();
        if (light->is_infinite())
            infinite_.push_back(light);
        if (const auto* area = dynamic_cast<const AreaLight*>(light))
            by_mesh_[area->mesh_id()] = area;
        const auto* sky = dynamic_cast<const EnvironmentLight*>(light);
        const bool constant = sky && sky->is_constant();
        if (constant && !uniform_sky_)
            uniform_sky_ = sky;
        if (constant && !sample_uniform_sky)
            continue;  // found by BSDF sampling alone (see the header)
        index_[light] = static_cast<int>(sampled_.size());
        sampled_.push_back(light);
        // A NaN or negative power must not poison the distribution; such a light counts as 0.
        const float p = light->power();
        power.push_back(std::isfinite(p) && p > 0.0f ? p : 0.0f);
    }
    // Distribution1D treats an all-zero function as constant: uniform choice (pbrt-v4
    // PowerLightSampler does the same).
    if (!sampled_.empty())
        distribution_ = Distribution1D(power);
    uniform_sky_pmf_ = uniform_sky_ ? pmf(uniform_sky_) : 0.0f;
}

std::optional<SampledLight> LightSampler::sample_distribution(float u) const
{
    if (sampled_.empty())
        return std::nullopt;
    float pmf = 0.0f;
    const int i = distribution_.sample_discrete(u, &pmf);
    if (!(pmf > 0.0f))
        return std::nullopt;
    return SampledLight{sampled_[static_cast<size_t>(i)], pmf};
}

float LightSampler::pmf(const Light* light) const
{
    if (sampled_.size() == 1)
        return light == sampled_[0] ? 1.0f : 0.0f;
    const auto it = index_.find(light);
    return it == index_.end() ? 0.0f : distribution_.discrete_pmf(it->second);
}

const AreaLight* LightSampler::area_light_for_mesh(int mesh_id) const
{
    const auto it = by_mesh_.find(mesh_id);
    return it == by_mesh_.end() ? nullptr : it->second;
}

} // namespace patina::render
