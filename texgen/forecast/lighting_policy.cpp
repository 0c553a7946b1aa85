#include "texgen/forecast/lighting_policy.h"

#include "core/spectrum_csv.h"
#include "texgen/sun/date_time.h"
#include "texgen/sun/epw.h"
#include "texgen/sun/solar_position.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen::forecast {

namespace fs = std::filesystem;

namespace {

constexpr double kSecondsPerHour = 3600.0;
constexpr double kHoursPerYear = 365.0 * 24.0;

/// ∫ over the band of s(λ) (× filter) at 1 nm.
double band_integral(const fade::Illuminant& lamp, const UvFilter* filter)
{
    const int n = std::max(1, static_cast<int>(std::ceil(lamp.band_max_nm - lamp.band_min_nm)));
    const double h = (lamp.band_max_nm - lamp.band_min_nm) / n;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
        const double nm = lamp.band_min_nm + i * h;
        sum += (i == 0 || i == n ? 0.5 : 1.0) * h * lamp.relative.at(nm) *
               (filter ? filter->at(nm) : 1.0);
    }
    return sum;
}

struct DaylightYear {
    double band_j_m2 = 0.0;  // window plane, broadband × kSolarShareInBand, per year
    double lit_hours = 0.0;
};

// The window plane's daylight over the file, scaled to 365 days (Wh/m^2 -> J/m^2).
DaylightYear daylight_year(const DaylightSource& d)
{
    const EpwFile file = read_epw(d.epw);
    SolarSite site;
    site.latitude_deg = file.location.latitude_deg;
    site.longitude_deg = file.location.longitude_deg;
    site.elevation_m = file.location.elevation_m;
    const double interval_h = file.interval_minutes() / 60.0;
    // Reda & Andreas Eq. 47 measures the surface's azimuth from south, positive to the west.
    const double rotation = d.facing_azimuth_deg - 180.0;
    DaylightYear year;
    double hours = 0.0;
    for (const EpwRecord& r : file.records) {
        require_irradiance(file, r);
        hours += interval_h;
        const double jd_end = julian_day(record_end(file, r), file.location.timezone_hours);
        const SolarPosition sun = solar_position(jd_end - 0.5 * interval_h / 24.0, site);
        double direct = 0.0;
        if (sun.zenith_deg < 90.0) {
            const double cos_i = std::cos(incidence_angle_deg(sun, 90.0, rotation) * M_PI / 180.0);
            direct = r.dni_wh * std::max(0.0, cos_i);
        }
        // A vertical plane sees half the (isotropic) sky and half the ground.
        const double wh = direct + 0.5 * r.dhi_wh + 0.5 * d.ground_albedo * r.ghi_wh;
        year.band_j_m2 += wh * kSecondsPerHour * kSolarShareInBand;
        if (r.ghi_wh > 0.0)
            year.lit_hours += interval_h;
    }
    if (!(hours > 0.0))
        throw std::runtime_error(d.epw.string() + ": no data rows");
    year.band_j_m2 *= kHoursPerYear / hours;
    year.lit_hours *= kHoursPerYear / hours;
    return year;
}

}  // namespace

double UvFilter::at(double nm) const
{
    if (!transmittance.empty())
        return transmittance.at(nm);
    if (cutoff_nm > 0.0)
        return nm >= cutoff_nm ? 1.0 : 0.0;
    return 1.0;
}

double filter_share(const fade::Illuminant& lamp, const UvFilter& filter)
{
    if (!filter.active())
        return 1.0;
    return band_integral(lamp, &filter) / band_integral(lamp, nullptr);
}

fade::Illuminant filtered(const fade::Illuminant& lamp, const UvFilter& filter)
{
    if (!filter.active())
        return lamp;
    std::vector<double> nm, value;
    const int first = static_cast<int>(std::floor(lamp.band_min_nm));
    const int last = static_cast<int>(std::ceil(lamp.band_max_nm));
    for (int l = first; l <= last; ++l) {
        nm.push_back(l);
        value.push_back(lamp.relative.at(l) * filter.at(l));
    }
    fade::Illuminant out = fade::illuminant_from_table(lamp.name + " through " + filter.label,
                                                       std::move(nm), std::move(value));
    out.band_min_nm = lamp.band_min_nm;
    out.band_max_nm = lamp.band_max_nm;
    out.source = lamp.source + "; filter " + filter.label;
    return out;
}

UvFilter parse_uv_filter(const std::string& text, const std::string& what)
{
    UvFilter f;
    if (text.empty() || text == "none")
        return f;
    size_t used = 0;
    double cutoff = 0.0;
    try {
        cutoff = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used == text.size()) {
        if (!(cutoff > 0.0 && cutoff < 1000.0))
            throw std::runtime_error(fmt::format("{} {}: a cut-off wavelength in nm (e.g. 400) "
                                                 "must lie in 0-1000", what, text));
        f.cutoff_nm = cutoff;
        f.label = fmt::format("cut-off {:g} nm", cutoff);
        return f;
    }
    const size_t colon = text.rfind(':');
    const fs::path file = colon == std::string::npos ? fs::path(text) : fs::path(text.substr(0, colon));
    const std::string column = colon == std::string::npos ? "" : text.substr(colon + 1);
    if (!fs::exists(file))
        throw std::runtime_error(fmt::format("{} {}: neither a cut-off wavelength nor an existing "
                                             "transmittance file", what, text));
    const SpectrumCsv csv = read_spectrum_csv(file);
    const size_t c = csv.column(column);
    for (size_t i = 0; i < csv.lambda_nm.size(); ++i)
        if (!(csv.values[c][i] >= 0.0 && csv.values[c][i] <= 1.0))
            throw std::runtime_error(fmt::format(
                "{} {}: transmittance {} at {} nm is outside 0-1", what, text, csv.values[c][i],
                csv.lambda_nm[i]));
    f.transmittance.nm = csv.lambda_nm;
    f.transmittance.value = csv.values[c];
    f.label = file.filename().string() + (column.empty() ? "" : ":" + column);
    return f;
}

PolicyExposure policy_exposure(const LightingPolicy& p)
{
    auto fail = [&](const std::string& what) {
        throw std::runtime_error(fmt::format("policy '{}': {}", p.name, what));
    };
    const int sources = (p.daylight ? 1 : 0) + (p.exposure ? 1 : 0);
    if (sources > 1)
        fail("daylight and an exposure map exclude each other");
    if (!(p.hours_per_day >= 0.0 && p.hours_per_day <= 24.0))
        fail(fmt::format("hours a day must be in 0-24, got {}", p.hours_per_day));
    if (!(p.days_per_year >= 0.0 && p.days_per_year <= 366.0))
        fail(fmt::format("days a year must be in 0-366, got {}", p.days_per_year));
    if (!(p.lux >= 0.0) || !std::isfinite(p.lux))
        fail(fmt::format("lux must be a finite number >= 0, got {}", p.lux));

    PolicyExposure e;
    e.spectrum = filtered(p.lamp, p.filter);
    e.photometry = lamp_photometry(e.spectrum);
    if (p.daylight) {
        const DaylightSource& d = *p.daylight;
        if (!(d.share >= 0.0 && d.share <= 1.0))
            fail(fmt::format("daylight share must be in 0-1, got {}", d.share));
        const DaylightYear y = daylight_year(d);
        // The glazing takes its part of the band's energy.
        e.dose_per_year_j_m2 = y.band_j_m2 * filter_share(p.lamp, p.filter) * d.share;
        e.lit_hours_per_year = y.lit_hours;
    } else if (p.exposure) {
        const fade::ExposureMap map = fade::read_exposure_map(p.exposure->map, p.exposure->channel);
        const double factor = fade::dose_factor(map, p.exposure->scale, 365.0 * 86400.0);
        double sum = 0.0, covered = 0.0;
        for (size_t i = 0; i < map.values.size(); ++i) {
            if (map.coverage[i] > 0.0f) {
                sum += map.values[i];
                covered += 1.0;
            }
        }
        if (covered == 0.0)
            fail(p.exposure->map.string() + ": no covered texel");
        e.dose_per_year_j_m2 = factor * sum / covered;
        e.lit_hours_per_year = p.hours_per_day * p.days_per_year;
    } else {
        // The lux is the lamp's, as designed; a filter in front takes away its part
        e.lit_hours_per_year = p.hours_per_day * p.days_per_year;
        const double band_w_m2 = p.lux / lamp_photometry(p.lamp).luminous_efficacy_lm_per_w;
        e.dose_per_year_j_m2 = band_w_m2 * filter_share(p.lamp, p.filter) * e.lit_hours_per_year * kSecondsPerHour;
    }
    e.lux_hours_per_year =
        e.dose_per_year_j_m2 / kSecondsPerHour * e.photometry.luminous_efficacy_lm_per_w;
    return e;
}

}  // namespace patina::texgen::forecast
