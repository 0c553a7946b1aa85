// Illuminants for fading (Kimmel et al. 2013, §5, §6.2): a relative spectral power
// distribution and the band over which a dose is counted. Under one illuminant the
// spectral irradiance is E(λ) = E * s(λ) / ∫_band s, so the state of a fading layer depends
// on the dose H = ∫ E dt (radiant exposure of the band, J/m^2) alone.
#pragma once

#include "texgen/fade/fading_simulation.h"
#include "texgen/fade/spectral_grid.h"

#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen::fade {

struct Illuminant {
    std::string name;
    TabulatedSpectrum relative;  ///< relative SPD; 0 outside its table
    double band_min_nm = 300.0;  ///< the dose counts the irradiance in [band_min, band_max]
    double band_max_nm = 830.0;
    std::string source;          ///< where the table comes from

    /// Spectral irradiance (W m^-2 nm^-1) at every grid wavelength for a band irradiance of
    /// `irradiance_w_m2`.
    std::vector<double> spectral_irradiance(const WavelengthGrid& grid,
                                            double irradiance_w_m2) const;
    /// Illumination from the top (and from below too when both_sides) at that irradiance.
    Illumination illumination(const WavelengthGrid& grid, double irradiance_w_m2,
                              bool both_sides = false) const;
};

/// "D65" (CIE 15:2004 table, 300-830 nm at 5 nm), "A" (Planck 2856 K, CIE 15:2004, over
/// 300-830 nm), "E" or "flat" (equal energy, 300-830 nm), "F1".."F12" (CIE 15:2004 = 15:2018
/// fluorescent lamps, 380-780 nm at 5 nm; the paper's lamp, figure 4, is a fluorescent
/// bulb) and the CIE 15:2018 LED illuminants "LED-B1".."LED-B5", "LED-BH1", "LED-RGB1",
/// "LED-V1", "LED-V2" (380-780 nm at 5 nm). The F and LED tables are read from
/// data/lamps/ (core/data_files.h). Case-insensitive; "fluorescent" = F11. Throws
/// std::runtime_error listing the names for any other.
Illuminant illuminant_by_name(const std::string& name);
/// The names illuminant_by_name knows, comma separated.
std::string known_illuminant_names();

/// An illuminant from a spectral CSV (core/spectrum_csv.h): column `column` ("" when the
/// file holds one spectrum); the band is the table's range. Throws std::runtime_error naming
/// the file (and line) for a broken file, a missing column or a negative value.
Illuminant illuminant_from_csv(const std::filesystem::path& file, const std::string& column);

/// An illuminant from text: a name illuminant_by_name knows, or "FILE[:COLUMN]" (a spectral
/// CSV: a path with a '/', a name ending in .csv, or an existing file).
Illuminant illuminant_from_text(const std::string& text);

/// An illuminant from a table (e.g. an exposure map's own spectrum): knots in nm and
/// relative values (zero outside the knots); the band is the table's range.
Illuminant illuminant_from_table(const std::string& name, std::vector<double> nm,
                                 std::vector<double> relative);

}  // namespace patina::texgen::fade
