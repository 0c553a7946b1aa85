#include "texgen/exposure/exposure_period.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace patina::texgen {

namespace {

constexpr double kMinutesPerDay = 1440.0;

// An ordering key for month, day and time of day (not a duration): later in the year is
// larger, whatever the year.
double calendar_key(int month, int day, double minutes)
{
    return (month * 32.0 + day) * kMinutesPerDay + minutes;
}

double calendar_key(const DateTime& t)
{
    return calendar_key(t.month, t.day, t.hour * 60.0 + t.minute + t.second / 60.0);
}

std::string number(double v)
{
    return fmt::format("{}", v);
}

void add_site_parameters(Metadata& m, const SolarSite& site, double timezone_hours)
{
    m.push_back({"latitude_deg", number(site.latitude_deg)});
    m.push_back({"longitude_deg", number(site.longitude_deg)});
    m.push_back({"elevation_m", number(site.elevation_m)});
    m.push_back({"timezone_hours", number(timezone_hours)});
    m.push_back({"delta_t_s", site.delta_t_s ? number(*site.delta_t_s)
                                             : std::string("Espenak & Meeus 2006 at each step's date")});
    m.push_back({"solar_position", std::string("NREL SPA (Reda & Andreas 2004)")});
}

}  // namespace

double standard_pressure_mbar(double elevation_m)
{
    return 1013.25 * std::pow(1.0 - 2.25577e-5 * elevation_m, 5.25588);
}

ExposurePeriod clear_sky_period(const ClearSkyPeriodOptions& o)
{
    if (!(o.step_minutes > 0.0) || !std::isfinite(o.step_minutes))
        throw std::runtime_error("--step-minutes must be positive, got " + number(o.step_minutes));
    const double jd_start = julian_day(o.start, o.timezone_hours);
    const double jd_end = julian_day(o.end, o.timezone_hours);
    if (!(jd_end > jd_start))
        throw std::runtime_error("--end (" + format_date_time(o.end) +
                                 ") must come after --start (" + format_date_time(o.start) + ")");
    ClearSkyParameters sky = o.clear_sky;
    sky.elevation_m = o.site.elevation_m;

    ExposurePeriod period;
    period.duration_s = (jd_end - jd_start) * 86400.0;
    const double step_days = o.step_minutes / kMinutesPerDay;
    const double steps = std::ceil((jd_end - jd_start) / step_days - 1e-9);
    if (steps > kMaxPeriodSteps)
        throw std::runtime_error(fmt::format(
            "--step-minutes {}: the period from {} to {} would have {:.3g} steps, more than "
            "the limit of {:.0e}; take a longer step",
            number(o.step_minutes), format_date_time(o.start), format_date_time(o.end), steps,
            kMaxPeriodSteps));
    const auto count = static_cast<long long>(steps);
    period.step_bound = static_cast<size_t>(count);
    const SolarSite site = o.site;
    period.for_each_step = [=](const StepSink& sink) {
        for (long long i = 0; i < count; ++i) {
            // Midpoint rule; the last step ends at jd_end.
            const double t0 = jd_start + static_cast<double>(i) * step_days;
            const double t1 = std::min(jd_end, t0 + step_days);
            const double mid = 0.5 * (t0 + t1);
            const SolarPosition sun = solar_position(mid, site);
            const ClearSkyIrradiance c = ineichen_perez(
                sun.zenith_deg, extraterrestrial_normal_irradiance(sun.earth_radius_vector_au),
                sky);
            // A step without light is visited too (its irradiance 0), so that a consumer
            // polls for cancellation through a polar night as well.
            const bool lit = c.ghi > 0.0;
            sink({mid, (t1 - t0) * 86400.0, sun_direction(sun.zenith_deg, sun.azimuth_deg),
                  lit ? c.dni : 0.0, lit ? c.dhi : 0.0});
        }
    };

    Metadata& m = period.parameters;
    m.push_back({"source", std::string("clear-sky model")});
    add_site_parameters(m, o.site, o.timezone_hours);
    m.push_back({"start", format_date_time(o.start)});
    m.push_back({"end", format_date_time(o.end)});
    m.push_back({"step_minutes", number(o.step_minutes)});
    m.push_back({"clear_sky_model",
                 std::string("Ineichen & Perez 2002, Kasten & Young 1989 air mass")});
    m.push_back({"linke_turbidity", number(sky.linke_turbidity)});
    m.push_back({"pressure_mbar", number(o.site.pressure_mbar)});
    m.push_back({"temperature_c", number(o.site.temperature_c)});
    m.push_back({"solar_constant_w_m2", number(kSolarConstant)});
    return period;
}

ExposurePeriod epw_period(const EpwFile& file, const EpwPeriodOptions& o)
{
    if (!(o.step_minutes > 0.0) || !std::isfinite(o.step_minutes))
        throw std::runtime_error("--step-minutes must be positive, got " + number(o.step_minutes));
    const EpwLocation& loc = file.location;
    SolarSite site;
    site.latitude_deg = loc.latitude_deg;
    site.longitude_deg = loc.longitude_deg;
    site.elevation_m = loc.elevation_m;
    site.delta_t_s = o.delta_t_s;
    const double default_pressure = standard_pressure_mbar(loc.elevation_m);

    constexpr double kInfinity = std::numeric_limits<double>::infinity();
    const double start_key = o.start ? calendar_key(*o.start) : -kInfinity;
    const double end_key = o.end ? calendar_key(*o.end) : kInfinity;
    const bool wraps = start_key > end_key;

    const double interval = file.interval_minutes();
    const int substeps = std::max(1, static_cast<int>(std::lround(interval / o.step_minutes)));
    const double sub_days = interval / substeps / kMinutesPerDay;

    // A weather file's steps are bounded by the file (8760 rows a year): kept in memory.
    ExposurePeriod period;
    std::vector<IrradianceStep> all_steps;
    size_t rows = 0;
    std::vector<SolarPosition> suns(substeps);
    for (const EpwRecord& r : file.records) {
        const DateTime end = record_end(file, r);
        const double e = calendar_key(end);
        const double s = e - interval;
        const bool in_range = wraps ? (s >= start_key || e <= end_key)
                                    : (s >= start_key && e <= end_key);
        if (!in_range)
            continue;
        require_irradiance(file, r);
        ++rows;
        period.duration_s += interval * 60.0;

        // Refraction from the row's own air when the file has it (dictionary: 999999 Pa
        // and 99.9 C are missing values).
        site.pressure_mbar = (r.pressure_pa > 31000.0 && r.pressure_pa < 120000.0)
                                 ? r.pressure_pa / 100.0
                                 : default_pressure;
        site.temperature_c = (r.dry_bulb_c > -70.0 && r.dry_bulb_c < 70.0) ? r.dry_bulb_c : 15.0;

        const double jd_end = julian_day(end, loc.timezone_hours);
        const double jd_start = jd_end - interval / kMinutesPerDay;
        int up = 0;
        for (int k = 0; k < substeps; ++k) {
            suns[k] = solar_position(jd_start + (k + 0.5) * sub_days, site);
            up += suns[k].zenith_deg < 90.0 ? 1 : 0;
        }
        // Wh/m^2 over the interval -> J/m^2, then the mean irradiance of each sub-step.
        const double direct_j = r.dni_wh * 3600.0;
        const double diffuse_j = r.dhi_wh * 3600.0;
        const double sub_s = sub_days * 86400.0;
        if (up == 0)
            period.dropped_direct += direct_j;
        for (int k = 0; k < substeps; ++k) {
            const bool sun_up = suns[k].zenith_deg < 90.0;
            IrradianceStep step;
            step.jd_ut = jd_start + (k + 0.5) * sub_days;
            step.duration_s = sub_s;
            step.sun = sun_direction(suns[k].zenith_deg, suns[k].azimuth_deg);
            step.dni = sun_up ? direct_j / (up * sub_s) : 0.0;
            step.dhi = diffuse_j / (substeps * sub_s);
            if (step.dni > 0.0 || step.dhi > 0.0)
                all_steps.push_back(step);
        }
    }
    if (rows == 0)
        throw std::runtime_error(file.path + ": no data row lies in the requested date range");
    period.step_bound = all_steps.size();
    period.for_each_step = [steps = std::move(all_steps)](const StepSink& sink) {
        for (const IrradianceStep& step : steps)
            sink(step);
    };

    Metadata& m = period.parameters;
    m.push_back({"source", std::string("EPW weather file")});
    m.push_back({"epw_file", file.path});
    m.push_back({"epw_location", loc.city + ", " + loc.state + ", " + loc.country + " (" +
                                     loc.source + " " + loc.wmo + ")"});
    add_site_parameters(m, site, loc.timezone_hours);
    m.push_back({"start", o.start ? format_date_time(*o.start) : std::string("file start")});
    m.push_back({"end", o.end ? format_date_time(*o.end) : std::string("file end")});
    m.push_back({"epw_rows", static_cast<int>(rows)});
    m.push_back({"step_minutes", number(interval / substeps)});
    m.push_back({"epw_direct_dropped_j_m2", number(period.dropped_direct)});
    return period;
}

}  // namespace patina::texgen
