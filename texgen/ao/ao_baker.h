// Ambient occlusion: the fraction of the cosine-weighted hemisphere about the shading normal
// from which a ray escapes the scene (within a maximum distance). 1 on an open plane, 0 at
// the bottom of a closed box. A comparison baker next to Miller's accessibility.
#pragma once

#include "texgen/ao/sobol02.h"
#include "texgen/bake/sample_baker.h"

#include <patina/shading/sampling.h>

#include <cmath>
#include <limits>

namespace patina::texgen {

struct AoOptions {
    /// Rays per output element (texel or vertex), split over the element's samples, at
    /// least one per sample.
    int rays = 64;
    /// Occluders farther than this (m) along a ray are ignored; infinity: no limit.
    float max_distance = std::numeric_limits<float>::infinity();
};

/// Cosine-weighted hemisphere rays about the sample's shading normal N, stratified by a
/// scrambled (0,2)-sequence (a fresh scramble per sample from its generator). A direction
/// that points below the triangle's geometric normal Ng (possible where N and Ng differ)
/// would enter the surface: it counts as occluded, the way the facet itself would block it.
/// Rays start at offset_ray_origin(P, Ng, dir) so they cannot hit their own triangle.
class AoBaker final : public SampleBaker {
public:
    /// Throws std::runtime_error naming the parameter when rays < 1 or max_distance <= 0.
    AoBaker(const EmbreeScene& scene, const AoOptions& options);

    std::vector<std::string> channels() const override { return {"ao"}; }
    size_t rays_per_sample(size_t group_size) const override;
    void evaluate(const SurfaceSample& s, size_t group_size, Pcg32& rng,
                  float* out) const override;

    const AoOptions& options() const { return options_; }

    /// The rays evaluate() traces for sample `s`: calls trace(origin, dir) for each ray
    /// that leaves above the facet (the others count as occluded) and returns how many
    /// rays there are in all. evaluate() traces them with EmbreeScene::occluded; the
    /// benchmark records them to replay through raw Embree.
    template <class Trace>
    uint32_t for_each_ray(const SurfaceSample& s, size_t group_size, Pcg32& rng,
                          Trace&& trace) const;

private:
    const EmbreeScene& scene_;
    AoOptions options_;
};

template <class Trace>
uint32_t AoBaker::for_each_ray(const SurfaceSample& s, size_t group_size, Pcg32& rng,
                               Trace&& trace) const
{
    const uint32_t n = static_cast<uint32_t>(rays_per_sample(group_size));
    // A fresh random-digit scramble per sample keeps the estimate unbiased while the
    // points stay stratified (Kollig & Keller 2002 §3).
    const uint32_t scramble0 = rng.uniform_u32();
    const uint32_t scramble1 = rng.uniform_u32();

    // Orthonormal frame about N: Duff et al. 2017, "Building an Orthonormal Basis,
    // Revisited", JCGT 6(1), Listing 3.
    const Imath::V3f& N = s.N;
    const float sign = std::copysign(1.0f, N.z);
    const float a = -1.0f / (sign + N.z);
    const float b = N.x * N.y * a;
    const Imath::V3f T(1.0f + sign * N.x * N.x * a, sign * b, -sign * N.x);
    const Imath::V3f B(b, sign + N.y * N.y * a, -N.y);

    for (uint32_t i = 0; i < n; ++i) {
        const shading::Vec2 u(sobol02_to_float(sobol02_dimension0(i, scramble0)),
                              sobol02_to_float(sobol02_dimension1(i, scramble1)));
        // Cosine-weighted direction (Malley's method): pbrt-v4 §A.5.3
        const shading::Vec3 w = shading::sample_cosine_hemisphere(u);
        const Imath::V3f dir = w.x * T + w.y * B + w.z * N;
        // Below the facet: the surface itself blocks it.
        if (dir.dot(s.Ng) <= 0.0f)
            continue;
        trace(offset_ray_origin(s.P, s.Ng, dir), dir);
    }
    return n;
}

}  // namespace patina::texgen
