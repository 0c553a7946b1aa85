// The deposit baker: where airborne deposits (soot, dust, salts) settle, from accessibility
// combined with visibility to deposit sources. Dorsey et al. 1999 §6: "The deposit maps were
// computed with accessibility [Miller 1994] combined with visibility to area deposit sources".
//
// At a sample (P, N, uv):
//
//     visibility = min(1, sum over sources of strength * F_source)     (source_visibility.h)
//     hidden     = (1 - A)^accessibility_power
//     deposit    = clamp(accessibility_weight * hidden + visibility_weight * visibility, 0, 1)
//                  (combine = sum, the default), or
//     deposit    = clamp(hidden * visibility, 0, 1)                    (combine = product)
//
// A is the accessibility in [0, 1] (1: open, 0: deep in a crevice), read from an
// accessibility map at the sample's uv (channel "accessibility" of the `accessibility`
// baker) or, without a map, estimated inline as the unoccluded fraction of access_rays
// cosine-weighted rays of length access_distance (ambient occlusion, a cheap stand-in for
// Miller's tangent-sphere accessibility). Deposits collect where surfaces are hidden from
// cleaning (low accessibility) and where they see the sources.
#pragma once

#include "texgen/bake/sample_baker.h"
#include "texgen/deposit/deposit_sources.h"
#include "texgen/stack/surface_map.h"

#include <Imath/ImathBox.h>

#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace patina::texgen {

struct DepositParameters {
    std::vector<DepositSource> sources;
    int rays = 16; ///< shadow rays per texel per source (split over samples)
    float max_distance = std::numeric_limits<float>::infinity(); ///< directional sources, m

    std::filesystem::path accessibility_map; ///< optional; "<UDIM>" for a tile set
    std::string accessibility_channel = "accessibility";
    int access_rays = 16;              ///< inline estimate: rays per texel
    float access_distance = 0.0f;      ///< inline estimate: ray length, m; 0: 1/10 of the
                                       ///< scene's bounding-box diagonal
    float accessibility_power = 1.0f;  ///< >= 0
    float accessibility_weight = 0.5f; ///< >= 0 (combine = sum)
    float visibility_weight = 0.5f;    ///< >= 0 (combine = sum)
    enum class Combine { Sum, Product };
    Combine combine = Combine::Sum;

    /// Throw std::runtime_error naming the parameter as its command-line option when a
    /// value is out of range, or when no source is given although visibility is used.
    void validate() const;
    /// True when the accessibility term enters the value (no rays or map reads otherwise).
    bool uses_accessibility() const
    {
        return combine == Combine::Product || accessibility_weight > 0.0f;
    }
    bool uses_visibility() const { return combine == Combine::Product || visibility_weight > 0.0f; }
};

class DepositBaker : public SampleBaker {
public:
    /// `bounds`: the scene's world bounds (for the default access_distance). Opens the
    /// accessibility map now, so a bad map fails before the bake. `ocio_config` empty: the
    /// default config.
    DepositBaker(const EmbreeScene& scene, const Imath::Box3f& bounds,
                 const DepositParameters& parameters,
                 const std::filesystem::path& ocio_config = {});

    std::vector<std::string> channels() const override { return {"deposit"}; }
    size_t rays_per_sample(size_t group_size) const override;
    void evaluate(const SurfaceSample& s, size_t group_size, Pcg32& rng, float* out) const override;

    /// The inline estimate's ray length after the default is resolved.
    float access_distance() const { return access_distance_; }
    Metadata resolved_parameters() const override
    {
        return {{"access_distance", access_distance_}};
    }

    /// The accessibility A at `s` (map or inline estimate) and the source visibility, the
    /// two inputs of the formula.
    float accessibility(const SurfaceSample& s, size_t group_size, Pcg32& rng) const;
    float visibility(const SurfaceSample& s, size_t group_size, Pcg32& rng) const;

private:
    int split(int per_texel, size_t group_size) const;

    const EmbreeScene& scene_;
    DepositParameters p_;
    float access_distance_ = 0.0f;
    std::unique_ptr<SurfaceMap> accessibility_;
};

} // namespace patina::texgen
