// Spectra in a CSV file (docs/scene-format.md "Spectra from a CSV file"): a header row (the
// first column the wavelength in nm, then a name per column), then a row per wavelength,
// strictly increasing. Lines starting with '#' are comments (a source, units) and blank lines
// are skipped. Measured reflectances (a ColorChecker's patches), lamp SPDs and filter
// transmittances come in this form; the one reader of it.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace patina {

struct SpectrumCsv {
    std::filesystem::path file;
    std::vector<std::string> columns;          ///< the names after the wavelength's
    std::vector<double> lambda_nm;
    std::vector<std::vector<double>> values;   ///< per column, one value per wavelength

    /// The index of column `name` ("" = the only one); throws std::runtime_error naming the
    /// file and listing the columns when there is none (or "" names no single one).
    size_t column(const std::string& name) const;
};

/// Reads `file`. Throws std::runtime_error "file:line: what" for a row with another number
/// of fields, a field that is not a finite number, wavelengths that do not increase, or a
/// file without a header or rows.
SpectrumCsv read_spectrum_csv(const std::filesystem::path& file);

}  // namespace patina
