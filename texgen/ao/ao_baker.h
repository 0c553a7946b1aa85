// Ambient occlusion: the fraction of the cosine-weighted hemisphere about the shading normal
// from which a ray escapes the scene (within a maximum distance). 1 on an open plane, 0 at
// the bottom of a closed box. A comparison baker next to Miller's accessibility.
#pragma once

#include "texgen/bake/sample_baker.h"

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

private:
    const EmbreeScene& scene_;
    AoOptions options_;
};

}  // namespace patina::texgen
