// `patina-texgen export INPUT -o FILE`: a patina stack or time series as glTF 2.0 that other
// programs open already wired (texgen/export/export_patina.h; docs/export.md).
#include "texgen/cli/commands.h"
#include "texgen/cli/mesh_options.h"

#include "core/color_management.h"
#include "texgen/export/export_fade.h"
#include "texgen/export/export_forecast.h"
#include "texgen/export/export_flattened.h"
#include "texgen/export/export_patina.h"
#include "texgen/export/vdb_export.h"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <memory>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

struct ExportCommandOptions {
    std::vector<fs::path> inputs;
    fs::path output;
    ExportOptions exporting;
    fs::path scene;        ///< --scene: the slab_volume parameters of a .vdb export
    std::string medium;    ///< --medium: its name
    bool quiet = false;
};

void run_export(const ExportCommandOptions& o)
{
    const auto start = std::chrono::steady_clock::now();
    const ColorManager colors(ColorManager::default_config_path());
    const fs::path& input = o.inputs.front();
    if (is_fade_stack(input)) {
        // Fade stacks: one, or several in order of age (a series).
        for (const fs::path& other : o.inputs)
            if (!is_fade_stack(other))
                throw std::runtime_error(fmt::format(
                    "export: '{}' is not a fade stack (no fade.toml) but '{}' is; a series "
                    "of fade stacks takes fade stacks only", other.string(), input.string()));
        const ExportResult r = export_fade(o.inputs, o.output, o.exporting, colors);
        if (!o.quiet)
            std::fprintf(stderr, "export: %zu fade stack(s) of %dx%d, %zu texture(s) -> %s (%.2f s)\n",
                         r.steps, r.width, r.height, r.textures, o.output.string().c_str(),
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                             .count());
        return;
    }
    if (o.inputs.size() > 1)
        throw std::runtime_error(fmt::format(
            "export: {} inputs; several inputs are a series of fade stacks, and '{}' is not "
            "one (a patina series is its folder with series.toml)", o.inputs.size(),
            input.string()));
    if (is_forecast_folder(input)) {
        const ExportResult r = export_forecast(input, o.output, o.exporting, colors);
        if (!o.quiet)
            std::fprintf(stderr, "export: %s, a forecast of %dx%d, %zu texture(s) -> %s (%.2f s)\n",
                         input.string().c_str(), r.width, r.height, r.textures,
                         o.output.string().c_str(),
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                             .count());
        return;
    }
    if (is_flattened_stack(input)) {
        const ExportResult r = export_flattened(input, o.output, o.exporting, colors);
        if (!o.quiet)
            std::fprintf(stderr, "export: %s, flattened maps of %dx%d, %zu texture(s) -> %s (%.2f s)\n",
                         input.string().c_str(), r.width, r.height, r.textures,
                         o.output.string().c_str(),
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                             .count());
        return;
    }
    if (o.output.extension() == ".vdb") {
        // A stone run's volumes as OpenVDB, one file per step.
        const VdbOptions medium =
            o.scene.empty() ? VdbOptions() : read_medium_options(o.scene, o.medium, colors);
        const std::vector<fs::path> files = export_stone_vdb(input, o.output, medium, colors);
        if (!o.quiet)
            std::fprintf(stderr, "export: %s, %zu file(s) -> %s%s (%.2f s)\n",
                         input.string().c_str(), files.size(), files.front().string().c_str(),
                         files.size() > 1 ? " ..." : "",
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                             .count());
        return;
    }
    const ExportResult r = export_patina(input, o.output, o.exporting, colors);
    if (!o.quiet) {
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "export: %s, %zu step(s) of %dx%d, %zu texture(s) -> %s (%.2f s)\n",
                     input.string().c_str(), r.steps, r.width, r.height, r.textures,
                     o.output.string().c_str(), seconds);
    }
}

}  // namespace

void register_export_command(CLI::App& app)
{
    auto o = std::make_shared<ExportCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "export", "export a patina stack or time series as glTF 2.0 (a .glb, or .gltf with "
                  "--separate): the strip at its real size or the mesh it was grown on (a "
                  "material per UDIM tile), metallic-roughness + clearcoat maps, one "
                  "material variant per step named by age; or as textures packed for "
                  "Unreal, Unity HDRP or look files (--preset)");
    cmd->add_option("input", o->inputs,
                    "a stack folder or its stack.toml, or a time-series folder (series.toml) "
                    "written by `patina-texgen patina`; the maps `patina-texgen flatten` "
                    "wrote; one or more fade stacks (in order of age) written by "
                    "`patina-texgen fade`; with -o X.vdb a `patina-texgen stone` output folder")
        ->required();
    cmd->add_option("-o,--out", o->output,
                    "the .glb (or .gltf with --separate) to write; a folder for the texture "
                    "presets")
        ->required();
    cmd->add_option("--preset", o->exporting.preset,
                    "map packing and naming: gltf (a glTF asset), unreal, unity-hdrp or exr (a "
                    "folder of textures)")
        ->capture_default_str();
    cmd->add_option("--bits", o->exporting.bits,
                    "bits per channel of the texture presets: 8 or 16 (PNG), 32 (float EXR); "
                    "exr: 16 (half) or 32 (default: 8, exr 32)");
    cmd->add_flag("--separate", o->exporting.separate,
                  "write a .gltf with its .bin and PNG maps beside it instead of one .glb");
    cmd->add_option("--name-template", o->exporting.name_template,
                    "file names of the maps with --separate ($mesh, $material, $map, $udim)")
        ->capture_default_str();
    cmd->add_option("--resolution", o->exporting.resolution,
                    "texels per side of the maps (default: the stack's)")
        ->check(CLI::Range(8, 16384));
    cmd->add_option("--normal-scale", o->exporting.normal_scale,
                    "height exaggeration of the normal map")
        ->check(CLI::Range(0.0, 1000.0))
        ->capture_default_str();
    cmd->add_option("--target", o->exporting.target,
                    "the renderer the glTF material is fitted for: khronos (three.js, "
                    "Babylon.js, the Khronos sample viewer: glTF's reference BRDF) or blender "
                    "(Blender 3.4's Principled BSDF, which adds its lobes to the diffuse)")
        ->capture_default_str();
    cmd->add_option("--mesh", o->exporting.mesh,
                    "the mesh a stack was grown on (default: the path the stack records)")
        ->check(CLI::ExistingFile);
    add_mesh_convention_options(*cmd, o->exporting.convention);
    cmd->add_option("--scene", o->scene,
                    ".vdb: a patina-render scene whose slab_volume medium gives the density's "
                    "sigma_t and the colour's albedos and gains (default: the medium's defaults)")
        ->check(CLI::ExistingFile);
    cmd->add_option("--medium", o->medium,
                    ".vdb with --scene: the name of the slab_volume shader (default: the first)");
    cmd->add_flag("-q,--quiet", o->quiet, "no summary line");
    cmd->callback([o] { run_export(*o); });
}

}  // namespace patina::texgen
