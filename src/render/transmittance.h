// Visibility between two points through the scene's media: surfaces block, index-matched
// medium boundaries (objects with an interior medium and no bsdf) let the ray through and
// switch the medium, and each medium segment attenuates by its transmittance.
#pragma once

#include "render/scene.h"

#include "core/sampling.h"
#include "core/spectrum.h"

#include <Imath/ImathVec.h>

namespace patina::render {

/// Transmittance from `origin` along unit `dir` over `distance` (+inf for lights at
/// infinity), starting in `medium` (null = vacuum). 0 when a surface blocks the way.
SampledSpectrum transmittance_along(const Scene& scene, Imath::V3f origin, const Imath::V3f& dir,
                                    float distance, const ShaderInstance* medium,
                                    const PatinaWavelengths& wl, Pcg32& rng);

/// The medium a ray is in after crossing the surface of `obj` (outward geometric normal
/// `Ng`) in direction `dir`: entering the interior, or leaving it into vacuum.
inline const ShaderInstance* medium_after_crossing(const SceneObject& obj, const Imath::V3f& Ng,
                                                   const Imath::V3f& dir,
                                                   const ShaderInstance* current)
{
    if (!obj.interior)
        return current;
    return dir.dot(Ng) < 0.0f ? obj.interior.get() : nullptr;
}

}  // namespace patina::render
