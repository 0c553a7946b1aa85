// Fade maps: from an exposure map (the texgen `exposure` baker's J/m² or W/m² per texel) to
// the per-texel dose and its row in a material's dose table, the dose map of a fade stack.
//
// Under one illuminant spectrum the state of a fading layer depends on the dose alone
// (dose_table.h), so a map of any size costs one table (a few ms) plus one lookup per
// texel, done in parallel with TBB.
#pragma once

#include "texgen/fade/dose_table.h"

#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen::fade {

/// One channel of an exposure map and what its header says about it.
struct ExposureMap {
    std::filesystem::path file;
    int width = 0, height = 0;
    std::string channel;
    std::string units;              ///< "J/m^2" (exposure) or "W/m^2" (mean irradiance)
    std::vector<float> values;      ///< width x height, top row first
    /// Per texel, the map's coverage channel (stack/map_output.h: 1 baked, 0 empty); all 1
    /// for a map without one.
    std::vector<float> coverage;
    double period_s = 0.0;          ///< patina:period_seconds, 0 when absent
    std::string illuminant;         ///< patina:illuminant, "" when absent
    std::vector<double> illuminant_nm, illuminant_value;  ///< patina:illuminant_spectrum
};

/// Read `channel` of an exposure map ("" = `exposure` or else `irradiance`, whichever the
/// file has). Units: the header's patina:units, else from the channel name (`exposure`
/// J/m², `irradiance` W/m²). Throws std::runtime_error naming the file when it is missing,
/// has no such channel, or has units other than J/m² or W/m².
ExposureMap read_exposure_map(const std::filesystem::path& file, const std::string& channel);

/// Dose per unit of the map: scale × (duration / period) for J/m² (the map's period repeated
/// or cut; duration 0 = the period itself), scale × duration for W/m² (duration required).
/// Throws std::runtime_error saying which option is missing.
double dose_factor(const ExposureMap& map, double scale, double duration_s);

/// Per texel (coordinate, dose, coverage): dose = factor × value, coordinate = its
/// fractional row in `table`, coverage the exposure map's; parallel over rows. Throws std::runtime_error naming the first texel
/// (x, y) that is NaN, infinite or negative. `progress` (may be null) is called with the
/// number of rows done, from worker threads.
std::vector<float> make_dose_pixels(const ExposureMap& map, const DoseTable& table,
                                    double factor, void (*progress)(size_t rows, void*) = nullptr,
                                    void* progress_data = nullptr);

/// Minimum, mean and maximum dose over the map's texels.
struct DoseRange {
    double min = 0.0, mean = 0.0, max = 0.0;
};
/// The dose range factor × value; throws std::runtime_error naming the first texel (x, y)
/// that is NaN, infinite or negative.
DoseRange scan_doses(const ExposureMap& map, double factor);

}  // namespace patina::texgen::fade
