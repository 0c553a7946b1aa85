// patina-texgen uv-check MESH: the uv layout report (texels/uv_check.h) on stdout.
#include "texgen/cli/commands.h"
#include "texgen/cli/mesh_options.h"
#include "texgen/meshes/mesh_input.h"
#include "texgen/texels/uv_wrap.h"
#include "texgen/texels/uv_check.h"

#include <fmt/format.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <vector>

namespace patina::texgen {

namespace {

    struct UvCheckArguments {
        std::filesystem::path mesh;
        std::vector<int> resolution{1024, 1024};
        int supersampling = 2;
        bool strict = false;
        bool uv_wrap = false;
        MeshConventionOptions convention;
    };

    void run_uv_check(const UvCheckArguments& args)
    {
        MeshConvention convention;
        TriangleMesh mesh = load_mesh_with_warnings(args.mesh, args.convention, &convention);
        const size_t wrapped = args.uv_wrap ? wrap_uvs_outside_udims(mesh) : 0;
        UvCheckOptions options;
        options.width = args.resolution.front();
        options.height = args.resolution.back();
        options.supersampling = args.supersampling;
        UvCheck check = check_uvs(mesh, options);
        check.uv_wrap = args.uv_wrap;
        check.wrapped_triangles = wrapped;
        std::fputs(
            fmt::format("file             {}\naxes and unit    {}\n{}", args.mesh.string(),
                        convention.describe(), format_uv_check(check))
                .c_str(),
            stdout);
        std::fflush(stdout);
        if (const std::string refusal = check.refusal(); !refusal.empty() && check.has_uvs)
            throw std::runtime_error(fmt::format("uv-check: the bakers will refuse mesh file "
                                                 "'{}': {}", args.mesh.string(), refusal));
        if (args.strict && !check.has_uvs)
            throw std::runtime_error(fmt::format("uv-check --strict: mesh file '{}' has no uvs",
                                                 args.mesh.string()));
        if (args.strict && check.overlaps())
            throw std::runtime_error(fmt::format(
                "uv-check --strict: mesh file '{}' has overlapping uvs ({:.3g}% of the covered "
                "uv area, {} triangle pairs)",
                args.mesh.string(), 100.0 * check.overlap_fraction(),
                check.overlapping_triangle_pairs));
    }

}  // namespace

void register_uv_check_command(CLI::App& app)
{
    auto args = std::make_shared<UvCheckArguments>();
    CLI::App* command = app.add_subcommand(
        "uv-check", "Report a mesh's uv layout before baking: missing uvs, uv islands, "
                    "overlapping uv area, texel density, UDIM tiles, degenerate triangles");
    command->add_option("mesh", args->mesh, "Mesh file (any format Assimp reads); all its "
                                            "meshes are checked as one")
        ->required();
    command
        ->add_option("--resolution", args->resolution,
                     "Map size in texels, W H (or one value for a square map), for the texel "
                     "density and the overlap measure")
        ->expected(1, 2)
        ->capture_default_str();
    command
        ->add_option("--supersampling", args->supersampling,
                     "Sub-samples per texel axis for the overlap measure (1..8)")
        ->capture_default_str();
    add_mesh_convention_options(*command, args->convention);
    command->add_flag("--uv-wrap", args->uv_wrap,
                      "check the layout the bakers' --uv-wrap makes (uvs outside the UDIM tiles "
                      "folded into tile 1001)");
    command->add_flag("--strict", args->strict,
                      "Exit with status 1 when the mesh has no uvs or overlapping uvs");
    command->callback([args] { run_uv_check(*args); });
}

}  // namespace patina::texgen
