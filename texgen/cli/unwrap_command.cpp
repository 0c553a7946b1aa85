// patina-texgen unwrap MESH -o OUT.glb: a uv set for weathering, made by Blender headless
// (texgen/unwrap/unwrap.h), and how good it is.
#include "texgen/cli/commands.h"
#include "texgen/cli/mesh_options.h"
#include "texgen/unwrap/unwrap.h"

#include "core/progress.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <memory>

namespace patina::texgen {

namespace {

    struct UnwrapArguments {
        std::filesystem::path mesh;
        std::filesystem::path output;
        MeshConventionOptions convention;
        UnwrapOptions options;
        bool quiet = false;
    };

} // namespace

void register_unwrap_command(CLI::App& app)
{
    auto a = std::make_shared<UnwrapArguments>();
    CLI::App* cmd = app.add_subcommand(
        "unwrap", "give a mesh a uv set of its own for weathering (Blender's Smart UV Project or "
                  "Lightmap Pack, headless): every surface point its own texels; writes a .glb "
                  "with the artist's uvs first and the new set after them");
    cmd->add_option("mesh", a->mesh, "the mesh (any format Assimp reads)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("-o,--out", a->output, "the .glb to write")->required();
    add_mesh_convention_options(*cmd, a->convention);
    cmd->add_option("--method", a->options.method,
                    "smart (Smart UV Project: islands split at sharp edges) or lightmap "
                    "(Lightmap Pack: a square per face pair, even texel density)")
        ->capture_default_str()
        ->check(CLI::IsMember({"smart", "lightmap"}));
    cmd->add_option("--angle-limit", a->options.angle_limit_deg,
                    "smart: faces meeting at more than this many degrees start new islands")
        ->capture_default_str()
        ->check(CLI::Range(1.0, 89.0));
    cmd->add_option("--margin", a->options.margin,
                    "space between islands, a fraction of the tile (0.005 is 5 texels at 1024)")
        ->capture_default_str()
        ->check(CLI::Range(0.0, 0.1));
    cmd->add_option("--resolution", a->options.resolution,
                    "texels per side the report's utilisation is measured at")
        ->capture_default_str()
        ->check(CLI::Range(16, 8192));
    cmd->add_option("--blender", a->options.blender, "the Blender to run")->capture_default_str();
    cmd->add_flag("-q,--quiet", a->quiet, "no report");
    cmd->callback([a] {
        const UnwrapReport report = unwrap_mesh(a->mesh, a->convention, a->output, a->options);
        if (!a->quiet)
            std::fputs(format_unwrap_report(report).c_str(), stdout);
        if (report.overlap_fraction > 0.0)
            print_warning("patina-texgen",
                          fmt::format("unwrap: {:.3g}% of the new layout's covered area still "
                                      "overlaps (islands folding over themselves): try "
                                      "--angle-limit {:g}, or --method lightmap",
                                      100.0 * report.overlap_fraction,
                                      std::floor(a->options.angle_limit_deg * 0.66)));
    });
}

} // namespace patina::texgen
