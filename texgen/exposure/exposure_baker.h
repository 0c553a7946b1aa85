// Exposure: the solar energy a surface receives over a period, direct sun plus sky, with
// shadows from the scene (Dorsey & Hanrahan 1996 §5.2-5.3: "a precomputed exposure map,
// that gives the average irradiance due to the sun and sky received by that part of the
// surface").
//
// Per sample with shading normal N (world, +y up), from an ExposureSky accumulated once:
//   direct = sum over sun bins b of max(0, N . W_b) V(s_b)
//     W_b = sum of DNI dt s over the bin's steps, s_b its mean direction, V = 1 when a
//     shadow ray towards s_b (jittered over the sun's disc, 0.53 deg across) escapes;
//   sky = sum over sky cells c of R_c max(0, N . w_c) V(w_c) Omega_c
//     R_c the cell's radiance-time, w_c a direction jittered uniformly within the cell
//     (one stratified ray per cell), Omega_c = 2 pi / n^2.
// Ground-reflected light is not included (no albedo term).
//
// relative = (direct + sky) / H, H the same period's exposure of unobstructed horizontal
// ground: sum over sun bins of max(0, W_b . up) plus sum over sky cells of R_c cos(theta_c)
// Omega_c at the cells' centres. 1 is "as much as open flat ground", whatever the site,
// period or units: the channel patina scripts use (docs/texgen-exposure.md).
#pragma once

#include "texgen/bake/sample_baker.h"
#include "texgen/exposure/sky_accumulation.h"

#include <limits>

namespace patina::texgen {

struct ExposureOptions {
    bool average = false;     ///< W/m^2 over the period instead of J/m^2
    bool components = false;  ///< also the "direct" and "sky" channels
    float max_distance = std::numeric_limits<float>::infinity();  ///< shadow ray length
    float sun_diameter_deg = 0.53f;  ///< shadow rays are jittered over this disc; 0: none
};

class ExposureBaker final : public SampleBaker {
public:
    /// Keeps references to `scene` and `sky`, which must outlive the baker. Throws
    /// std::runtime_error naming the option for max_distance <= 0, an average over an empty
    /// period, or a negative sun diameter.
    ExposureBaker(const EmbreeScene& scene, const ExposureSky& sky, const ExposureOptions& options);

    /// {"exposure"} (J/m^2) or {"irradiance"} (W/m^2), then "direct" and "sky" with
    /// components, then "relative" (to unobstructed horizontal ground, dimensionless).
    std::vector<std::string> channels() const override;
    /// One ray per sun bin and per non-empty sky cell (an upper bound: directions below
    /// the surface cast none).
    size_t rays_per_sample(size_t group_size) const override;
    void evaluate(const SurfaceSample& s, size_t group_size, Pcg32& rng,
                  float* out) const override;

    /// H, the exposure of unobstructed horizontal ground over the period (J/m^2).
    double horizontal_exposure() const { return horizontal_; }

private:
    const EmbreeScene& scene_;
    const ExposureSky& sky_;
    ExposureOptions options_;
    double scale_ = 1.0;        // 1, or 1 / duration for --average
    double horizontal_ = 0.0;   // H: unobstructed horizontal ground's exposure, J/m^2
    float cos_sun_radius_ = 1.0f;
};

}  // namespace patina::texgen
