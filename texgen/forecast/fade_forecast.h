// Forecasts of a fading material under lighting policies: the colour difference CIEDE2000
// against the unexposed material over the years, and the dose and years to a just-noticeable
// fade (a threshold ΔE00: 1.0 by default; 1.6 is ISO 105-A02's grey-scale step 4, the "just
// noticeable fade" of the conservation literature).
//
// The fading model (Kimmel et al. 2013, texgen/fade/) is reciprocal under one spectrum: its
// state depends on the dose of the spectrum's band alone (dose_table.h). So the dose to the
// threshold is a property of the material and the spectrum reaching it, found once, and the
// years of a policy are that dose over the policy's dose per year.
#pragma once

#include "core/color_difference.h"
#include "texgen/fade/dose_table.h"
#include "texgen/forecast/lighting_policy.h"

#include <limits>
#include <span>
#include <string>
#include <vector>

namespace patina::texgen::forecast {

/// CIELAB of reflectance spectra seen under a viewing illuminant with the CIE 1931 2°
/// observer, relative to the perfect white diffuser under the same illuminant (CIE 15:2018
/// §7). Sums over the solver's grid with its trapezoid weights.
class ColourMeter {
public:
    ColourMeter(const fade::WavelengthGrid& grid, const fade::Illuminant& view);
    Lab lab(std::span<const double> reflectance) const;
    /// CIE XYZ of a reflectance, the perfect white diffuser at Y = 1.
    Imath::V3d xyz(std::span<const double> reflectance) const;
    /// CIELAB of an XYZ on that scale.
    Lab lab_of_xyz(const Imath::V3d& xyz) const { return xyz_to_lab(xyz, white_ / white_.y); }
    const std::string& view_name() const { return view_; }

private:
    std::vector<double> wx_, wy_, wz_;  // S(λ) x̄ w, per grid wavelength
    Imath::V3d white_;
    std::string view_;
};

struct ForecastOptions {
    double threshold_de2000 = 1.0;
    double horizon_years = 100.0;     ///< the curve's span
    int curve_points = 201;           ///< samples of the curve, 0 to the horizon
    /// Samples evenly in log10 years over four decades up to the horizon (the first at
    /// horizon / 10^4), for policies years apart; else evenly from 0.
    bool log_years = false;
    int entries = 96;                 ///< dose table entries
    int sublayers = 100;
    bool both_sides = false;
};

inline constexpr double kNever = std::numeric_limits<double>::infinity();

/// The largest dose the threshold search tries (J/m^2): 1e14, some 10^5 years of 50 lx
/// of a typical lamp; a material that has not reached the threshold by then never does.
inline constexpr double kMaxSearchDose = 1e14;

/// The smallest dose (band J/m^2) at which the material's ΔE00 under `meter` first reaches
/// `threshold`, or kNever. Tables of growing range (×100 from 100 J/m^2) until one holds a
/// crossing, then bisection of the table's interpolation within the crossing interval.
double threshold_dose(const fade::FadeMaterial& material, const fade::Illuminant& spectrum,
                      const fade::WavelengthGrid& grid, const ColourMeter& meter,
                      const ForecastOptions& options);

/// ΔE00 against the unexposed material as a function of dose, tabulated finely in the dose
/// table's own coordinate u = ln(1 + H / H_0) so a map of any size costs one table and a
/// lookup per texel.
class DeltaECurve {
public:
    DeltaECurve(const fade::DoseTable& table, const ColourMeter& meter, int samples = 4096);
    double operator()(double dose_j_m2) const
    {
        const double u = std::log1p(std::max(dose_j_m2, 0.0) / knee_) * inv_du_;
        if (u >= last_)
            return values_.back();
        const size_t i = static_cast<size_t>(u);
        const double w = u - static_cast<double>(i);
        return values_[i] + w * (values_[i + 1] - values_[i]);
    }

private:
    std::vector<double> values_;
    double knee_ = 1.0, inv_du_ = 0.0, last_ = 0.0;
};

struct PolicyForecast {
    std::string policy;
    PolicyExposure exposure;
    double threshold_dose_j_m2 = kNever;  ///< band J/m^2
    double threshold_lux_hours = kNever;  ///< the same dose in lux hours of this spectrum
    double years_to_threshold = kNever;
    std::vector<double> years, delta_e;   ///< the curve
};

/// The forecast of `material` under `policy`. Throws std::runtime_error for a bad policy
/// (naming it) or material.
PolicyForecast forecast_policy(const fade::FadeMaterial& material, const LightingPolicy& policy,
                               const fade::WavelengthGrid& grid, const ColourMeter& meter,
                               const ForecastOptions& options);

}  // namespace patina::texgen::forecast
