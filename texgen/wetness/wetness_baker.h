// The wetness baker: how wet a surface point gets under rain, from a rain direction with an
// angular spread, visibility to the rain, an inclination law, drying by exposure and water
// collecting near the base.
//
// Sources: Dorsey et al. 1999 §6, "wetness maps were computed with visibility to a
// directional rain source ... the rain direction was from above, causing the wetness map to
// be stronger in the horizontal areas"; Dorsey & Hanrahan 1996 §5.2-5.3, "the wetness is
// controlled by a precomputed exposure map ... and a simple function that decreases the
// average wetness of inclined surfaces" (inclined areas facing the sun are dryer), and "another
// simple procedure increases the wetness along the base of the statue where water is likely
// to accumulate" (the "base" curve).
//
// The value at a sample (P, N) with rain travelling along the directions d_i of the cone of
// half-angle `spread` about the rain direction d, up axis U:
//
//     rain     = sum_i V_i max(0, -N.d_i) / sum_i (d.d_i)          (directional_catch)
//     incline  = max(0, N.U)^inclination_power
//     base     = base_amount * max(0, 1 - (P.U - base_level) / base_height)   (base_height > 0)
//     dry      = 1 - drying * clamp(E(uv) / E_scale, 0, 1)          (with an exposure map)
//     wetness  = clamp((rain * incline + base) * dry, 0, 1)
//
// V_i: 1 if a shadow ray from P towards -d_i leaves on the front of the geometric normal and
// meets nothing within max_distance. E(uv): the exposure map read at the sample's uv;
// E_scale: `exposure_scale`, or the map's largest value when that is 0. base_level: the
// lowest point of the baked mesh along U unless given.
//
// Closed forms: an open surface facing the rain has rain = 1 for any spread; under vertical
// rain without spread an open horizontal surface has wetness 1, a vertical wall 0 (catch),
// a plane tilted by theta cos(theta)^(1 + inclination_power).
#pragma once

#include "core/mesh.h"
#include "texgen/bake/sample_baker.h"
#include "texgen/wetness/directional_catch.h"
#include "texgen/stack/surface_map.h"

#include <Imath/ImathVec.h>

#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <string>

namespace patina::texgen {

struct WetnessParameters {
    Imath::V3f rain_direction{0.0f, -1.0f, 0.0f}; ///< the direction rain travels
    float spread_deg = 0.0f;                      ///< cone half-angle, [0, 90)
    Imath::V3f up{0.0f, 1.0f, 0.0f};              ///< the scene's up axis
    float inclination_power = 1.0f;               ///< >= 0; 0 turns the inclination law off
    int rays = 16;                                ///< rain rays per texel (split over samples)
    float max_distance = std::numeric_limits<float>::infinity(); ///< shadow-ray length, m

    std::filesystem::path exposure_map; ///< optional; "<UDIM>" for a tile set
    std::string exposure_channel;       ///< empty: "exposure", else "irradiance"
    float drying = 1.0f;                ///< in [0, 1]: wetness left at the most exposed point
    float exposure_scale = 0.0f;        ///< E_scale; 0: the map's maximum

    float base_height = 0.0f;        ///< m; 0: no base accumulation
    float base_amount = 1.0f;        ///< extra wetness at the base level, >= 0
    std::optional<float> base_level; ///< coordinate along U; default: the mesh's lowest

    /// Throw std::runtime_error naming the parameter (as its command-line option) when a
    /// value is out of range.
    void validate() const;
};

class WetnessBaker : public SampleBaker {
public:
    /// `target`: the baked mesh (for the default base level). Opens the exposure map now,
    /// so a bad map fails before the bake. `ocio_config` empty: the default config.
    WetnessBaker(const EmbreeScene& scene, const TriangleMesh& target,
                 const WetnessParameters& parameters,
                 const std::filesystem::path& ocio_config = {});

    std::vector<std::string> channels() const override { return {"wetness"}; }
    size_t rays_per_sample(size_t group_size) const override;
    void evaluate(const SurfaceSample& s, size_t group_size, Pcg32& rng, float* out) const override;

    /// The values the formula uses after defaults are resolved (for the map's parameters).
    float base_level() const { return base_level_; }
    float exposure_scale() const { return exposure_scale_; }
    const SurfaceMap* exposure() const { return exposure_.get(); }
    Metadata resolved_parameters() const override;

private:
    const EmbreeScene& scene_;
    WetnessParameters p_;
    DirectionCone cone_;
    Imath::V3f up_;
    float base_level_ = 0.0f;
    float exposure_scale_ = 0.0f;
    std::unique_ptr<SurfaceMap> exposure_;
};

/// The lowest coordinate of `mesh` along the unit axis `up`.
float lowest_along(const TriangleMesh& mesh, const Imath::V3f& up);

} // namespace patina::texgen
