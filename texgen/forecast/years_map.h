// Per-texel forecasts (docs/forecast.md "Maps"): from an exposure map of an object as it is
// shown (the exposure baker in its room, with its windows and lamps), the years until each
// texel reaches the threshold ΔE00 and the ΔE00 each texel has after N years, so a curator
// sees where the object fades first.
//
// Both are one table lookup per texel: the threshold dose is the material's (one number per
// spectrum, fade_forecast.h), and ΔE00 against dose is one DeltaECurve.
#pragma once

#include "core/image_io.h"
#include "texgen/fade/fade_map.h"
#include "texgen/forecast/fade_forecast.h"

#include <vector>

namespace patina::texgen::forecast {

/// Years a texel that gets no light is given: a million years stands for "never" in a map
/// (a renderer or viewer would refuse an infinity).
inline constexpr double kNeverYears = 1e6;

struct YearsMaps {
    int width = 0, height = 0;
    std::vector<float> years;     ///< years to the threshold, capped at kNeverYears
    std::vector<float> delta_e;   ///< ΔE00 after `after_years`
    double min_years = 0.0, median_years = 0.0;  ///< over covered texels
    double max_delta_e = 0.0;
};

/// Per texel with dose per year d = dose_per_year_factor × value: years = threshold / d,
/// ΔE00 = curve(d × after_years). Parallel over rows (TBB); the result does not depend on
/// the thread count. Throws std::runtime_error naming the first texel (x, y) whose value is
/// NaN, infinite or negative.
YearsMaps make_years_maps(const fade::ExposureMap& map, double dose_per_year_factor,
                          double threshold_dose_j_m2, const DeltaECurve& curve,
                          double after_years);

/// The texture-stack map of a forecast: `fade_forecast.exr`.
inline constexpr const char* kForecastMap = "fade_forecast";

/// Write `fade_forecast.exr` into `dir` (tiled, mip-mapped, float; channels
/// years_to_threshold, delta_e_after, then the exposure map's `coverage` as its coverage
/// channel) and record it in the folder's stack.toml (a texture-stack map, baker "forecast",
/// `parameters` in its header).
void write_years_maps(const std::filesystem::path& dir, const YearsMaps& maps,
                      const std::vector<float>& coverage, const Metadata& parameters,
                      double threshold_de2000, double after_years);

/// The two channels as pictures for people, in the perceptually uniform "inferno" map
/// (display values, 3 per texel): years bright where the object fades first (log10 years
/// from the map's longest, dark, to its shortest, bright, over at least a decade), ΔE00 from
/// 0 (dark) to the map's largest or 3 × the threshold, whichever is more (bright). Texels
/// the exposure map does not cover are grey.
struct FalseColours {
    std::vector<float> years, delta_e;
    double log10_years_dark = 0.0, log10_years_bright = 0.0, delta_e_bright = 0.0;
};
FalseColours false_colours(const YearsMaps& maps, const std::vector<float>& coverage,
                           double threshold_de2000);

/// `fade_forecast_years.png` and `fade_forecast_delta_e.png` (8-bit) of false_colours.
void write_years_previews(const std::filesystem::path& dir, const YearsMaps& maps,
                          const std::vector<float>& coverage, double threshold_de2000);

}  // namespace patina::texgen::forecast
