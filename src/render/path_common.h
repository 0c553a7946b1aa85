// Pieces of a path's estimator shared by the per-path loop (integrator.cpp) and the
// wavefront loop (wavefront.cpp), so that both compute every value with the same
// operations in the same order (and so the same bits).
#pragma once

#include "render/environment_light.h"
#include "render/scene.h"
#include "render/shading_frame.h"

#include "core/sampling.h"
#include "core/spectrum.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace patina::render::path {

constexpr float kInf = std::numeric_limits<float>::infinity();

inline PatinaVec3 to_abi(const Imath::V3f& v) { return {v.x, v.y, v.z}; }
inline Imath::V3f from_abi(const PatinaVec3& v) { return {v.x, v.y, v.z}; }
// v / |v| with one square root and one division (Imath's normalized() divides thrice and
// checks for tiny vectors); v must not be 0.
inline Imath::V3f unit(const Imath::V3f& v) { return v * (1.0f / std::sqrt(v.dot(v))); }

// A contribution to a path's radiance after `bounces` scatterings of its light, clamped as
// FilmSettings::clamp_indirect says: light scattered more than once (bounces >= 2), whose
// largest wavelength exceeds the limit, is scaled down to it (its hue kept). Cycles' "Clamp
// Indirect": a biased cure for the fireflies of caustic paths (a diffuse floor seeing the
// sun in a polished sphere) that unidirectional sampling finds too rarely to converge.
inline SampledSpectrum clamp_indirect(const SampledSpectrum& c, int bounces, float limit)
{
    if (!(limit > 0.0f) || bounces < 2)
        return c;
    const float m = c.max_value();
    return m > limit ? c * (limit / m) : c;
}

// What the previous scattering vertex knows, for MIS weights of emission found by BSDF
// or phase sampling (pbrt-v4 §13.4 and §14.2, VolPathIntegrator).
struct PrevVertex {
    Imath::V3f P{0, 0, 0};
    float pdf = 0.0f;      // solid-angle pdf of the direction it sampled
    bool specular = true;  // camera ray or delta lobe: no light sampling competed
};

inline float emission_mis_weight(const Scene& scene, const PrevVertex& prev, float light_pdf)
{
    // light_pdf 0: no light sampling competed (a light left to BSDF sampling, such as the
    // uniform sky); the power heuristic would give 1 too, but 0 once prev.pdf² underflows.
    if (prev.specular || !scene.film.mis || light_pdf == 0.0f)
        return 1.0f;
    return power_heuristic(1, prev.pdf, 1, light_pdf);
}

// How a scattering vertex (a surface BSDF or a medium's phase function) answers NEE.
struct Scatterer {
    const ShaderInstance* shader;
    const PatinaShadingContext* ctx;
    const ShadingFrame* frame;  // null for a medium point (world-space directions)
    PatinaVec3 wo;

    // Value (times |cos| on surfaces) and pdf of scattering towards world direction wi;
    // the pdf is left at 0 when the value is 0 (the sample is dropped).
    float eval(const Imath::V3f& wi, const PatinaWavelengths& wl, SampledSpectrum& f) const
    {
        float v[PATINA_MAX_WAVELENGTHS] = {};
        if (frame) {
            const PatinaVec3 wl_i = to_abi(frame->to_local(wi));
            shader->bsdf()->eval(shader->get(), ctx, wo, wl_i, &wl, v);
            f = SampledSpectrum::from_lanes(wl.count, v) * std::abs(wl_i.z);
            if (f.is_black())
                return 0.0f;
            return shader->bsdf()->pdf(shader->get(), ctx, wo, wl_i, &wl);
        }
        const float pdf = shader->medium()->phase_eval(shader->get(), ctx, wo, to_abi(wi), &wl, v);
        f = SampledSpectrum::from_lanes(wl.count, v);
        return pdf;
    }
};

// A constant environment's radiance at the path's wavelengths, evaluated once per path
// (it is the same for every direction and every vertex), with its selection probability
// (0 when it is left to BSDF sampling, the default: light_sampler.h).
struct UniformSky {
    const EnvironmentLight* light = nullptr;
    SampledSpectrum L;
    float pmf = 0.0f;
    bool black = true;  // L is 0 at every wavelength (or there is no uniform sky)

    UniformSky() = default;
    UniformSky(const Scene& scene, const PatinaWavelengths& wl, const SampledSpectrum& d65)
        : light(scene.lights.uniform_sky())
    {
        if (light) {
            L = light->constant_radiance(wl, d65);
            pmf = scene.lights.uniform_sky_pmf();
            black = L.is_black();
        }
    }
};

// Radiance of the infinite lights seen by a ray leaving the scene, MIS-weighted.
inline SampledSpectrum escaped(const Scene& scene, const Ray& ray, const PrevVertex& prev,
                               const PatinaWavelengths& wl, const UniformSky& sky)
{
    SampledSpectrum L(wl.count, 0.0f);
    for (const Light* light : scene.lights.infinite_lights()) {
        if (light == sky.light) {
            if (!sky.black)
                L += sky.L * emission_mis_weight(scene, prev,
                                                 sky.pmf * EnvironmentLight::kUniformSpherePdf);
            continue;
        }
        const SampledSpectrum Le = light->escaped_radiance(ray.dir, wl);
        if (Le.is_black())
            continue;
        const float light_pdf = scene.lights.pmf(light) * light->pdf(prev.P, ray.dir);
        L += Le * emission_mis_weight(scene, prev, light_pdf);
    }
    return L;
}

// η'² of a sampled transmission (1 for reflection), for the roulette's throughput:
// pbrt-v4 §13.4 ("etaScale"). A plugin that leaves eta unset counts as 1.
inline float eta_scale_of(const PatinaBsdfSample& bs)
{
    if (!(bs.lobe & PATINA_LOBE_TRANSMISSION) || !(bs.eta > 0.0f) || !std::isfinite(bs.eta))
        return 1.0f;
    return bs.eta * bs.eta;
}

// Russian roulette once the path has some length (pbrt-v4 §13.4, PathIntegrator::Li and
// VolPathIntegrator::Li). The throughput it looks at is the largest component of beta
// times `eta_scale`, the product of η'² over the boundaries crossed, so that the 1/η'²
// radiance scaling inside a dense body does not count as a loss. A path whose throughput
// is 1 or more always goes on; below 1 it survives with probability equal to it and is
// divided by it, which brings its throughput to exactly 1. Roulette thus never raises a
// throughput above 1: no path can blow up however many albedo-0.99 scatterings or internal
// reflections it makes (the rule it replaces, a kill probability of at least 0.05 and a
// division by 0.95, multiplied a weight by 1/0.95 per vertex). False ends the path.
inline bool survive_roulette(int depth, SampledSpectrum& beta, float eta_scale, Pcg32& rng)
{
    if (depth < 3)
        return true;
    const float throughput = beta.max_value() * eta_scale;
    if (!(throughput < 1.0f))
        return true;
    const float q = std::max(0.0f, 1.0f - throughput);
    if (rng.uniform_float() < q)
        return false;
    beta /= 1.0f - q;
    return true;
}

}  // namespace patina::render::path
