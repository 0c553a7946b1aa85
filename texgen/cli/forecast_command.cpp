// `patina-texgen forecast`: how long can this be shown, under this light, before anyone sees
// the difference? A fading material (the library's, or one of the ISO Blue Wool categories)
// under one or more lighting policies -> ΔE00 over the years, the years to a just-noticeable
// fade, the lamps' photometry, a side-by-side table (docs/forecast.md); and, from an exposure
// map, the same per texel.
#include "texgen/cli/commands.h"
#include "texgen/cli/fade_options.h"

#include "core/cancel.h"
#include "core/image_io.h"
#include "core/output_transaction.h"
#include "texgen/fade/fade_map.h"
#include "texgen/fade/fade_material.h"
#include "texgen/fade/fade_plot.h"
#include "texgen/forecast/fade_forecast.h"
#include "texgen/forecast/policy_file.h"
#include "texgen/forecast/years_map.h"
#include "texgen/stack/map_output.h"

#include <fmt/format.h>
#include <tbb/global_control.h>

#include <chrono>
#include <cmath>
#include <memory>
#include <optional>
#include <sstream>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

struct ForecastCliOptions {
    FadeMaterialChoice material;
    fs::path policies;
    // One policy from options
    LampPolicyChoice one;  ///< --lamp, --lux, ...; with --exposure, --lamp and --uv-filter are the map's
    std::string view = "D65";
    double threshold = 1.0;
    double years = 100.0;
    bool log_years = false;
    std::string wavelengths = "300:830:5";
    int sublayers = 100;
    fs::path out_dir;
    // Per texel
    fs::path exposure;
    std::string channel;
    double scale = 1.0;
    double after_years = 0.0;
    bool preview = false;
    int threads = 0;
    bool quiet = false;
};

std::string years_text(double years)
{
    if (!std::isfinite(years))
        return "never";
    if (years >= 1e5)
        return fmt::format("{:.3g}", years);
    return years < 10.0 ? fmt::format("{:.2f}", years) : fmt::format("{:.1f}", years);
}

// The policies of the file and/or the one the options describe.
std::vector<forecast::LightingPolicy> gather_policies(const ForecastCliOptions& o)
{
    std::vector<forecast::LightingPolicy> policies;
    if (!o.policies.empty())
        policies = forecast::read_policy_file(o.policies);
    // --lamp alone with --exposure names the map's light, not a policy
    if (o.one.lux || (!o.one.lamp.empty() && o.exposure.empty()))
        policies.push_back(lamp_policy(o.one));
    if (policies.empty() && o.exposure.empty())
        throw std::runtime_error("no lighting: give --policies FILE, or --lamp and --lux, or "
                                 "--exposure MAP");
    return policies;
}

void write_outputs(const ForecastCliOptions& o, const fade::FadeMaterial& material,
                   const forecast::ColourMeter& meter,
                   const std::vector<forecast::PolicyForecast>& results)
{
    // The side-by-side table: printed, and as CSV
    std::ostringstream csv, table;
    csv << "# patina-texgen forecast: " << material.name << ", viewed under " << meter.view_name()
        << ", threshold dE2000 " << o.threshold << "\n"
        << "# dose = lux x hours (reciprocity: the fading model's state depends on the dose of "
           "one spectrum alone)\n";
    csv << "policy,spectrum,lux_hours_per_year,luminous_efficacy_lm_per_w,uv_uw_per_lm,"
           "damage_factor_mw_per_lm,dose_per_year_j_m2,threshold_dose_j_m2,"
           "threshold_mlx_h,years_to_threshold,delta_e_at_horizon\n";
    table << fmt::format("{:<32} {:>11} {:>7} {:>7} {:>8} {:>12} {:>10} {:>9} {:>7}\n", "policy",
                         "klx h/year", "lm/W", "uW/lm", "dmg mW/lm", "J/m2 a year", "JNF Mlx h",
                         "years", "dE@end");
    for (const forecast::PolicyForecast& f : results) {
        const auto& e = f.exposure;
        csv << fmt::format("\"{}\",\"{}\",{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},{:.6g},"
                           "{:.4f}\n",
                           f.policy, e.spectrum.name, e.lux_hours_per_year,
                           e.photometry.luminous_efficacy_lm_per_w, e.photometry.uv_uw_per_lm,
                           e.photometry.damage_factor_w_per_lm * 1e3, e.dose_per_year_j_m2,
                           f.threshold_dose_j_m2, f.threshold_lux_hours * 1e-6,
                           f.years_to_threshold, f.delta_e.back());
        table << fmt::format("{:<32} {:>11.4g} {:>7.1f} {:>7.1f} {:>8.3f} {:>12.4g} {:>10.3g} "
                             "{:>9} {:>7.2f}\n",
                             f.policy.substr(0, 32), e.lux_hours_per_year * 1e-3,
                             e.photometry.luminous_efficacy_lm_per_w, e.photometry.uv_uw_per_lm,
                             e.photometry.damage_factor_w_per_lm * 1e3, e.dose_per_year_j_m2,
                             f.threshold_lux_hours * 1e-6, years_text(f.years_to_threshold),
                             f.delta_e.back());
    }
    std::printf("%s under %zu polic%s, viewed under %s; years to dE2000 %g (a just-noticeable "
                "fade); dE2000 after %g years:\n%s",
                material.name.c_str(), results.size(), results.size() == 1 ? "y" : "ies",
                meter.view_name().c_str(), o.threshold, o.years, table.str().c_str());
    std::printf("Reciprocity: dose = lux x hours; the model's state under one spectrum depends on "
                "the dose alone, so halving the lux doubles the years.\n");
    if (o.out_dir.empty())
        return;
    write_file_atomic(o.out_dir / "policies.csv", {csv.str()}, "forecast table");

    // The curves: years, then dE2000 per policy
    std::ostringstream curves;
    curves << "years";
    for (const auto& f : results)
        curves << ",\"" << f.policy << "\"";
    curves << "\n";
    for (size_t i = 0; i < results.front().years.size(); ++i) {
        curves << fmt::format("{:.6g}", results.front().years[i]);
        for (const auto& f : results)
            curves << fmt::format(",{:.5f}", f.delta_e[i]);
        curves << "\n";
    }
    write_file_atomic(o.out_dir / "forecast.csv", {curves.str()}, "forecast curves");

    std::vector<fade::PlotCurve> plot;
    double top = 2.0 * o.threshold;
    for (size_t k = 0; k < results.size(); ++k) {
        fade::PlotCurve c;
        c.label = results[k].policy + " (" + years_text(results[k].years_to_threshold) + " y)";
        c.x = results[k].years;
        if (o.log_years)
            for (double& x : c.x)
                x = std::log10(x);
        c.y = results[k].delta_e;
        c.rgb = fade::categorical_color(k);
        top = std::max(top, *std::max_element(c.y.begin(), c.y.end()));
        plot.push_back(std::move(c));
    }
    fade::PlotCurve threshold;
    threshold.label = fmt::format("dE2000 {:g}", o.threshold);
    threshold.x = o.log_years ? std::vector<double>{std::log10(o.years) - 4.0, std::log10(o.years)}
                              : std::vector<double>{0.0, o.years};
    threshold.y = {o.threshold, o.threshold};
    threshold.rgb = {0.55f, 0.55f, 0.55f};
    plot.push_back(threshold);
    fade::PlotOptions po;
    po.title = fmt::format("{}: dE2000 under {} against years on display", material.name,
                           meter.view_name());
    po.x_label = o.log_years ? "log10 years" : "years";
    po.y_label = "dE2000";
    po.x_min = o.log_years ? std::log10(o.years) - 4.0 : 0.0;
    po.x_max = o.log_years ? std::log10(o.years) : o.years;
    po.y_min = 0.0;
    // The curves where they cross the threshold matter most: up to 5 thresholds
    po.y_max = std::min(top * 1.05, 5.0 * o.threshold);
    po.width = 1280;
    po.height = 640;
    po.legend_width = 440;
    fade::write_reflectance_plot(o.out_dir / "forecast.png", plot, po);
}

// Per texel: years to the threshold and dE2000 after --after years, as a texture stack.
void write_maps(const ForecastCliOptions& o, const fade::FadeMaterial& material,
                const fade::WavelengthGrid& grid, const forecast::ColourMeter& meter,
                const forecast::ForecastOptions& fo)
{
    const auto start = std::chrono::steady_clock::now();
    const fade::ExposureMap map = fade::read_exposure_map(o.exposure, o.channel);
    // The light's spectrum: --lamp, else the map's own (recorded by the exposure baker)
    fade::Illuminant lamp =
        !o.one.lamp.empty() ? forecast::parse_lamp(o.one.lamp)
        : !map.illuminant_nm.empty()
            ? fade::illuminant_from_table(map.illuminant.empty() ? "exposure map" : map.illuminant,
                                          map.illuminant_nm, map.illuminant_value)
            : fade::illuminant_by_name(map.illuminant.empty() ? "D65" : map.illuminant);
    const forecast::UvFilter filter = forecast::parse_uv_filter(o.one.uv_filter, "--uv-filter");
    const fade::Illuminant spectrum = forecast::filtered(lamp, filter);
    // A filter in front of a baked map takes its part of the band's energy too
    const double through = forecast::filter_share(lamp, filter);
    const double per_year_factor =
        fade::dose_factor(map, o.scale, 365.0 * 86400.0) * through;
    const double threshold = forecast::threshold_dose(material, spectrum, grid, meter, fo);
    const fade::DoseRange range = fade::scan_doses(map, per_year_factor);
    fade::DoseTableOptions t;
    t.max_dose_j_m2 = std::max(range.max * o.after_years, 1.0);
    t.knee_dose_j_m2 = t.max_dose_j_m2 * 1e-6;
    t.entries = 96;
    t.sublayers = o.sublayers;
    const fade::DoseTable table = fade::DoseTable::build(material, spectrum, grid, t);
    const forecast::DeltaECurve curve(table, meter);
    throw_if_cancelled();
    const forecast::YearsMaps maps =
        forecast::make_years_maps(map, per_year_factor, threshold, curve, o.after_years);
    throw_if_cancelled();

    const Metadata parameters = {{"material", material.name},
                                 {"spectrum", spectrum.name},
                                 {"view", meter.view_name()},
                                 {"threshold_de2000", static_cast<float>(o.threshold)},
                                 {"after_years", static_cast<float>(o.after_years)},
                                 {"exposure", fs::absolute(o.exposure).string()},
                                 {"scale", static_cast<float>(o.scale)}};
    forecast::write_years_maps(o.out_dir, maps, map.coverage, parameters, o.threshold,
                               o.after_years);
    if (o.preview)
        forecast::write_years_previews(o.out_dir, maps, map.coverage, o.threshold);
    if (!o.quiet)
        std::fprintf(stderr,
                     "forecast: %dx%d maps of %s under %s: years to dE2000 %g from %s (first) to "
                     "%s (median); dE2000 after %g years up to %.2f; %.2f s\n",
                     map.width, map.height, material.name.c_str(), spectrum.name.c_str(),
                     o.threshold, years_text(maps.min_years).c_str(),
                     years_text(maps.median_years).c_str(), o.after_years, maps.max_delta_e,
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                         .count());
}

void run_forecast(const ForecastCliOptions& o)
{
    std::optional<tbb::global_control> threads;
    if (o.threads > 0)
        threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    install_cancel_handler();

    if (!(o.threshold > 0.0))
        throw std::runtime_error(fmt::format("--threshold {}: a dE2000 must be > 0", o.threshold));
    if (!(o.years > 0.0))
        throw std::runtime_error(fmt::format("--years {}: must be > 0", o.years));
    if (!o.exposure.empty() && o.out_dir.empty())
        throw std::runtime_error("--exposure writes maps: give -o DIR");
    if (!o.exposure.empty() && !(o.after_years > 0.0))
        throw std::runtime_error("--exposure needs --after N (the years of the dE2000 map)");
    const fade::FadeMaterial material = load_material(o.material);
    const std::vector<forecast::LightingPolicy> policies = gather_policies(o);
    const fade::WavelengthGrid grid = parse_grid(o.wavelengths);
    const forecast::ColourMeter meter(grid, forecast::parse_lamp(o.view));
    if (!o.out_dir.empty()) {
        if (!policies.empty())
            reserve_output(o.out_dir / "policies.csv");
        if (!o.exposure.empty())
            reserve_output(o.out_dir / (std::string(forecast::kForecastMap) + ".exr"));
    }
    forecast::ForecastOptions fo;
    fo.threshold_de2000 = o.threshold;
    fo.horizon_years = o.years;
    fo.log_years = o.log_years;
    fo.sublayers = o.sublayers;

    std::vector<forecast::PolicyForecast> results;
    for (const forecast::LightingPolicy& p : policies) {
        results.push_back(forecast::forecast_policy(material, p, grid, meter, fo));
        throw_if_cancelled();
    }
    if (!results.empty())
        write_outputs(o, material, meter, results);
    if (!o.exposure.empty())
        write_maps(o, material, grid, meter, fo);
}

}  // namespace

void register_forecast_command(CLI::App& app)
{
    auto o = std::make_shared<ForecastCliOptions>();
    CLI::App* cmd = app.add_subcommand(
        "forecast",
        "years on display to a just-noticeable fade: a fading material under lighting policies "
        "(lamp, lux, hours, UV filter, daylight), and per texel from an exposure map");
    add_material_options(cmd, o->material);
    cmd->add_option("--policies", o->policies, "lighting-policy file ([[policy]] tables)");
    add_lamp_policy_options(cmd, o->one, " (with --exposure: the map's light)");
    cmd->add_option("--view", o->view, "viewing illuminant for the colours")->capture_default_str();
    cmd->add_option("--threshold", o->threshold,
                    "dE2000 of a just-noticeable fade (1.6: the grey-scale step 4)")
        ->capture_default_str();
    cmd->add_option("--years", o->years, "span of the curves, years")->capture_default_str();
    cmd->add_flag("--log-years", o->log_years,
                  "curves and plot over four decades of years on a log scale (up to --years)");
    cmd->add_option("--wavelengths", o->wavelengths, "solver wavelengths FIRST:LAST:STEP, nm")
        ->capture_default_str();
    cmd->add_option("--sublayers", o->sublayers, "sublayers of the two-flux solver (§4.1)")
        ->capture_default_str()->check(CLI::Range(1, 100000));
    cmd->add_option("-o,--out", o->out_dir,
                    "folder for policies.csv, forecast.csv, forecast.png and the maps");
    cmd->add_option("--exposure", o->exposure,
                    "exposure map of the object as shown: write fade_forecast.exr, years to the "
                    "threshold and dE2000 after --after years per texel (its period repeated "
                    "over a year)");
    cmd->add_option("--channel", o->channel, "channel of the exposure map");
    cmd->add_option("--scale", o->scale, "band dose per unit of the exposure map")
        ->capture_default_str();
    cmd->add_option("--after", o->after_years, "years of the dE2000 map");
    cmd->add_flag("--preview", o->preview,
                  "with --exposure: fade_forecast_years.png and fade_forecast_delta_e.png, the "
                  "maps in false colour (bright: fades first)");
    cmd->add_option("--threads", o->threads, "worker threads (0 = all cores)")->capture_default_str();
    cmd->add_flag("--quiet", o->quiet, "no progress");
    cmd->callback([o] { run_forecast(*o); });
}

}  // namespace patina::texgen
