// `patina-texgen exposure`: the solar energy (or mean irradiance) each texel receives over a
// period, direct sun plus CIE sky, shadowed by the scene; from the clear-sky model at a site
// or from an EnergyPlus weather file.
#include "texgen/cli/commands.h"

#include "core/cli_errors.h"
#include "core/spectrum.h"
#include "texgen/cli/bake_command.h"
#include "texgen/exposure/exposure_baker.h"
#include "texgen/exposure/exposure_period.h"
#include "texgen/exposure/sky_accumulation.h"
#include "texgen/sun/cie_sky.h"
#include "texgen/sun/epw.h"

#include <fmt/format.h>

#include <cstdio>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>

namespace patina::texgen {

namespace {

struct ExposureArguments {
    CommonBakeOptions common;
    std::optional<double> latitude, longitude, timezone, elevation;
    std::optional<std::string> start, end;
    double step_minutes = 10.0;
    std::string sky = "clear";
    std::filesystem::path epw;
    bool average = false;
    bool components = false;
    double sun_bins_deg = 0.5;
    int sky_samples = 256;
    float max_distance = std::numeric_limits<float>::infinity();
    double linke_turbidity = 3.0;
    std::optional<double> delta_t;
    std::optional<double> pressure;
    double temperature = 15.0;
};

// The illuminant of daylight for fading: CIE D65 at 5 nm, "nm:value" pairs (relative SPD,
// 100 at 560 nm, CIE 15:2004).
std::string d65_spectrum_text()
{
    std::string s;
    for (int i = 0; i < kCieSamples; ++i) {
        const float nm = kLambdaMinNm + kCieStepNm * static_cast<float>(i);
        s += fmt::format("{}{:g}:{:g}", s.empty() ? "" : " ", nm, d65(nm));
    }
    return s;
}

ExposurePeriod make_period(const ExposureArguments& a)
{
    if (!a.epw.empty()) {
        for (const auto& [given, name] :
             {std::pair{a.latitude.has_value(), "--latitude"},
              std::pair{a.longitude.has_value(), "--longitude"},
              std::pair{a.timezone.has_value(), "--timezone"},
              std::pair{a.elevation.has_value(), "--elevation"},
              std::pair{a.pressure.has_value(), "--pressure"}})
            if (given)
                throw std::runtime_error(std::string(name) +
                                         " cannot be combined with --epw: the site comes "
                                         "from the weather file's LOCATION line");
        const EpwFile file = read_epw(a.epw);
        EpwPeriodOptions o;
        if (a.start)
            o.start = parse_date_time(*a.start, "--start");
        if (a.end)
            o.end = parse_date_time(*a.end, "--end");
        o.step_minutes = a.step_minutes;
        o.delta_t_s = a.delta_t;
        return epw_period(file, o);
    }
    for (const auto& [given, name] :
         {std::pair{a.latitude.has_value(), "--latitude"},
          std::pair{a.longitude.has_value(), "--longitude"},
          std::pair{a.timezone.has_value(), "--timezone"},
          std::pair{a.start.has_value(), "--start"}, std::pair{a.end.has_value(), "--end"}})
        if (!given)
            throw std::runtime_error(std::string(name) +
                                     " is required without --epw (the clear-sky model needs "
                                     "the site and the period)");
    ClearSkyPeriodOptions o;
    o.site.latitude_deg = *a.latitude;
    o.site.longitude_deg = *a.longitude;
    o.site.elevation_m = a.elevation.value_or(0.0);
    o.site.pressure_mbar = a.pressure ? *a.pressure : standard_pressure_mbar(o.site.elevation_m);
    o.site.temperature_c = a.temperature;
    o.site.delta_t_s = a.delta_t;
    o.timezone_hours = *a.timezone;
    o.start = parse_date_time(*a.start, "--start");
    o.end = parse_date_time(*a.end, "--end");
    o.step_minutes = a.step_minutes;
    o.clear_sky.linke_turbidity = a.linke_turbidity;
    return clear_sky_period(o);
}

void run_exposure(const ExposureArguments& a)
{
    const CieSky sky_model = parse_cie_sky(a.sky, "--sky");
    const ExposurePeriod period = make_period(a);
    AccumulationOptions accumulation;
    accumulation.sun_bin_deg = a.sun_bins_deg;
    accumulation.sky_cells = a.sky_samples;
    accumulation.progress = !a.common.quiet;
    const ExposureSky sky = accumulate_exposure(period, sky_model, accumulation);
    if (!a.common.quiet)
        std::fprintf(stderr,
                     "exposure: %zu time steps, %.4g MJ/m^2 direct normal, %.4g MJ/m^2 diffuse "
                     "horizontal -> %zu sun bins + %d sky cells (at most %zu rays per sample)\n",
                     sky.steps, sky.direct_normal * 1e-6,
                     sky.diffuse_horizontal * 1e-6, sky.sun_bins.size(),
                     sky.non_empty_sky_cells,
                     sky.sun_bins.size() + static_cast<size_t>(sky.non_empty_sky_cells));

    ExposureOptions options;
    options.average = a.average;
    options.components = a.components;
    options.max_distance = a.max_distance;

    MapDescription map;
    map.name = "exposure";
    map.units = a.average ? "W/m^2" : "J/m^2";
    map.description =
        a.average ? "mean solar irradiance over the period, direct sun plus sky, shadowed by "
                    "the scene"
                  : "solar radiant exposure over the period, direct sun plus sky, shadowed by "
                    "the scene";
    map.baker = "exposure";
    map.parameters = period.parameters;
    Metadata& m = map.parameters;
    m.push_back({"sky", sky_model.name});
    m.push_back({"sun_bins_deg", fmt::format("{}", a.sun_bins_deg)});
    m.push_back({"sun_bins", static_cast<int>(sky.sun_bins.size())});
    m.push_back({"sun_diameter_deg", fmt::format("{}", options.sun_diameter_deg)});
    m.push_back({"sky_cells", sky.sky_resolution * sky.sky_resolution});
    m.push_back({"max_distance", fmt::format("{}", a.max_distance)});
    m.push_back({"average", a.average ? 1 : 0});
    m.push_back({"period_seconds", fmt::format("{}", sky.duration_s)});
    m.push_back({"direct_normal_j_m2", fmt::format("{}", sky.direct_normal)});
    m.push_back({"diffuse_horizontal_j_m2", fmt::format("{}", sky.diffuse_horizontal)});
    m.push_back({"ground_reflection", std::string("none")});
    m.push_back({"illuminant", std::string("D65")});
    m.push_back({"illuminant_spectrum", d65_spectrum_text()});

    run_bake(a.common,
             [&sky, options](const BakeScene& s) {
                 return std::make_unique<ExposureBaker>(s.scene, sky, options);
             },
             map);
}

}  // namespace

void register_exposure_command(CLI::App& app)
{
    auto a = std::make_shared<ExposureArguments>();
    CLI::App* cmd = app.add_subcommand(
        "exposure",
        "bake solar exposure: direct sun (NREL SPA) plus CIE sky over a period, from the "
        "Ineichen-Perez clear-sky model at a site or from an EnergyPlus EPW weather file, "
        "shadowed by the scene (channel 'exposure' J/m^2, or 'irradiance' W/m^2 with --average)");
    add_common_bake_options(*cmd, a->common);
    cmd->add_option("--latitude", a->latitude, "site latitude, degrees north (without --epw)")
        ->check(CLI::Range(-90.0, 90.0));
    cmd->add_option("--longitude", a->longitude, "site longitude, degrees east (without --epw)")
        ->check(CLI::Range(-180.0, 180.0));
    cmd->add_option("--elevation", a->elevation, "site elevation, m (without --epw; default 0)")
        ->check(CLI::Range(-500.0, 9000.0));
    cmd->add_option("--timezone", a->timezone,
                    "hours east of Greenwich of --start and --end (without --epw)")
        ->check(CLI::Range(-14.0, 14.0));
    cmd->add_option("--start", a->start,
                    "period start, local standard time, YYYY-MM-DD[THH:MM[:SS]] (with --epw: "
                    "optional, the year is ignored)");
    cmd->add_option("--end", a->end, "period end (exclusive), same form as --start");
    cmd->add_option("--step-minutes", a->step_minutes,
                    "time step of the sun's path (with --epw: sub-steps of each row)")
        ->capture_default_str()->check(CLI::Range(0.1, 1440.0));
    cmd->add_option("--sky", a->sky,
                    "sky luminance distribution: clear (CIE type 12), overcast (CIE traditional "
                    "overcast, Moon-Spencer), or a CIE S 011 type 1-15")
        ->capture_default_str();
    cmd->add_option("--epw", a->epw,
                    "EnergyPlus weather file: hourly direct normal and diffuse horizontal "
                    "radiation replace the clear-sky model; the site comes from the file")
        ->check(CLI::ExistingFile);
    cmd->add_flag("--average", a->average,
                  "write the mean irradiance over the period (W/m^2, channel 'irradiance')");
    cmd->add_flag("--components", a->components,
                  "also write the 'direct' and 'sky' parts as channels");
    cmd->add_option("--sun-bins-deg", a->sun_bins_deg,
                    "angular size of the sun-direction bins; one shadow ray per bin and sample "
                    "(larger bins bake long periods faster, with softer shadows)")
        ->capture_default_str()->check(CLI::Range(0.01, 10.0));
    cmd->add_option("--sky-samples", a->sky_samples,
                    "sky cells of equal solid angle, one stratified shadow ray each per sample")
        ->capture_default_str()->check(CLI::Range(4, 65536));
    cmd->add_option("--max-distance", a->max_distance,
                    "ignore occluders farther than this along a shadow ray (m; default: no limit)")
        ->check(patina::positive);
    cmd->add_option("--linke-turbidity", a->linke_turbidity,
                    "clear-sky Linke turbidity (2 very clean, 3 typical, 5+ hazy)")
        ->capture_default_str()->check(CLI::Range(1.0, 10.0));
    cmd->add_option("--delta-t", a->delta_t,
                    "TT - UT in seconds for the solar position (default: from the date, "
                    "Espenak & Meeus 2006)")
        ->check(CLI::Range(-8000.0, 8000.0));
    cmd->add_option("--pressure", a->pressure,
                    "mean pressure, mbar, for refraction (default: standard atmosphere at the "
                    "elevation; with --epw each row's own)")
        ->check(CLI::Range(100.0, 1200.0));
    cmd->add_option("--temperature", a->temperature, "mean temperature, C, for refraction")
        ->capture_default_str()->check(CLI::Range(-90.0, 60.0));
    cmd->callback([a] { run_exposure(*a); });
}

}  // namespace patina::texgen
