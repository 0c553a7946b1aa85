// The fade stack (docs/file-formats.md "Fade stack"): what `patina-texgen fade` writes
// (texgen/fade/fade_stack.cpp) and the spectral_km shader reads (plugins/spectral_km). A
// folder of three files:
//
//   fade.toml       the description below (FadeDescription), written last
//   fade_table.exr  one row per dose sample (row 0 unexposed), one column per wavelength,
//                   float channels kFadeTableChannels (OpenEXR's sorted order, the order
//                   every reader gets them in): the pigment layer alone lit from below and
//                   from above, the layer over its substrate, the layer's transmittance
//   dose.exr        tiled, mip-mapped, raw: kDoseMapChannels, the fractional table row at
//                   the texel's dose, the dose in J/m², and the exposure map's coverage
//
// The table coordinate of a dose H is u = ln(1 + H / H_0) / du with du = ln(1 + H_max /
// H_0) / (entries − 1), so linear interpolation between rows in u is the table's own.
#pragma once

#include "formats/pixels.h"
#include "formats/texture_stack/texture_stack.h"

#include <toml++/toml.h>

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace patina::formats {

/// The layout this build writes and reads ([fade] format); a newer one is refused.
inline constexpr int kFadeFormatVersion = 1;

inline constexpr const char* kFadeDescription = "fade.toml";
inline constexpr const char* kFadeTableFile = "fade_table.exr";
inline constexpr const char* kDoseMapFile = "dose.exr";
inline constexpr std::array<const char*, 4> kFadeTableChannels = {"R_bottom", "R_top",
                                                                  "R_total", "T"};
inline constexpr std::array<const char*, 3> kDoseMapChannels = {"coordinate", "dose",
                                                                kCoverageChannel};

/// How the doses were made from exposure maps (their doses add up; none: a uniform dose).
struct FadeExposure {
    std::vector<std::filesystem::path> files;
    std::string channel = "exposure";
    std::string units = "J/m^2";  ///< "J/m^2" or "W/m^2"
    double scale = 1.0;           ///< dose per unit of the map
    double duration_s = 0.0;      ///< 0: the map's own period
    double period_s = 0.0;        ///< the period the map covers (0: unknown)
};

/// fade.toml.
struct FadeDescription {
    int format = kFadeFormatVersion;
    std::string generator;
    // [fade]
    std::string material, material_file, illuminant;
    double band_min_nm = 0.0, band_max_nm = 0.0;  ///< the band a dose counts
    int sublayers = 0;
    bool both_sides = false;
    // [table]
    std::string table_file = kFadeTableFile;
    int entries = 0, substeps = 0;
    double knee_dose = 0.0, max_dose = 0.0;     ///< H_0, H_max (J/m²)
    double max_interpolation_error = 0.0;       ///< max |ΔR_total| at interval midpoints
    std::vector<double> wavelength_nm;          ///< per column, increasing
    std::vector<double> doses;                  ///< per row, increasing from 0
    // [substrate]
    std::vector<double> substrate;              ///< ρ* per column, in [0, 1]
    // [dose_map]
    std::string dose_map_file = kDoseMapFile;
    int width = 0, height = 0;
    double min_dose = 0.0, mean_dose = 0.0, max_dose_in_map = 0.0;
    // [exposure]
    FadeExposure exposure;

    /// The table and dose map as paths, relative ones resolved against `folder`.
    std::filesystem::path table_path(const std::filesystem::path& folder) const;
    std::filesystem::path dose_map_path(const std::filesystem::path& folder) const;
};

/// Read `path` (fade.toml, or the stack folder holding it). Throws std::runtime_error
/// "file:line:column: what" for a syntax error, a newer or missing format, and a missing or
/// malformed key (wavelengths not increasing, a substrate value per wavelength outside
/// [0, 1], a table or dose map without a file).
FadeDescription read_fade_description(const std::filesystem::path& path);

/// fade.toml's tables, with a comment line first.
std::string fade_description_text(const FadeDescription& description);

/// fade_table.exr: the pigment layer at every dose sample (row) and wavelength (column),
/// row-major (entry = row * columns + column).
struct FadeTable {
    int rows = 0, columns = 0;
    std::vector<float> r_bottom, r_top, r_total, t;
};

/// The table's pixels as fade_table.exr holds them: `columns` x `rows`, the channels
/// kFadeTableChannels, the material and illuminant of `description` in the header.
Pixels fade_table_pixels(const FadeTable& table, const FadeDescription& description);

/// The table of the stack described by `description` in `folder`, read through `reader`.
/// Throws naming the file when its size is not the description's (wavelengths x doses), a
/// channel is missing, or an entry is no passive layer (R, T >= 0; R + T <= 1 from either
/// side, to 1e-4).
FadeTable read_fade_table(const PixelReader& reader, const FadeDescription& description,
                          const std::filesystem::path& folder);

/// dose.exr's pixels: per texel, interleaved, the table coordinate (the fractional row of
/// its dose), the dose (J/m²) and the exposure map's coverage (kDoseMapChannels).
Pixels dose_map_pixels(int width, int height, std::vector<float> coordinate_dose_coverage,
                       const FadeDescription& description);

/// The table coordinate of every texel of the stack's dose map (row-major), read through
/// `reader`; `width` and `height` receive its size. Throws naming the file for a missing
/// channel or a coordinate that is not finite.
std::vector<float> read_dose_coordinates(const PixelReader& reader,
                                         const FadeDescription& description,
                                         const std::filesystem::path& folder, int* width,
                                         int* height);

}  // namespace patina::formats
