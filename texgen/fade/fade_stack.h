// The fade stack: what `patina-texgen fade` writes and the spectral_km shader reads.
//
// The files and the description's keys are formats/fade_stack/fade_stack.h (docs/file-formats.md
// "Fade stack"); this writes them from a DoseTable and reads them back for plots and tests.
#pragma once

#include "formats/fade_stack/fade_stack.h"
#include "texgen/fade/dose_table.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen::fade {

inline constexpr const char* kFadeToml = formats::kFadeDescription;
using formats::kDoseMapFile;
using formats::kFadeTableFile;

/// How the doses of a stack were made from its exposure maps (their doses add up; none: a
/// uniform dose): fade.toml's [exposure].
using ExposureSource = formats::FadeExposure;

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
