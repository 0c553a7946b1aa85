// `patina-texgen fade`: an exposure map and a fading material (Kimmel et al. 2013) -> a fade
// stack (fade.toml, fade_table.exr, dose.exr) for the spectral_km shader, and optionally a
// plot of the material's reflectance over time like the paper's figures 9-13.
#include "texgen/cli/commands.h"
#include "texgen/cli/fade_options.h"

#include "core/cancel.h"
#include "core/image_io.h"
#include "core/limits.h"
#include "core/number_text.h"
#include "core/output_transaction.h"
#include "core/progress.h"
#include "texgen/fade/depth_profiles.h"
#include "texgen/cli/farm_plan.h"
#include "texgen/fade/dose_table.h"
#include "texgen/fade/fade_map.h"
#include "texgen/fade/fade_material.h"
#include "texgen/fade/fade_plot.h"
#include "texgen/fade/fade_stack.h"
#include "texgen/fade/illuminant.h"

#include <fmt/format.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

struct FadeOptions {
    std::vector<fs::path> exposures;
    std::optional<double> dose;  ///< --dose, J/m^2
    std::string channel;
    std::string material;
    std::vector<fs::path> materials;
    std::string rates;
    fs::path out_dir;
    std::string illuminant;
    std::string duration;
    double scale = 1.0;
    std::string wavelengths = "300:830:5";
    int entries = 64;
    double max_dose = 0.0;
    double knee_dose = 0.0;
    int sublayers = 100;
    int substeps = 2;
    bool both_sides = false;
    fs::path plot;
    std::string plot_title;
    // The simulation itself over time (depth profiles)
    std::optional<double> irradiance;
    std::string time_step;
    int steps = 0;
    std::vector<std::string> profiles_at;
    int threads = 0;
    bool quiet = false;
};

fade::Illuminant choose_illuminant(const FadeOptions& o, const fade::ExposureMap& map)
{
    if (!o.illuminant.empty())
        return fade::illuminant_from_text(o.illuminant);
    if (!map.illuminant_nm.empty())
        return fade::illuminant_from_table(map.illuminant.empty() ? "exposure map"
                                                                  : map.illuminant,
                                           map.illuminant_nm, map.illuminant_value);
    if (!map.illuminant.empty())
        return fade::illuminant_by_name(map.illuminant);
    return fade::illuminant_by_name("D65");
}

// The material's reflectance at doses spread like the paper's 0h, 6h, 1d, 7d over the
// largest dose of the map, from the table (figures 9-13).
void write_plot(const FadeOptions& o, const fade::DoseTable& table, double max_dose,
                double duration_s, const std::string& title)
{
    const double fractions[] = {0.0, 6.0 / 168.0, 24.0 / 168.0, 1.0};
    std::vector<fade::PlotCurve> curves;
    for (size_t k = 0; k < std::size(fractions); ++k) {
        const double dose = fractions[k] * max_dose;
        fade::PlotCurve c;
        c.label = duration_s > 0.0 ? fade::duration_label(fractions[k] * duration_s)
                                   : fmt::format("{:.3g} J/m2", dose);
        c.x = table.grid().nm;
        c.y = table.spectra_at(dose).reflectance;
        c.rgb = fade::time_ramp_color(k, std::size(fractions));
        curves.push_back(std::move(c));
    }
    fade::PlotOptions p;
    p.title = title;
    fade::write_reflectance_plot(o.plot, curves, p);
}

// The dose of every texel: the sum over the exposure maps (each with its own period and
// units), or a uniform --dose on a small map. `first` keeps the first map's header.
struct Doses {
    fade::ExposureMap map;    // values in J/m^2, factor 1
    fade::ExposureMap first;  // header of the first map (illuminant, units, period)
};

Doses gather_doses(const FadeOptions& o, double duration_s)
{
    Doses d;
    if (o.dose) {
        if (!o.exposures.empty())
            throw std::runtime_error("--dose and --exposure exclude each other");
        if (!std::isfinite(*o.dose) || *o.dose < 0.0)
            throw std::runtime_error(fmt::format("--dose must be a finite number of J/m^2 >= 0, "
                                                 "got {}", *o.dose));
        d.map.width = d.map.height = 4;
        d.map.channel = "dose";
        d.map.units = "J/m^2";
        d.map.values.assign(16, static_cast<float>(*o.dose * o.scale));
        d.first = d.map;
        return d;
    }
    if (o.exposures.empty())
        throw std::runtime_error("--exposure MAP (or --dose) is required");
    for (size_t k = 0; k < o.exposures.size(); ++k) {
        const fade::ExposureMap m = fade::read_exposure_map(o.exposures[k], o.channel);
        const double factor = fade::dose_factor(m, o.scale, duration_s);
        fade::scan_doses(m, factor);  // names a NaN or negative texel of this file
        if (k == 0) {
            d.first = m;
            d.map = m;
            d.map.units = "J/m^2";
            d.map.values.assign(m.values.size(), 0.0f);
        } else if (m.width != d.map.width || m.height != d.map.height) {
            throw std::runtime_error(fmt::format(
                "exposure map '{}' is {}x{}, but '{}' is {}x{}: maps whose doses add up need "
                "one resolution",
                m.file.string(), m.width, m.height, d.first.file.string(), d.map.width,
                d.map.height));
        }
        for (size_t i = 0; i < m.values.size(); ++i)
            d.map.values[i] += static_cast<float>(factor * m.values[i]);
    }
    return d;
}

// --time-step: the layered simulation under a constant irradiance, the colorants' fractions
// over depth and the reflectance at chosen times (docs/fading.md "Depth profiles").
void run_profiles(const FadeOptions& o, const fade::FadeMaterial& material)
{
    if (!o.exposures.empty() || o.dose)
        throw std::runtime_error("--time-step runs the simulation under --irradiance: leave out "
                                 "--exposure and --dose");
    if (!o.irradiance)
        throw std::runtime_error("--time-step needs --irradiance W/m^2 (in the illuminant's band)");
    fade::ProfileRun run;
    run.irradiance_w_m2 = *o.irradiance;
    run.time_step_s = parse_duration(o.time_step, "--time-step");
    run.steps = o.steps;
    run.sublayers = o.sublayers;
    run.both_sides = o.both_sides;
    for (const std::string& t : o.profiles_at)
        run.times_s.push_back(parse_duration(t, "--profiles-at"));
    if (run.times_s.empty())
        run.times_s.push_back(run.time_step_s * run.steps);
    const fade::Illuminant illuminant = fade::illuminant_from_text(o.illuminant.empty() ? "D65" : o.illuminant);
    const fade::WavelengthGrid grid = parse_grid(o.wavelengths);
    reserve_output(o.out_dir / "profiles.csv");
    const auto start = std::chrono::steady_clock::now();
    const fade::DepthProfiles p = fade::run_depth_profiles(material, illuminant, grid, run);
    write_file_atomic(o.out_dir / "profiles.csv", {fade::profiles_csv(p)}, "depth profiles");
    write_file_atomic(o.out_dir / "reflectance.csv", {fade::reflectance_csv(p)}, "reflectance");
    const std::string what = fmt::format("{} under {} at {:g} W/m2", material.name,
                                         illuminant.name, run.irradiance_w_m2);
    fade::write_profiles_plot(o.out_dir / "profiles.png", p,
                              o.plot_title.empty() ? what + ": colorants over depth" : o.plot_title);
    std::vector<fade::PlotCurve> curves;
    for (size_t k = 0; k < p.snapshots.size(); ++k) {
        fade::PlotCurve c;
        c.label = fade::duration_label(p.snapshots[k].time_s);
        c.x = p.wavelength_nm;
        c.y = p.snapshots[k].reflectance;
        c.rgb = fade::time_ramp_color(k, p.snapshots.size());
        curves.push_back(std::move(c));
    }
    fade::PlotOptions po;
    po.title = what;
    fade::write_reflectance_plot(o.out_dir / "reflectance.png", curves, po);
    if (!o.quiet)
        std::fprintf(stderr, "fade: %d steps of %s, %zu profiles of %d sublayers -> %s in %.2f s\n",
                     run.steps, fade::duration_label(run.time_step_s).c_str(), p.snapshots.size(),
                     run.sublayers, o.out_dir.string().c_str(),
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
}

void run_fade(const FadeOptions& o)
{
    std::optional<tbb::global_control> threads;
    if (o.threads > 0)
        threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    install_cancel_handler();
    const auto start = std::chrono::steady_clock::now();

    // Inputs first, so a bad one fails before any work or output
    std::vector<fs::path> files = fade::FadeLibrary::default_files();
    files.insert(files.end(), o.materials.begin(), o.materials.end());
    if (files.empty())
        throw std::runtime_error("no fading materials: none found under $PATINA_SHADER_PATH or "
                                 "<exe>/../share/patina/shaders/fade; pass --materials FILE");
    const fade::FadeLibrary library = fade::FadeLibrary::load_files(files);
    const fade::FadeMaterial material = library.material_with_rates(o.material, o.rates);
    if (!o.time_step.empty())
        return run_profiles(o, material);
    // Output locations, before any work.
    reserve_output(o.out_dir / fade::kFadeToml);
    if (!o.plot.empty())
        reserve_output(o.plot);
    const fade::WavelengthGrid grid = parse_grid(o.wavelengths);
    const double duration_s = parse_duration(o.duration);
    const Doses doses = gather_doses(o, duration_s);
    const fade::ExposureMap& map = doses.map;
    const fade::Illuminant illuminant = choose_illuminant(o, doses.first);
    const fade::DoseRange range = fade::scan_doses(map, 1.0);

    // The dose table, up to the map's largest dose (or --max-dose)
    fade::DoseTableOptions t;
    t.max_dose_j_m2 = o.max_dose > 0.0 ? o.max_dose : std::max(range.max, 1.0);
    // Six decades of logarithmic spacing: fast colorants (a newsprint tint fades within
    // ~1e4 J/m^2) and slow ones (lignin, ~5e7) both get rows where they change
    t.knee_dose_j_m2 = o.knee_dose > 0.0 ? o.knee_dose : t.max_dose_j_m2 * 1e-6;
    t.entries = o.entries;
    t.sublayers = o.sublayers;
    t.substeps = o.substeps;
    t.both_sides = o.both_sides;
    if (!o.quiet)
        std::fprintf(stderr,
                     "fade: %s under %s, %zu wavelengths, %d sublayers; doses %.4g-%.4g J/m^2 "
                     "(mean %.4g) -> table of %d entries up to %.4g J/m^2\n",
                     material.name.c_str(), illuminant.name.c_str(), grid.size(), t.sublayers,
                     range.min, range.max, range.mean, t.entries, t.max_dose_j_m2);
    const fade::DoseTable table = fade::DoseTable::build(material, illuminant, grid, t);
    throw_if_cancelled();
    // The table's error: its interpolation against a table twice as fine
    fade::DoseTableOptions fine_options = t;
    fine_options.entries = 2 * t.entries - 1;
    fine_options.substeps = std::max(1, t.substeps / 2);
    const fade::DoseTable fine = fade::DoseTable::build(material, illuminant, grid, fine_options);
    const double table_error = fade::interpolation_error(table, fine);
    throw_if_cancelled();
    // (A uniform dose sits on the table's first or last row: nothing is interpolated)
    if (table_error > 0.01 && range.max > range.min)
        std::fprintf(stderr,
                     "fade: warning: the table's interpolation error is %.2g in reflectance; "
                     "more --entries or another --knee-dose would lower it\n",
                     table_error);

    // Per texel: dose and table row, in parallel
    Progress progress(static_cast<size_t>(map.height), o.quiet, "fade");
    const std::vector<float> pixels = fade::make_dose_pixels(
        map, table, 1.0,
        [](size_t rows, void* p) {
            static_cast<Progress*>(p)->step(rows);
            throw_if_cancelled();
        },
        &progress);
    progress.finish();

    fade::FadeStackInfo info;
    info.material = material.name;
    info.material_file = material.file;
    info.illuminant = illuminant.name;
    info.band_min_nm = illuminant.band_min_nm;
    info.band_max_nm = illuminant.band_max_nm;
    info.substrate = grid.sample(material.substrate_reflectance);
    info.max_interpolation_error = table_error;
    for (const fs::path& f : o.exposures)
        info.exposure.files.push_back(fs::absolute(f));
    info.exposure.channel = doses.first.channel;
    info.exposure.units = doses.first.units;
    info.exposure.scale = o.scale;
    info.exposure.duration_s = duration_s;
    info.exposure.period_s = doses.first.period_s;
    info.width = map.width;
    info.height = map.height;
    info.min_dose = range.min;
    info.mean_dose = range.mean;
    info.max_dose = range.max;
    fade::write_fade_stack(o.out_dir, table, info, pixels);

    if (!o.plot.empty()) {
        // Each exposure map is a period of its own: the plot's last curve is their sum
        const double shown = (duration_s > 0.0 ? duration_s : map.period_s) *
                             static_cast<double>(std::max<size_t>(o.exposures.size(), 1));
        const std::string title =
            o.plot_title.empty()
                ? fmt::format("{} under {}, up to {:.3g} J/m2", material.name, illuminant.name,
                              range.max)
                : o.plot_title;
        write_plot(o, table, range.max, shown, title);
    }
    if (!o.quiet)
        std::fprintf(stderr,
                     "fade: wrote %s (%dx%d dose map; table error %.2g in reflectance) in "
                     "%.2f s\n",
                     (o.out_dir / fade::kFadeToml).string().c_str(), map.width, map.height,
                     table_error,
                     std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                         .count());
}

/// --dose: one dose in J/m^2.
double parse_dose(const std::string& text)
{
    const std::optional<double> dose = parse_double(text);
    if (!dose)
        throw std::runtime_error(fmt::format(
            "--dose '{}' is not a number of J/m^2{}", text,
            text.find(',') != std::string::npos ? " (a list is for a farm's series: --plan)" : ""));
    return *dose;
}

/// The tasks of a farm (--plan): a stack per value of the list given to --duration or
/// --dose, each into a folder of -o named after its value ("7d", "1e+06").
formats::TexgenPlan fade_plan(const FadeOptions& o, const std::string& dose_text)
{
    std::string option, list;
    for (const auto& [name, text] : {std::pair{"--duration", o.duration}, std::pair{"--dose", dose_text}})
        if (text.find(',') != std::string::npos) {
            if (!option.empty())
                throw std::runtime_error("a fade series on a farm takes one list: --duration or "
                                         "--dose, not both");
            option = name;
            list = text;
        }
    if (option.empty())
        throw std::runtime_error("a fade series on a farm needs a list, --duration D1,D2,... or "
                                 "--dose J1,J2,... (a stack each)");
    formats::TexgenPlan plan;
    plan.command = "fade";
    plan.output = fs::absolute(o.out_dir).lexically_normal();
    const std::vector<std::string> args = task_arguments();
    std::stringstream in(list);
    std::string value;
    std::vector<std::string> folders;
    while (std::getline(in, value, ',')) {
        // Each value is checked as the run will read it.
        if (option == "--duration")
            (void)parse_duration(value);
        else
            (void)parse_dose(value);
        // The value names the folder ("7d", "1e+06"), other characters as '_'.
        std::string folder = value;
        for (char& c : folder)
            if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '+' && c != '-')
                c = '_';
        if (folder.empty() || std::find(folders.begin(), folders.end(), folder) != folders.end())
            throw std::runtime_error(fmt::format("{} '{}': an empty or repeated value", option, list));
        folders.push_back(folder);
        formats::TexgenPlanTask task;
        task.label = fmt::format("{} {}", option, value);
        task.folder = folder;
        task.args = with_option(with_option(args, {option}, value), {"-o", "--out"},
                                (plan.output / folder).string());
        task.outputs = {plan.output / folder};
        plan.tasks.push_back(std::move(task));
    }
    return plan;
}

}  // namespace

void register_fade_command(CLI::App& app)
{
    auto o = std::make_shared<FadeOptions>();
    CLI::App* cmd = app.add_subcommand(
        "fade",
        "turn an exposure map into a fade stack (Kimmel et al. 2013): a dose table of the "
        "material under one illuminant and a dose map, for the spectral_km shader");
    cmd->add_option("--exposure", o->exposures,
                    "exposure map from `patina-texgen exposure` (J/m^2, or W/m^2 with "
                    "--duration); any EXR with an exposure or irradiance channel. Repeat it "
                    "to add the doses of several maps (occluders moved between exposures)");
    auto dose_text = std::make_shared<std::string>();
    cmd->add_option("--dose", *dose_text,
                    "a uniform dose in J/m^2 instead of exposure maps (swatches, plots)");
    cmd->add_option("--channel", o->channel,
                    "channel of the map to read (default: exposure, else irradiance)");
    cmd->add_option("--material", o->material, "fading material (shaders/fade/*.toml)")
        ->required();
    cmd->add_option("--materials", o->materials, "more fading material files (repeatable)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--rates", o->rates,
                    "a named set of fading rates from the material files (e.g. Table V's rows)");
    cmd->add_option("-o,--out", o->out_dir, "fade stack folder")->required();
    cmd->add_option("--illuminant", o->illuminant,
                    "D65, A, E (= flat), F1..F12, LED-B1..LED-V2, or SPD.csv[:COLUMN] (default: the "
                    "exposure map's own spectrum, else D65)");
    cmd->add_option("--duration", o->duration,
                    "exposure time (7d, 30y, 6h, seconds): required for a W/m^2 map; for a "
                    "J/m^2 map the map's period is repeated over it");
    cmd->add_option("--scale", o->scale,
                    "dose per unit of the map (e.g. the share of broadband solar energy in the "
                    "illuminant's band)")
        ->capture_default_str();
    cmd->add_option("--wavelengths", o->wavelengths, "solver wavelengths FIRST:LAST:STEP, nm")
        ->capture_default_str();
    cmd->add_option("--entries", o->entries, "dose table entries")
        ->capture_default_str()->check(CLI::Range(2, 4096));
    cmd->add_option("--max-dose", o->max_dose,
                    "largest dose of the table, J/m^2 (default: the map's largest)");
    cmd->add_option("--knee-dose", o->knee_dose,
                    "dose where the table's spacing turns logarithmic (default: max / 1e6)");
    cmd->add_option("--sublayers", o->sublayers, "sublayers of the two-flux solver (§4.1)")
        ->capture_default_str()->check(CLI::Range(1, 100000));
    cmd->add_option("--substeps", o->substeps, "time steps per table interval (§4.2)")
        ->capture_default_str()->check(CLI::Range(1, 1000));
    cmd->add_flag("--both-sides", o->both_sides, "light the layer from below too (a free sheet)");
    cmd->add_option("--plot", o->plot,
                    "write the material's reflectance at 0, 1/28, 1/7 and all of the largest "
                    "dose (0h, 6h, 1d, 7d of a week) as a PNG");
    cmd->add_option("--plot-title", o->plot_title, "title of the plot");
    cmd->add_option("--irradiance", o->irradiance,
                    "with --time-step: constant irradiance in the illuminant's band, W/m^2");
    cmd->add_option("--time-step", o->time_step,
                    "run the simulation itself in steps of this length (1h, 1d, seconds) and "
                    "write profiles.csv/png (fractions over depth) and reflectance.csv/png");
    cmd->add_option("--steps", o->steps, "with --time-step: number of steps")
        ->capture_default_str();
    cmd->add_option("--profiles-at", o->profiles_at,
                    "with --time-step: times to keep (6h,1d,7d; default: the end)")
        ->delimiter(',');
    cmd->add_option("--threads", o->threads, "worker threads (0 = all cores)")
        ->capture_default_str();
    cmd->add_flag("--quiet", o->quiet, "no progress");
    auto plan = std::make_shared<bool>(false);
    cmd->add_flag("--plan", *plan,
                  "print the tasks a farm runs for a series of stacks, one per value of a list "
                  "given to --duration (7d,30d) or --dose (as TOML; docs/farm.md), instead of "
                  "running");
    cmd->callback([o, plan, dose_text] {
        if (*plan) {
            print_plan(fade_plan(*o, *dose_text));
            return;
        }
        if (!dose_text->empty())
            o->dose = parse_dose(*dose_text);
        run_fade(*o);
    });
}

}  // namespace patina::texgen
