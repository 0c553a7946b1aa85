#include "texgen/deposit/source_visibility.h"

#include "texgen/wetness/directional_catch.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace patina::texgen {

namespace {

    constexpr float kPi = std::numbers::pi_v<float>;
    // Shadow rays of area sources stop just short of the sampled source point.
    constexpr float kShortOfSource = 1.0f - 1e-4f;

    // V(w) for a direction w towards a source point at distance `distance` (inf: none).
    bool unoccluded(const EmbreeScene& scene, const SurfaceSample& s, const Imath::V3f& w,
                    float distance)
    {
        // A direction behind the geometric surface cannot reach the point.
        if (s.Ng.dot(w) <= 0.0f)
            return false;
        return !scene.occluded(offset_ray_origin(s.P, s.Ng, w), w, 0.0f, distance);
    }

    float sphere_visibility(const EmbreeScene& scene, const SurfaceSample& s,
                            const DepositSource& src, int rays, Pcg32& rng)
    {
        const Imath::V3f to_center = src.center - s.P;
        const float d = to_center.length();
        // Inside the source: it fills the whole hemisphere.
        if (d <= src.radius)
            return 1.0f;
        const Imath::V3f axis = to_center / d;
        Imath::V3f t, b;
        orthonormal_basis(axis, &t, &b);
        // The cone the sphere subtends: sin(theta_max) = R / d (pbrt-v4 §6.2.4, sphere sampling).
        const float sin2_max = (src.radius * src.radius) / (d * d);
        const float cos_max = std::sqrt(std::max(0.0f, 1.0f - sin2_max));
        double sum = 0.0;
        for (int i = 0; i < rays; ++i) {
            const Imath::V2f u = jittered_sample(i, rays, rng);
            // Uniform direction in the cone: pbrt-v4 §A.5.4 (SampleUniformCone).
            const float cos_theta = 1.0f - u.x * (1.0f - cos_max);
            const float sin2_theta = std::max(0.0f, 1.0f - cos_theta * cos_theta);
            const float sin_theta = std::sqrt(sin2_theta);
            const float phi = 2.0f * kPi * u.y;
            const Imath::V3f w = (sin_theta * std::cos(phi)) * t + (sin_theta * std::sin(phi)) * b +
                                 cos_theta * axis;
            const float c = s.N.dot(w);
            if (c <= 0.0f)
                continue;
            // Near intersection with the sphere: t = d cos - sqrt(R^2 - d^2 sin^2).
            const float disc = src.radius * src.radius - d * d * sin2_theta;
            const float hit = d * cos_theta - std::sqrt(std::max(0.0f, disc));
            if (unoccluded(scene, s, w, hit * kShortOfSource))
                sum += c;
        }
        // F = (1/pi) * solid angle * mean(V cos), solid angle 2 pi (1 - cos(theta_max)).
        const double solid_angle = 2.0 * std::numbers::pi * (1.0 - static_cast<double>(cos_max));
        return static_cast<float>(solid_angle / std::numbers::pi * sum / rays);
    }

    // Form factor of a planar two-sided source from uniform samples of its area: with
    // dw = cos_s dA / r^2 (pbrt-v4 §4.2.3, integrals over area), F = (A / pi) mean(V cos_p cos_s /
    // r^2).
    template <class PointOnSource>
    float planar_visibility(const EmbreeScene& scene, const SurfaceSample& s,
                            const Imath::V3f& source_normal, float area, int rays, Pcg32& rng,
                            const PointOnSource& point_on_source)
    {
        double sum = 0.0;
        for (int i = 0; i < rays; ++i) {
            const Imath::V3f q = point_on_source(jittered_sample(i, rays, rng));
            const Imath::V3f to_q = q - s.P;
            const float r2 = to_q.length2();
            if (!(r2 > 0.0f))
                continue;
            const float r = std::sqrt(r2);
            const Imath::V3f w = to_q / r;
            const float cos_p = s.N.dot(w);
            const float cos_s = std::abs(source_normal.dot(w));
            if (cos_p <= 0.0f || cos_s <= 0.0f)
                continue;
            if (unoccluded(scene, s, w, r * kShortOfSource))
                sum += static_cast<double>(cos_p) * cos_s / r2;
        }
        return static_cast<float>(area / std::numbers::pi * sum / rays);
    }

} // namespace

float source_visibility(const EmbreeScene& scene, const SurfaceSample& s,
                        const DepositSource& source, int rays, float max_distance, Pcg32& rng)
{
    rays = std::max(rays, 1);
    using K = DepositSource::Kind;
    switch (source.kind) {
    case K::Sphere:
        return sphere_visibility(scene, s, source, rays, rng);
    case K::Disc: {
        Imath::V3f t, b;
        orthonormal_basis(source.normal, &t, &b);
        const float area = kPi * source.radius * source.radius;
        return planar_visibility(
            scene, s, source.normal, area, rays, rng, [&](const Imath::V2f& u) {
                // Uniform in area: r = R sqrt(u1), phi = 2 pi u2 (pbrt-v4 §A.5.1).
                const float r = source.radius * std::sqrt(u.x);
                const float phi = 2.0f * kPi * u.y;
                return source.center + (r * std::cos(phi)) * t + (r * std::sin(phi)) * b;
            });
    }
    case K::Rectangle: {
        const Imath::V3f n = source.edge1.cross(source.edge2);
        const float area = n.length();
        return planar_visibility(scene, s, n / area, area, rays, rng, [&](const Imath::V2f& u) {
            return source.corner + u.x * source.edge1 + u.y * source.edge2;
        });
    }
    case K::Directional: {
        const DirectionCone cone(source.direction, source.spread_deg * kPi / 180.0f);
        return directional_catch(scene, s, cone, rays, max_distance, rng);
    }
    }
    return 0.0f;
}

} // namespace patina::texgen
