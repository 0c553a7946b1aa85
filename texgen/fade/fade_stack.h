// The fade stack: what `patina-texgen fade` writes and the spectral_km shader reads.
//
// A fade stack is a folder with three files:
//
//   fade.toml       what the stack holds and how it was made (below)
//   fade_table.exr  the material's state over dose under one illuminant (DoseTable): a
//                   scanline float EXR, one row per dose sample (row 0 = unexposed), one
//                   column per wavelength; channels (sorted, as OpenEXR stores them)
//                   R_bottom  reflectance of the pigment layer alone, lit from below
//                   R_top     reflectance of the pigment layer alone, lit from above
//                   R_total   reflectance of the layer over its substrate,
//                             R_top + T² ρ* / (1 − R_bottom ρ*)
//                   T         diffuse transmittance of the layer
//   dose.exr        tiled, mip-mapped float EXR (raw data), the exposure map's texels:
//                   channel 0 `coordinate` = the fractional row of fade_table.exr at the
//                   texel's dose, channel 1 `dose` = the dose in J/m²
//
// fade.toml:
//
//   [fade]       format = 1, generator, material, material_file, illuminant,
//                illuminant_band_nm = [min, max] (the band a dose counts), dose_units,
//                sublayers, both_sides
//   [table]      file, channels, rule (text), entries, knee_dose, max_dose, substeps,
//                max_interpolation_error (max |ΔR_total| at interval midpoints against a
//                table twice as fine), wavelength_nm = [...] (columns), dose = [...] (rows)
//   [substrate]  reflectance = [...] (ρ*, one per column)
//   [dose_map]   file, channels, resolution, min_dose, mean_dose, max_dose
//   [exposure]   files, channel, units, scale, duration_s, period_s: how doses were made,
//                dose = scale × value × (duration / period) for a J/m² map, or
//                scale × value × duration for a W/m² map, summed over the files (occluders
//                moved between exposures); no files: a uniform dose (--dose)
//
// The table coordinate of a dose H follows DoseTable's rule: u = ln(1 + H / H_0) / du, so
// linear interpolation between rows in the coordinate is DoseTable's own interpolation.
#pragma once

#include "texgen/fade/dose_table.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen::fade {

inline constexpr const char* kFadeToml = "fade.toml";
inline constexpr const char* kFadeTableFile = "fade_table.exr";
inline constexpr const char* kDoseMapFile = "dose.exr";

/// How the doses of a stack were made from its exposure maps (their doses add up; none: a
/// uniform dose).
struct ExposureSource {
    std::vector<std::filesystem::path> files;
    std::string channel = "exposure";
    std::string units = "J/m^2";   ///< "J/m^2" or "W/m^2"
    double scale = 1.0;            ///< dose per unit of the map
    double duration_s = 0.0;       ///< 0: the map's own period
    double period_s = 0.0;         ///< the period the map covers (0: unknown)
};

/// Everything fade.toml holds besides the table's numbers.
struct FadeStackInfo {
    std::string material;
    std::filesystem::path material_file;
    std::string illuminant;
    double band_min_nm = 0.0, band_max_nm = 0.0;
    std::vector<double> substrate;  ///< ρ* at every table wavelength
    double max_interpolation_error = 0.0;
    ExposureSource exposure;
    int width = 0, height = 0;  ///< dose map resolution
    double min_dose = 0.0, mean_dose = 0.0, max_dose = 0.0;
};

/// The fractional row of a table at a dose, u = ln(1 + H / H_0) / du clamped to the table
/// (DoseTable::locate as one number), with the rule's constants computed once.
class DoseRow {
public:
    explicit DoseRow(const DoseTable& table);
    double operator()(double dose_j_m2) const
    {
        const double u = std::log1p(std::max(dose_j_m2, 0.0) / knee_) * inv_du_;
        return std::min(u, last_);
    }

private:
    double knee_ = 1.0, inv_du_ = 0.0, last_ = 0.0;
};

/// The fractional row of `table` at `dose_j_m2`.
double table_coordinate(const DoseTable& table, double dose_j_m2);

/// The largest |R_total| difference, over wavelengths and interval midpoints, between
/// `table`'s interpolation and `fine`, a table of the same material with 2n − 1 entries
/// (so its odd entries fall on `table`'s interval midpoints).
double interpolation_error(const DoseTable& table, const DoseTable& fine);

/// Write fade_table.exr, dose.exr (interleaved (coordinate, dose, coverage) pixels, `width`
/// x `height`, top row first: make_dose_pixels) and, last, fade.toml into `dir` (created if
/// needed), each atomically. Throws std::runtime_error naming the file on failure.
void write_fade_stack(const std::filesystem::path& dir, const DoseTable& table,
                      const FadeStackInfo& info, const std::vector<float>& dose_pixels);

/// What a fade stack holds, read back (for plots and tests).
struct FadeStack {
    std::vector<double> wavelength_nm;
    std::vector<double> doses;                 ///< per row
    std::vector<double> substrate;             ///< per column
    std::vector<std::vector<double>> r_total;  ///< [row][column]
    std::vector<std::vector<double>> r_top, t, r_bottom;
    std::string material, illuminant;
    double max_interpolation_error = 0.0;
    std::filesystem::path dose_map;
};

/// Read `dir`/fade.toml and its table. Throws std::runtime_error naming the file and key.
FadeStack read_fade_stack(const std::filesystem::path& dir);

}  // namespace patina::texgen::fade
