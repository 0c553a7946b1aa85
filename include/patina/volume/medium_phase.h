// The phase-function half of a medium's function table (PatinaMediumFuncs::phase_eval and
// phase_sample), written once for every medium plugin: the directions checked, the phase
// function of the instance evaluated or sampled, the value (the same at every wavelength)
// filled in. A phase object has `eval(cos θ)`, cos θ = dot(wo, wi) with both directions
// pointing away from the scattering point (pbrt-v4's convention), and
// `sample(wo, u, &pdf)` returning wi with pdf = p(wo, wi).
#pragma once

#include <patina/abi.h>
#include <patina/shading/phase.h>
#include <patina/shading/spectral.h>
#include <patina/shading/vec.h>

#include <cmath>

namespace patina::volume {

/// w as a unit vector, or false when it has no direction. Directions that are unit already
/// (as abi.h requires) pass unchanged, so that phase_eval at a sampled wi sees the very
/// numbers phase_sample used.
inline bool unit_direction(PatinaVec3 w, shading::Vec3* out)
{
    const shading::Vec3 v(w);
    const float len2 = shading::length_squared(v);
    if (!shading::is_finite(v) || !std::isfinite(len2) || len2 == 0.0f)
        return false;
    *out = std::abs(len2 - 1.0f) > 1e-5f ? v / std::sqrt(len2) : v;
    return true;
}

/// Henyey-Greenstein as a phase object (shading/phase.h), g in (−1, 1).
struct HenyeyGreenstein {
    float g = 0.0f;

    float eval(float cos_theta) const { return shading::henyey_greenstein(cos_theta, g); }
    shading::Vec3 sample(shading::Vec3 wo, shading::Vec2 u, float* pdf) const
    {
        return shading::sample_henyey_greenstein(wo, g, u, pdf);
    }
};

/// PatinaMediumFuncs::phase_eval for instances of `Instance` whose phase object is the
/// member `Phase` (e.g. phase_eval<Fog, &Fog::phase>).
template <class Instance, auto Phase>
float phase_eval(const void* instance, const PatinaShadingContext*, PatinaVec3 wo, PatinaVec3 wi,
                 const PatinaWavelengths* wl, float* p)
{
    const auto& phase = static_cast<const Instance*>(instance)->*Phase;
    shading::Vec3 o, i;
    if (!unit_direction(wo, &o) || !unit_direction(wi, &i)) {
        shading::fill(0.0f, *wl, p);
        return 0.0f;
    }
    const float value = static_cast<float>(phase.eval(shading::dot(o, i)));
    shading::fill(value, *wl, p);
    return value;
}

/// PatinaMediumFuncs::phase_sample for the same instances.
template <class Instance, auto Phase>
float phase_sample(const void* instance, const PatinaShadingContext*, PatinaVec3 wo, PatinaVec2 u,
                   const PatinaWavelengths* wl, PatinaVec3* wi, float* p)
{
    const auto& phase = static_cast<const Instance*>(instance)->*Phase;
    shading::Vec3 o;
    if (!unit_direction(wo, &o)) {
        shading::fill(0.0f, *wl, p);
        *wi = shading::Vec3();
        return 0.0f;
    }
    float pdf = 0.0f;
    *wi = phase.sample(o, shading::Vec2(u), &pdf);
    shading::fill(pdf, *wl, p);
    return pdf;
}

}  // namespace patina::volume
