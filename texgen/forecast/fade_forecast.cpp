#include "texgen/forecast/fade_forecast.h"

#include "core/spectrum.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace patina::texgen::forecast {

ColourMeter::ColourMeter(const fade::WavelengthGrid& grid, const fade::Illuminant& view)
    : view_(view.name)
{
    const std::vector<double> w = grid.trapezoid_weights();
    const std::vector<double> s = grid.sample(view.relative);
    white_ = Imath::V3d(0.0);
    for (size_t i = 0; i < grid.size(); ++i) {
        const float nm = static_cast<float>(grid.nm[i]);
        wx_.push_back(s[i] * cie_x(nm) * w[i]);
        wy_.push_back(s[i] * cie_y(nm) * w[i]);
        wz_.push_back(s[i] * cie_z(nm) * w[i]);
        white_ += Imath::V3d(wx_.back(), wy_.back(), wz_.back());
    }
    if (!(white_.y > 0.0))
        throw std::runtime_error("viewing illuminant '" + view.name +
                                 "' has no light within the solver's wavelengths");
}

Imath::V3d ColourMeter::xyz(std::span<const double> reflectance) const
{
    Imath::V3d xyz(0.0);
    for (size_t i = 0; i < wx_.size(); ++i)
        xyz += Imath::V3d(wx_[i], wy_[i], wz_[i]) * reflectance[i];
    return xyz / white_.y;
}

Lab ColourMeter::lab(std::span<const double> reflectance) const
{
    return lab_of_xyz(xyz(reflectance));
}

namespace {

fade::DoseTable make_table(const fade::FadeMaterial& material, const fade::Illuminant& spectrum,
                           const fade::WavelengthGrid& grid, const ForecastOptions& o,
                           double max_dose)
{
    fade::DoseTableOptions t;
    t.max_dose_j_m2 = max_dose;
    // Four decades of logarithmic spacing: half the entries in the top two decades, where
    // the search looks for the crossing
    t.knee_dose_j_m2 = max_dose * 1e-4;
    t.entries = o.entries;
    t.sublayers = o.sublayers;
    t.both_sides = o.both_sides;
    return fade::DoseTable::build(material, spectrum, grid, t);
}

}  // namespace

double threshold_dose(const fade::FadeMaterial& material, const fade::Illuminant& spectrum,
                      const fade::WavelengthGrid& grid, const ColourMeter& meter,
                      const ForecastOptions& o)
{
    if (!(o.threshold_de2000 > 0.0))
        throw std::runtime_error(fmt::format("threshold ΔE00 must be > 0, got {}",
                                             o.threshold_de2000));
    for (double max_dose = 100.0; max_dose <= kMaxSearchDose * 1.0001; max_dose *= 100.0) {
        const fade::DoseTable table = make_table(material, spectrum, grid, o, max_dose);
        const Lab unexposed = meter.lab(table.spectra(0).reflectance);
        auto delta_e = [&](double dose) {
            return delta_e2000(unexposed, meter.lab(table.spectra_at(dose).reflectance));
        };
        const std::vector<double>& doses = table.doses();
        for (size_t k = 1; k < doses.size(); ++k) {
            if (delta_e2000(unexposed, meter.lab(table.spectra(k).reflectance)) <
                o.threshold_de2000)
                continue;
            // Bisection within the crossing interval (the table's own interpolation)
            double lo = doses[k - 1], hi = doses[k];
            for (int i = 0; i < 60 && hi - lo > 1e-9 * hi; ++i) {
                const double mid = 0.5 * (lo + hi);
                (delta_e(mid) >= o.threshold_de2000 ? hi : lo) = mid;
            }
            return hi;
        }
    }
    return kNever;
}

DeltaECurve::DeltaECurve(const fade::DoseTable& table, const ColourMeter& meter, int samples)
{
    const fade::DoseTableOptions& t = table.options();
    knee_ = t.knee_dose_j_m2;
    const double u_max = std::log1p(t.max_dose_j_m2 / knee_);
    inv_du_ = (samples - 1) / u_max;
    last_ = samples - 1;
    const Lab unexposed = meter.lab(table.spectra(0).reflectance);
    values_.resize(static_cast<size_t>(samples));
    for (int i = 0; i < samples; ++i) {
        const double dose = knee_ * std::expm1(u_max * i / (samples - 1));
        values_[i] = delta_e2000(unexposed, meter.lab(table.spectra_at(dose).reflectance));
    }
}

PolicyForecast forecast_policy(const fade::FadeMaterial& material, const LightingPolicy& policy,
                               const fade::WavelengthGrid& grid, const ColourMeter& meter,
                               const ForecastOptions& o)
{
    if (!(o.horizon_years > 0.0) || o.curve_points < 2)
        throw std::runtime_error("forecast: the horizon must be > 0 years with >= 2 points");
    PolicyForecast f;
    f.policy = policy.name;
    f.exposure = policy_exposure(policy);
    f.threshold_dose_j_m2 = threshold_dose(material, f.exposure.spectrum, grid, meter, o);
    const double per_year = f.exposure.dose_per_year_j_m2;
    if (std::isfinite(f.threshold_dose_j_m2)) {
        f.threshold_lux_hours = f.threshold_dose_j_m2 / 3600.0 *
                                f.exposure.photometry.luminous_efficacy_lm_per_w;
        if (per_year > 0.0)
            f.years_to_threshold = f.threshold_dose_j_m2 / per_year;
    }
    f.years.resize(static_cast<size_t>(o.curve_points));
    f.delta_e.assign(f.years.size(), 0.0);
    for (size_t i = 0; i < f.years.size(); ++i)
        f.years[i] = o.log_years
                         ? o.horizon_years *
                               std::pow(10.0, -4.0 + 4.0 * static_cast<double>(i) / (o.curve_points - 1))
                         : o.horizon_years * static_cast<double>(i) / (o.curve_points - 1);
    if (per_year > 0.0) {
        const fade::DoseTable table =
            make_table(material, f.exposure.spectrum, grid, o, per_year * o.horizon_years);
        const Lab unexposed = meter.lab(table.spectra(0).reflectance);
        for (size_t i = 0; i < f.years.size(); ++i)
            f.delta_e[i] = delta_e2000(
                unexposed, meter.lab(table.spectra_at(per_year * f.years[i]).reflectance));
    }
    return f;
}

}  // namespace patina::texgen::forecast
