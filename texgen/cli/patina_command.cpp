// `patina-texgen patina SCRIPT`: runs a patina script (Dorsey & Hanrahan 1996 §3, §5) on a
// mesh's texels or on a flat strip and writes a thickness stack per time step.
#include "texgen/cli/commands.h"

#include "formats/texture_stack/texture_stack.h"

#include "core/cli_errors.h"
#include "core/cancel.h"
#include "core/color_management.h"
#include "core/limits.h"
#include "core/number_text.h"
#include "core/output_transaction.h"
#include "core/progress.h"
#include "texgen/patina/interpreter.h"
#include "texgen/patina/material_library.h"
#include "texgen/patina/script_parser.h"
#include "texgen/patina/stack_writer.h"
#include "texgen/cli/farm_plan.h"
#include "texgen/cli/mesh_options.h"
#include "texgen/meshes/mesh_input.h"
#include "texgen/texels/uv_wrap.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>
#include <sstream>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

struct PatinaOptions {
    fs::path script;
    fs::path mesh;
    MeshConventionOptions convention;
    bool uv_wrap = false;
    std::vector<std::string> keep_off;  ///< source materials that grow nothing
    fs::path out_dir = "patina";
    std::vector<double> times{30.0};
    double end_time = 0;
    int width = 0, height = 0;  // 0: 512 for a strip, 1024 for a mesh
    double strip_size = 0.1;
    std::string strip_boundary = "open";
    int supersampling = 2;
    uint64_t seed = 1;
    int threads = 0;
    std::vector<fs::path> materials;
    int padding = 16;
    bool half = false;
    bool no_preview = false;
    bool quiet = false;
};

/// `mesh` as a path relative to the folder `dir` (both made absolute), or absolute when
/// they share no root: recorded in the stack so that export finds the mesh again when the
/// stack and the mesh move together.
fs::path mesh_path_from(const fs::path& dir, const fs::path& mesh)
{
    const fs::path to = fs::absolute(mesh).lexically_normal();
    const fs::path rel = to.lexically_relative(fs::absolute(dir).lexically_normal());
    return rel.empty() ? to : rel;
}

/// The convention to read the mesh with: the user's options, completed by what the stacks of
/// the script's maps record (they were baked on the same mesh); a map baked with another
/// convention than the options say, or two maps that disagree, are refused.
MeshConventionOptions convention_with_maps(const Script& script, const fs::path& script_dir,
                                           const MeshConventionOptions& user)
{
    MeshConventionOptions options = user;
    for (const Statement& statement : script.statements) {
        const auto* map = std::get_if<MapStatement>(&statement);
        if (!map || !map->material.empty())  // a material mask reads no file
            continue;
        const fs::path file = fs::path(map->path).is_relative() ? script_dir / map->path
                                                                : fs::path(map->path);
        std::error_code ec;
        if (!fs::is_regular_file(file.parent_path() / formats::kStackManifest, ec))
            continue;
        const formats::TextureStack stack = formats::read_texture_stack(file.parent_path());
        for (const auto& [name, entry] : stack.maps)
            if (entry.file == file.filename() || entry.pattern == file.filename())
                options = convention_for_stack(
                    options, recorded_convention(entry.parameters),
                    fmt::format("map '{}' ({})", map->name, file.string()));
    }
    return options;
}

void run_patina(const PatinaOptions& o)
{
    std::optional<tbb::global_control> threads;
    if (o.threads > 0)
        threads.emplace(tbb::global_control::max_allowed_parallelism, o.threads);
    const auto start = std::chrono::steady_clock::now();

    if (o.mesh.empty() && (!o.convention.empty() || o.uv_wrap))
        throw std::runtime_error("--up, --unit, --scale and --uv-wrap describe the file of "
                                 "--mesh; a strip is in metres with uvs in one tile");
    reserve_output(o.out_dir / formats::kSeriesManifest);  // a bad output folder fails before the run
    ColorManager colors(ColorManager::default_config_path());
    const MaterialLibrary library = MaterialLibrary::load_default(o.materials, colors);

    const Script script = parse_script_file(o.script, library.names());
    // Every step's stack is kept until the series is written: at least one layer of floats
    // per texel and step.
    {
        const double side = o.width > 0 ? o.width : (o.mesh.empty() ? 512 : 1024);
        const double texels = side * (o.height > 0 ? o.height : side);
        check_memory("--times, --resolution", 4.0 * texels * static_cast<double>(o.times.size()),
                     fmt::format("{} steps of {:.0f} texels", o.times.size(), texels));
    }

    TriangleMesh mesh;
    MeshConvention convention;
    MeshConventionOptions read_with;
    PatinaDomain domain;
    if (!o.mesh.empty()) {
        read_with = convention_with_maps(script, o.script.parent_path(), o.convention);
        mesh = load_mesh_with_warnings(o.mesh, read_with, &convention);
        if (o.uv_wrap)
            wrap_uvs_outside_udims(mesh);
        RasterOptions raster;
        raster.width = o.width > 0 ? o.width : 1024;
        raster.height = o.height > 0 ? o.height : raster.width;
        raster.supersampling = o.supersampling;
        domain = make_mesh_domain(mesh, raster);
    } else {
        const int w = o.width > 0 ? o.width : 512;
        domain = make_strip_domain(w, o.height > 0 ? o.height : w, o.strip_size,
                                   o.strip_boundary == "periodic" ? GridBoundary::periodic
                                                                  : GridBoundary::open);
    }

    InterpreterOptions run;
    run.times_years = o.times;
    run.end_time_years = o.end_time;
    run.seed = o.seed;
    run.script_dir = o.script.parent_path();
    Progress progress(patina_work_units(script, run), o.quiet, "patina");
    run.progress = &progress;
    // Nothing grows on the --keep-off materials (glass, rubber): every layer is scaled by the
    // share of each texel that lies on other materials. A name the mesh lacks fails here,
    // before the run.
    std::vector<float> keep;
    if (!o.keep_off.empty()) {
        keep.assign(domain.size(), 1.0f);
        for (const std::string& material : o.keep_off) {
            std::vector<float> fraction;
            try {
                fraction = material_fraction(domain, material);
            } catch (const std::exception& e) {
                throw std::runtime_error(fmt::format("--keep-off: {}", e.what()));
            }
            for (size_t i = 0; i < keep.size(); ++i)
                keep[i] = std::max(0.0f, keep[i] - fraction[i]);
        }
    }
    std::vector<PatinaStep> steps = run_patina_script(script, library, domain, run);
    progress.finish();
    if (!keep.empty()) {
        for (PatinaStep& step : steps) {
            for (ResultLayer& layer : step.layers)
                for (size_t i = 0; i < keep.size(); ++i)
                    layer.thickness_um[i] *= keep[i];
            for (size_t i = 0; i < keep.size(); ++i)
                step.total_um[i] *= keep[i];
        }
    }

    PatinaOutputOptions out;
    out.maps.padding = o.padding;
    out.maps.format = o.half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
    out.preview = !o.no_preview;
    out.script = o.script.filename().string();
    out.parameters = {{"patina:script", o.script.filename().string()},
                      {"patina:seed", static_cast<int>(o.seed)},
                      {"patina:end_time_years",
                       static_cast<float>(o.end_time > 0 ? o.end_time : o.times.back())},
                      {"patina:domain", o.mesh.empty() ? std::string("strip")
                                                       : o.mesh.filename().string()}};
    if (!o.keep_off.empty())
        out.parameters.emplace_back("patina:keep_off", fmt::format("{}", fmt::join(o.keep_off, ",")));
    if (o.mesh.empty()) {
        out.parameters.emplace_back("patina:strip_size_m", static_cast<float>(o.strip_size));
        out.parameters.emplace_back("patina:strip_boundary", o.strip_boundary);
    }

    const bool series = steps.size() > 1;
    formats::StackSeries series_toml;
    series_toml.script = out.script;
    for (size_t k = 0; k < steps.size(); ++k) {
        throw_if_cancelled();
        const fs::path dir =
            series ? o.out_dir / formats::series_step_folder(steps[k].time_years,
                                                         steps.back().time_years)
                   : o.out_dir;
        PatinaOutputOptions step_out = out;
        if (!o.mesh.empty()) {  // where export finds the mesh: relative to the step's folder
            step_out.parameters.emplace_back(
                "patina:mesh", mesh_path_from(dir, o.mesh).generic_string());
            record_convention(step_out.parameters, convention);
            record_uv_set(step_out.parameters, read_with.uv_set);
            if (o.uv_wrap)
                record_uv_wrap(step_out.parameters);
        }
        write_patina_step(dir, steps[k], domain, step_out, colors);
        series_toml.steps.push_back({steps[k].time_years, dir.filename().string()});
    }
    if (series)
        write_file_atomic(o.out_dir / formats::kSeriesManifest,
                          {formats::stack_series_text(series_toml)}, "series manifest");

    if (!o.quiet) {
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        const PatinaStep& last = steps.back();
        std::fprintf(stderr, "patina: %s, %zu nodes, %zu step(s), %zu layer(s) over %s -> %s "
                             "(%.2f s)\n",
                     out.script.c_str(), domain.size(), steps.size(), last.layers.size(),
                     last.base->name.c_str(), o.out_dir.string().c_str(), seconds);
    }
}

/// Most steps of one patina run (each is a stack folder of maps).
constexpr double kMaxTimeSteps = 1000;

std::vector<double> parse_times(const std::string& text)
{
    std::vector<double> times;
    std::stringstream in(text);
    std::string item;
    while (std::getline(in, item, ',')) {
        check_limit("--times", static_cast<double>(times.size() + 1), kMaxTimeSteps, "times");
        const std::optional<double> time = parse_double(item);
        if (!time || *time < 0)
            throw std::runtime_error(fmt::format("--times: '{}' is not a time in years >= 0 "
                                                 "(expected e.g. 0,6,12,18,24,30)", item));
        const double v = *time;
        if (!times.empty() && !(v > times.back()))
            throw std::runtime_error(fmt::format("--times must ascend ({} after {})", v,
                                                 times.back()));
        times.push_back(v);
    }
    if (times.empty())
        throw std::runtime_error("--times: no times given");
    return times;
}

/// The tasks of a farm (--plan): one per time of --times, each writing its step's folder of
/// the series (the stack itself for one time), the script describing --end-time.
formats::TexgenPlan patina_plan(const PatinaOptions& o, const std::string& times_text)
{
    if (times_text.empty())
        throw std::runtime_error("a patina series on a farm needs --times (its steps, a task each)");
    formats::TexgenPlan plan;
    plan.command = "patina";
    plan.output = fs::absolute(o.out_dir).lexically_normal();
    const std::string end = fmt::format("{}", o.end_time > 0 ? o.end_time : o.times.back());
    const std::vector<std::string> args = task_arguments();
    for (const double t : o.times) {
        formats::TexgenPlanTask task;
        task.time_years = t;
        // One step alone is written as the stack itself, as a run without a farm does.
        task.folder = o.times.size() > 1 ? formats::series_step_folder(t, o.times.back()) : "";
        const fs::path out = task.folder.empty() ? plan.output : plan.output / task.folder;
        task.label = fmt::format("t = {} y", t);
        task.args = with_option(with_option(with_option(args, {"--times"}, fmt::format("{}", t)),
                                            {"--end-time"}, end),
                                {"-o", "--out"}, out.string());
        task.outputs = {out};
        plan.tasks.push_back(std::move(task));
    }
    return plan;
}

}  // namespace

void register_patina_command(CLI::App& app)
{
    auto o = std::make_shared<PatinaOptions>();
    auto times_text = std::make_shared<std::string>();
    auto plan = std::make_shared<bool>(false);
    CLI::App* cmd = app.add_subcommand(
        "patina", "run a patina script (Dorsey & Hanrahan 1996: new, coat, erode, fill, polish, "
                  "offset, growth models) on a mesh or a flat strip; writes a thickness stack "
                  "per time step");
    cmd->add_option("script", o->script, "the .patina script")->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("--mesh", o->mesh, "the uv-mapped mesh (any Assimp format); without it, "
                                       "a flat strip")->check(CLI::ExistingFile);
    add_mesh_convention_options(*cmd, o->convention);
    cmd->add_option("--keep-off", o->keep_off,
                    "source materials of the mesh on which nothing grows (glass, rubber; "
                    "repeatable or comma-separated): every layer is zero on their texels")
        ->delimiter(',')
        ->needs("--mesh");
    cmd->add_flag("--uv-wrap", o->uv_wrap,
                  "fold triangles whose uvs lie outside the UDIM tiles into tile 1001, as a "
                  "renderer's repeat wrapping reads them (as the bakers' --uv-wrap)");
    cmd->add_option("-o,--out", o->out_dir, "output folder (a stack, or one per time step)")
        ->capture_default_str();
    cmd->add_option("--times", *times_text,
                    "years to compute, ascending, e.g. 0,6,12,18,24,30 (default 30); the script "
                    "describes the last one");
    cmd->add_option("--end-time", o->end_time, "years the script describes (default: the last "
                                               "of --times)")->check(patina::positive);
    cmd->add_option("--resolution", o->width, "texels per side (strip default 512, mesh 1024)")
        ->check(CLI::Range(8, 16384));
    cmd->add_option("--strip-size", o->strip_size, "width of the strip in metres")
        ->capture_default_str()->check(patina::positive);
    cmd->add_option("--strip-boundary", o->strip_boundary,
                    "open: a real strip, its edge texels have fewer neighbours; periodic: one "
                    "tile of an endless sheet (growth and offset wrap around the edges)")
        ->capture_default_str()->check(CLI::IsMember({"open", "periodic"}))
        ->excludes("--mesh");
    cmd->add_option("--supersampling", o->supersampling, "sub-samples per texel side (mesh)")
        ->capture_default_str()->check(CLI::Range(1, 8));
    cmd->add_option("--seed", o->seed, "random seed of the growth models")->capture_default_str();
    cmd->add_option("--threads", o->threads, "worker threads (0: all cores)")
        ->capture_default_str()->check(patina::non_negative);
    cmd->add_option("--materials", o->materials, "more material library files (TOML)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--padding", o->padding, "texels of push-pull padding (-1: all)")
        ->capture_default_str();
    cmd->add_flag("--half", o->half, "write half-float maps");
    cmd->add_flag("--no-preview", o->no_preview, "skip the preview PNG");
    cmd->add_flag("-q,--quiet", o->quiet, "no progress");
    cmd->add_flag("--plan", *plan,
                  "print the tasks a farm runs for this series (one per time of --times, as "
                  "TOML; docs/farm.md) instead of running it");
    cmd->callback([o, times_text, plan] {
        if (!times_text->empty())
            o->times = parse_times(*times_text);
        if (*plan)
            print_plan(patina_plan(*o, *times_text));
        else
            run_patina(*o);
    });
}

}  // namespace patina::texgen
