// A lighting policy: how an object is lit on display, in the terms a museum states it (a
// lamp, lux at the object, hours a day, days a year, a UV filter) or as daylight through a
// window from a weather file, or the mean of an exposure map. What the fading model needs
// from it is the spectrum that reaches the object and the radiant exposure of its band per
// year (policy_exposure).
//
// Reciprocity: the fading model's state under one spectrum depends on the dose alone
// (texgen/fade/dose_table.h), so a policy is summed into a dose per year, dose = lux ×
// hours, and the years to a fade scale as 1 / (lux × hours × days).
#pragma once

#include "texgen/fade/fade_map.h"
#include "texgen/fade/illuminant.h"
#include "texgen/forecast/lamp_photometry.h"

#include <filesystem>
#include <optional>
#include <string>

namespace patina::texgen::forecast {

/// Transmittance of a UV filter (or glazing) before the object: an ideal cut-off (0 below
/// `cutoff_nm`, 1 from it on), or a measured curve (0-1, linear between its knots, held
/// beyond them). Neither: no filter.
struct UvFilter {
    std::string label = "none";
    double cutoff_nm = 0.0;
    fade::TabulatedSpectrum transmittance;
    bool active() const { return cutoff_nm > 0.0 || !transmittance.empty(); }
    double at(double nm) const;
};

/// Daylight on the object through a window, from an EnergyPlus weather file: the window
/// plane's irradiance (sun on it, half the diffuse sky, half the ground's reflection),
/// times `share`, the part of it that reaches the object (1 = in the window, facing out).
struct DaylightSource {
    std::filesystem::path epw;
    double facing_azimuth_deg = 0.0;  ///< the window's outward normal, clockwise from north
    double share = 1.0;
    double ground_albedo = 0.2;
};

/// The mean dose of an exposure map's covered texels (`patina-texgen exposure`).
struct ExposureMapSource {
    std::filesystem::path map;
    std::string channel;     ///< "" = exposure, else irradiance
    double scale = 1.0;      ///< band dose per unit of the map (fade --scale)
};

struct LightingPolicy {
    std::string name;
    fade::Illuminant lamp;   ///< the source's relative spectrum (daylight: D65)
    UvFilter filter;
    /// Illuminance of the lamp at the object without the filter, as a lighting plan states
    /// it; the filter takes away its part (a 400 nm cut-off: under 1 % of the lux).
    double lux = 0.0;
    double hours_per_day = 8.0;
    double days_per_year = 365.0;
    std::optional<DaylightSource> daylight;
    std::optional<ExposureMapSource> exposure;
};

/// Broadband solar energy (the weather file's Wh/m^2) that falls within the D65 band
/// 300-830 nm: 0.575 for a 5778 K black body, the share docs/fading.md uses (--scale 0.58).
inline constexpr double kSolarShareInBand = 0.575;

/// What reaches the object in a year.
struct PolicyExposure {
    fade::Illuminant spectrum;        ///< lamp × filter, over the lamp's band
    LampPhotometry photometry;        ///< of `spectrum`
    double lux_hours_per_year = 0.0;  ///< at the object, after the filter
    double dose_per_year_j_m2 = 0.0;  ///< radiant exposure of the band (the model's dose)
    double lit_hours_per_year = 0.0;  ///< hours with light (daylight: hours the file has light)
};

/// Checks a policy (lux ≥ 0, 0 ≤ hours ≤ 24, 0 ≤ days ≤ 366, filter within 0-1, a source)
/// and sums its year. Throws std::runtime_error naming the policy and the field.
PolicyExposure policy_exposure(const LightingPolicy& policy);

/// The share of the lamp's band energy `filter` lets through (1 without a filter).
double filter_share(const fade::Illuminant& lamp, const UvFilter& filter);

/// `lamp` seen through `filter`, tabulated at 1 nm over the lamp's band.
fade::Illuminant filtered(const fade::Illuminant& lamp, const UvFilter& filter);

/// A filter from text: a cut-off in nm ("400"), "none", or "FILE[:COLUMN]" (a spectral CSV
/// of transmittance 0-1). Throws std::runtime_error naming `what` (the option or key).
UvFilter parse_uv_filter(const std::string& text, const std::string& what);

/// A lamp from text: fade::illuminant_from_text.
inline fade::Illuminant parse_lamp(const std::string& text)
{
    return fade::illuminant_from_text(text);
}

}  // namespace patina::texgen::forecast
