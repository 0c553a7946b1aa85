// What a surface point catches from a directional flux with an angular spread (rain for the
// wetness baker, a directional deposit source for the deposit baker): directions drawn
// uniformly in a cone, each weighted by the catch factor max(0, -N.d) and by its visibility
// (a shadow ray through the scene towards where the flux comes from). Dorsey et al. 1999 §6:
// "wetness maps were computed with visibility to a directional rain source".
#pragma once

#include "core/embree_scene.h"
#include "core/sampling.h"
#include "texgen/texels/surface_samples.h"

#include <Imath/ImathVec.h>

namespace patina::texgen {

/// Unit vectors t, b making (t, b, n) a right-handed orthonormal frame for the unit n.
void orthonormal_basis(const Imath::V3f& n, Imath::V3f* t, Imath::V3f* b);

/// Uniform numbers in [0,1)^2 for sample i of n: the first floor(sqrt(n))^2 samples jittered
/// on a floor(sqrt(n))^2 grid (stratified), the rest independent. Draws two numbers per call.
Imath::V2f jittered_sample(int i, int n, Pcg32& rng);

/// Directions uniformly distributed in solid angle within `spread_rad` of `axis`.
class DirectionCone {
public:
    /// `axis`: the direction the flux travels (any length > 0); spread in [0, pi/2).
    /// Throws std::runtime_error for a zero or non-finite axis or a spread outside range.
    DirectionCone(const Imath::V3f& axis, float spread_rad);

    const Imath::V3f& axis() const { return axis_; } ///< unit
    float spread() const { return spread_; }
    /// The direction for uniform numbers (u1, u2) in [0,1)^2: cos(theta) uniform in
    /// [cos(spread), 1] (uniform solid angle, pbrt-v4 §A.5.4 SampleUniformCone), phi = 2 pi u2.
    Imath::V3f sample(float u1, float u2) const;

private:
    Imath::V3f axis_, tangent_, bitangent_;
    float spread_ = 0.0f;
    float cos_spread_ = 1.0f;
};

/// The catch of sample `s` under a flux travelling along the cone's directions d_i,
/// i = 1..rays (stratified on a jittered sqrt(rays) x sqrt(rays) grid, the rest random):
///
///     catch = sum_i V_i max(0, -N.d_i) / sum_i (axis . d_i)
///
/// V_i is 1 when the shadow ray from s towards -d_i meets nothing within `max_distance` and
/// leaves on the front of the geometric normal, else 0. The denominator is the catch of an
/// open surface facing the flux, computed with the same directions, so such a surface gets
/// exactly 1 whatever the spread and ray count (a ratio estimator). In [0, 1] up to rounding
/// (a tilted normal can exceed the facing catch by sampling noise; callers clamp).
float directional_catch(const EmbreeScene& scene, const SurfaceSample& s, const DirectionCone& cone,
                        int rays, float max_distance, Pcg32& rng);

} // namespace patina::texgen
