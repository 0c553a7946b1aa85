// `patina-texgen export INPUT -o FILE`: a patina stack or time series as glTF 2.0 that other
// programs open already wired (texgen/export/export_patina.h; docs/export.md).
#include "texgen/cli/commands.h"

#include "core/color_management.h"
#include "texgen/export/export_patina.h"
#include "texgen/export/vdb_export.h"
#include "texgen/patina/material_library.h"

#include <chrono>
#include <cstdio>
#include <memory>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

struct ExportCommandOptions {
    fs::path input;
    fs::path output;
    std::vector<fs::path> materials;
    ExportOptions exporting;
    bool quiet = false;
};

void run_export(const ExportCommandOptions& o)
{
    const auto start = std::chrono::steady_clock::now();
    const ColorManager colors(ColorManager::default_config_path());
    if (o.output.extension() == ".vdb") {
        // A stone run's volumes as OpenVDB, one file per step.
        const std::vector<fs::path> files = export_stone_vdb(o.input, o.output, {}, colors);
        if (!o.quiet)
            std::fprintf(stderr, "export: %s, %zu stone volume(s) -> %s%s (%.2f s)\n",
                         o.input.string().c_str(), files.size(), files.front().string().c_str(),
                         files.size() > 1 ? " ..." : "",
                         std::chrono::duration<double>(std::chrono::steady_clock::now() - start)
                             .count());
        return;
    }
    const MaterialLibrary library = MaterialLibrary::load_default(o.materials, colors);
    const ExportResult r = export_patina(o.input, o.output, o.exporting, library, colors);
    if (!o.quiet) {
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "export: %s, %zu step(s) of %dx%d, %zu texture(s) -> %s (%.2f s)\n",
                     o.input.string().c_str(), r.steps, r.width, r.height, r.textures,
                     o.output.string().c_str(), seconds);
    }
}

}  // namespace

void register_export_command(CLI::App& app)
{
    auto o = std::make_shared<ExportCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "export", "export a patina stack or time series as glTF 2.0 (a .glb, or .gltf with "
                  "--separate): the strip at its real size, metallic-roughness + clearcoat "
                  "maps, one material variant per step named by age; or as textures packed "
                  "for Unreal, Unity HDRP or look files (--preset)");
    cmd->add_option("input", o->input, "a stack folder or its stack.toml, or a time-series "
                                       "folder (series.toml) written by `patina-texgen patina`; "
                                       "with -o X.vdb a `patina-texgen stone` output folder")
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
    cmd->add_option("--materials", o->materials,
                    "extra material library files (the ones the stack was made with)")
        ->check(CLI::ExistingFile);
    cmd->add_flag("-q,--quiet", o->quiet, "no summary line");
    cmd->callback([o] { run_export(*o); });
}

}  // namespace patina::texgen
