// `patina-texgen accessibility`: Miller's accessibility (Dorsey & Hanrahan 1996 §3.2), by
// the largest tangent sphere or by the height of the surface closed by a ball.
#include "texgen/cli/commands.h"

#include "texgen/accessibility/offset_surface_baker.h"
#include "texgen/accessibility/tangent_sphere_baker.h"
#include "texgen/cli/bake_command.h"

#include <memory>
#include <string>

namespace patina::texgen {

namespace {

    struct AccessibilityCommandOptions {
        CommonBakeOptions common;
        std::string method = "tangent-sphere";
        float max_radius = 0.1f;
        int voxels = 256;
    };

    void run_accessibility(const AccessibilityCommandOptions& o)
    {
        MapDescription map;
        map.name = "accessibility";
        map.baker = "accessibility";
        map.parameters = {{"method", o.method}, {"max_radius", o.max_radius}};
        BakerFactory factory;
        if (o.method == "tangent-sphere") {
            map.units = "1 (accessibility), m (accessibility_radius)";
            map.description = "Miller's accessibility: radius of the largest empty sphere "
                              "tangent at the point, over max_radius (1 = open)";
            const TangentSphereOptions options{o.max_radius};
            factory = [options](const BakeScene& s) {
                return std::make_unique<TangentSphereBaker>(s.scene, options);
            };
        } else {
            map.units = "1 (accessibility), m (offset_height)";
            map.description = "Miller's offset-surface accessibility: height of the surface "
                              "closed by a ball of radius max_radius above the point; "
                              "accessibility = 1 - height / max_radius (1 = open)";
            map.parameters.push_back({"voxels", o.voxels});
            const OffsetSurfaceOptions options{o.max_radius, o.voxels};
            factory = [options](const BakeScene& s) {
                return std::make_unique<OffsetSurfaceBaker>(s.scene, s.bounds, options);
            };
        }
        run_bake(o.common, factory, map);
    }

}  // namespace

void register_accessibility_command(CLI::App& app)
{
    auto options = std::make_shared<AccessibilityCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "accessibility",
        "bake Miller's accessibility: how large a ball can touch the surface (tangent-sphere: "
        "the largest empty tangent sphere; offset-surface: how deep below the surface closed "
        "by a ball of radius --max-radius the point lies)");
    add_common_bake_options(*cmd, options->common);
    cmd->add_option("--method", options->method, "tangent-sphere or offset-surface")
        ->capture_default_str()
        ->check(CLI::IsMember({"tangent-sphere", "offset-surface"}));
    cmd->add_option("--max-radius", options->max_radius,
                    "m: the cap and normalisation of the tangent-sphere radius, or the ball "
                    "radius of the offset surface")
        ->capture_default_str();  // checked by the bakers, which name the option
    cmd->add_option("--voxels", options->voxels,
                    "offset-surface: voxels along the longest side of the scene bounds "
                    "(8 to 2048; memory ~12 bytes per voxel)")
        ->capture_default_str();
    cmd->callback([options] { run_accessibility(*options); });
}

}  // namespace patina::texgen
