// `patina-texgen flatten STACK`: a patina stack (Dorsey & Hanrahan 1996 §4) flattened into
// maps for renderers without layered shading: KM diffuse albedo, per-interface specular
// colour and roughness, height, normal, and a two-lobe glTF (clearcoat) reduction.
#include "texgen/cli/commands.h"

#include "core/cli_errors.h"
#include "core/color_management.h"
#include "texgen/flatten/flatten_stack.h"
#include "texgen/flatten/patina_stack_files.h"

#include <fmt/format.h>

#include <chrono>
#include <cstdio>
#include <memory>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

struct FlattenCommandOptions {
    fs::path stack;
    fs::path out_dir;
    FlattenOptions flatten;
    std::string target = "khronos";
    bool quiet = false;
};

void run_flatten(const FlattenCommandOptions& o)
{
    const auto start = std::chrono::steady_clock::now();
    flatten_colorspace(o.flatten.color_space);  // a bad option fails before any work
    FlattenOptions options = o.flatten;
    options.target = gltf_target(o.target);
    ColorManager colors(ColorManager::default_config_path());
    const PatinaStackFiles stack = read_patina_stack(o.stack);
    const FlattenedStack flat = flatten_stack(stack, colors, options);
    const auto written = write_flattened(o.out_dir, flat, stack, options, colors);
    if (!o.quiet) {
        const double seconds =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        std::fprintf(stderr, "flatten: %s, %zu layer(s) over %s, %dx%d x %zu tile(s) -> %zu "
                             "files in %s (%.2f s)\n",
                     stack.manifest.string().c_str(), stack.layers.size(), stack.base.c_str(),
                     flat.width, flat.height, flat.udims.size(), written.size(),
                     o.out_dir.string().c_str(), seconds);
    }
}

}  // namespace

void register_flatten_command(CLI::App& app)
{
    auto o = std::make_shared<FlattenCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "flatten", "flatten a patina stack (D&H 1996 §4) into maps for other renderers: KM "
                   "diffuse albedo, per-interface specular and roughness, height, normal, and a "
                   "glTF metallic-roughness + clearcoat reduction");
    cmd->add_option("stack", o->stack, "a stack folder written by `patina-texgen patina`, or "
                                       "its stack.toml")->required();
    cmd->add_option("-o,--out", o->out_dir, "output folder (may be the stack's own)")
        ->required();
    cmd->add_option("--color-space", o->flatten.color_space,
                    "colour maps: srgb (sRGB-encoded) or acescg (linear ACEScg)")
        ->capture_default_str();
    cmd->add_option("--resolution", o->flatten.resolution,
                    "texels per tile side of the output (default: the stack's)")
        ->check(CLI::Range(8, 16384));
    cmd->add_option("--texel-size", o->flatten.texel_size_m,
                    "metres per texel for the normal map (default: a strip's size / resolution; "
                    "required for a mesh)")->check(patina::positive);
    cmd->add_option("--normal-scale", o->flatten.normal_scale,
                    "height exaggeration of the normal map (1: true relief)")
        ->capture_default_str()->check(patina::positive);
    cmd->add_option("--target", o->target,
                    "the renderer the gltf_* maps are fitted for: khronos (glTF's reference "
                    "BRDF: three.js, Babylon.js) or blender (Blender 3.4's Principled BSDF)")
        ->capture_default_str();
    cmd->add_flag("--half", o->flatten.half, "write half-float maps");
    cmd->add_flag("-q,--quiet", o->quiet, "no summary line");
    cmd->callback([o] { run_flatten(*o); });
}

}  // namespace patina::texgen
