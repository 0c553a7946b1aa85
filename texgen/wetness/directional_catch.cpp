#include "texgen/wetness/directional_catch.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace patina::texgen {

void orthonormal_basis(const Imath::V3f& n, Imath::V3f* t, Imath::V3f* b)
{
    // Branchless orthonormal basis: Duff et al. 2017, "Building an Orthonormal Basis,
    // Revisited", JCGT 6(1), Listing 3.
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float c = n.x * n.y * a;
    *t = Imath::V3f(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
    *b = Imath::V3f(c, sign + n.y * n.y * a, -n.y);
}

Imath::V2f jittered_sample(int i, int n, Pcg32& rng)
{
    const int grid = static_cast<int>(std::sqrt(static_cast<double>(std::max(n, 1))));
    float u1 = rng.uniform_float();
    float u2 = rng.uniform_float();
    if (i < grid * grid) {
        // Jittered (stratified) sampling: one sample per cell of a grid x grid grid.
        const float g = static_cast<float>(grid);
        u1 = std::min((static_cast<float>(i % grid) + u1) / g, 0x1.fffffep-1f);
        u2 = std::min((static_cast<float>(i / grid) + u2) / g, 0x1.fffffep-1f);
    }
    return {u1, u2};
}

DirectionCone::DirectionCone(const Imath::V3f& axis, float spread_rad) : spread_(spread_rad)
{
    const float length = axis.length();
    if (!(length > 0.0f) || !std::isfinite(length))
        throw std::runtime_error(fmt::format("direction ({}, {}, {}) must be finite and non-zero",
                                             axis.x, axis.y, axis.z));
    if (!(spread_rad >= 0.0f && spread_rad < 0.5f * std::numbers::pi_v<float>))
        throw std::runtime_error(
            fmt::format("spread {} deg must be in [0, 90)", spread_rad * 180.0 / std::numbers::pi));
    axis_ = axis / length;
    cos_spread_ = std::cos(spread_rad);
    orthonormal_basis(axis_, &tangent_, &bitangent_);
}

Imath::V3f DirectionCone::sample(float u1, float u2) const
{
    if (spread_ == 0.0f)
        return axis_;
    // Uniform cone: cos(theta) = 1 - u (1 - cos(spread)), pbrt-v4 §A.5.4 (SampleUniformCone).
    const float cos_theta = 1.0f - u1 * (1.0f - cos_spread_);
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    const float phi = 2.0f * std::numbers::pi_v<float> * u2;
    return (sin_theta * std::cos(phi)) * tangent_ + (sin_theta * std::sin(phi)) * bitangent_ +
           cos_theta * axis_;
}

float directional_catch(const EmbreeScene& scene, const SurfaceSample& s, const DirectionCone& cone,
                        int rays, float max_distance, Pcg32& rng)
{
    rays = std::max(rays, 1);
    // Without spread every direction is the axis: one ray says everything.
    if (cone.spread() == 0.0f)
        rays = 1;
    double caught = 0.0;
    double reference = 0.0;
    for (int i = 0; i < rays; ++i) {
        const Imath::V2f u = jittered_sample(i, rays, rng);
        const Imath::V3f d = cone.sample(u.x, u.y);
        reference += cone.axis().dot(d);
        // Catch factor: the flux through a surface facing it (Lambert's cosine).
        const float c = -s.N.dot(d);
        const Imath::V3f towards_source = -d;
        // A direction behind the geometric surface cannot reach the point.
        if (c <= 0.0f || s.Ng.dot(towards_source) <= 0.0f)
            continue;
        const Imath::V3f origin = offset_ray_origin(s.P, s.Ng, towards_source);
        if (!scene.occluded(origin, towards_source, 0.0f, max_distance))
            caught += c;
    }
    return static_cast<float>(caught / reference);
}

} // namespace patina::texgen
