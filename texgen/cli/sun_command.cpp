// `patina-texgen sun`: the sun's position and the clear-sky irradiance for a date, time and
// place, one "name: value unit" line each, to check the model against other tools (e.g.
// NREL's SPA calculator or pvlib).
#include "texgen/cli/commands.h"

#include "texgen/exposure/exposure_period.h"
#include "texgen/sun/clear_sky.h"
#include "texgen/sun/date_time.h"
#include "texgen/sun/solar_position.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

namespace patina::texgen {

namespace {

struct SunArguments {
    std::string date;
    std::optional<std::string> time;  ///< default 12:00 unless --date holds a time
    double timezone = 0.0;
    SolarSite site;
    std::optional<double> pressure;
    double linke_turbidity = 3.0;
    std::optional<double> slope;
    double surface_azimuth = 0.0;
};

void run_sun(const SunArguments& a)
{
    DateTime local = parse_date_time(a.date, "--date");
    const bool date_has_time = a.date.size() > 10;
    if (a.time && date_has_time)
        throw std::runtime_error("--date " + a.date + " already holds a time; drop --time " +
                                 *a.time);
    if (!date_has_time)
        parse_time_of_day(a.time ? *a.time : std::string("12:00"), "--time", local);
    SolarSite site = a.site;
    site.pressure_mbar = a.pressure ? *a.pressure : standard_pressure_mbar(site.elevation_m);
    const SolarPosition p = solar_position(julian_day(local, a.timezone), site);
    const double i0 = extraterrestrial_normal_irradiance(p.earth_radius_vector_au);
    ClearSkyParameters sky;
    sky.linke_turbidity = a.linke_turbidity;
    sky.elevation_m = site.elevation_m;
    const ClearSkyIrradiance c = ineichen_perez(p.zenith_deg, i0, sky);
    // The hour angle as usually quoted: negative in the morning, positive after noon.
    const double hour_angle = std::remainder(p.hour_angle_deg, 360.0);

    std::string out;
    out += fmt::format("julian_day: {:.6f} d\n", p.julian_day);
    out += fmt::format("delta_t: {:.2f} s\n", p.delta_t_s);
    out += fmt::format("zenith: {:.5f} deg\n", p.zenith_deg);
    out += fmt::format("azimuth: {:.5f} deg\n", p.azimuth_deg);
    out += fmt::format("elevation: {:.5f} deg\n", p.elevation_deg);
    out += fmt::format("declination: {:.5f} deg\n", p.declination_deg);
    out += fmt::format("hour_angle: {:.5f} deg\n", hour_angle);
    out += fmt::format("earth_sun_distance: {:.7f} AU\n", p.earth_radius_vector_au);
    out += fmt::format("extraterrestrial_normal_irradiance: {:.2f} W/m^2\n", i0);
    out += fmt::format("air_mass: {:.4f} 1\n", relative_air_mass(p.zenith_deg));
    out += fmt::format("clear_sky_dni: {:.2f} W/m^2\n", c.dni);
    out += fmt::format("clear_sky_dhi: {:.2f} W/m^2\n", c.dhi);
    out += fmt::format("clear_sky_ghi: {:.2f} W/m^2\n", c.ghi);
    if (a.slope)
        out += fmt::format("incidence: {:.5f} deg\n",
                           incidence_angle_deg(p, *a.slope, a.surface_azimuth));
    std::fputs(out.c_str(), stdout);
    std::fflush(stdout);
}

}  // namespace

void register_sun_command(CLI::App& app)
{
    auto a = std::make_shared<SunArguments>();
    CLI::App* cmd = app.add_subcommand(
        "sun", "print the sun's position (NREL SPA) and the clear-sky irradiance "
               "(Ineichen-Perez) for a date, time and place, one 'name: value unit' per line");
    cmd->add_option("--date", a->date, "date, YYYY-MM-DD (optionally with THH:MM[:SS])")
        ->required();
    cmd->add_option("--time", a->time, "local standard time of day, HH:MM[:SS] (default 12:00)");
    cmd->add_option("--timezone", a->timezone,
                    "hours east of Greenwich of the local time (e.g. -7 for MST)")
        ->capture_default_str()->check(CLI::Range(-14.0, 14.0));
    cmd->add_option("--latitude", a->site.latitude_deg, "degrees, north positive")
        ->required()->check(CLI::Range(-90.0, 90.0));
    cmd->add_option("--longitude", a->site.longitude_deg, "degrees, east positive")
        ->required()->check(CLI::Range(-180.0, 180.0));
    cmd->add_option("--elevation", a->site.elevation_m, "metres above sea level")
        ->capture_default_str()->check(CLI::Range(-500.0, 9000.0));
    cmd->add_option("--pressure", a->pressure,
                    "mean local pressure, mbar, for refraction (default: standard atmosphere "
                    "at the elevation)")
        ->check(CLI::Range(100.0, 1200.0));
    cmd->add_option("--temperature", a->site.temperature_c,
                    "mean local temperature, C, for refraction")
        ->capture_default_str()->check(CLI::Range(-90.0, 60.0));
    cmd->add_option("--delta-t", a->site.delta_t_s,
                    "TT - UT, seconds (default: from the date, Espenak & Meeus 2006)")
        ->check(CLI::Range(-8000.0, 8000.0));
    cmd->add_option("--linke-turbidity", a->linke_turbidity,
                    "Linke turbidity of the clear sky (2 very clean, 3 typical, 5+ hazy)")
        ->capture_default_str()->check(CLI::Range(1.0, 10.0));
    cmd->add_option("--slope", a->slope,
                    "also print the incidence angle on a surface of this tilt (deg)")
        ->check(CLI::Range(0.0, 180.0));
    cmd->add_option("--surface-azimuth", a->surface_azimuth,
                    "with --slope: the surface's azimuth rotation from south, west positive (deg)")
        ->capture_default_str()->check(CLI::Range(-360.0, 360.0));
    cmd->callback([a] { run_sun(*a); });
}

}  // namespace patina::texgen
