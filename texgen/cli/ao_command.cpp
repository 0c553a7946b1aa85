// `patina-texgen ao`: cosine-weighted ambient occlusion per texel (or vertex), for
// comparison with Miller's accessibility.
#include "texgen/cli/commands.h"

#include "texgen/ao/ao_baker.h"
#include "texgen/cli/bake_command.h"

#include <limits>
#include <memory>

namespace patina::texgen {

namespace {

    struct AoCommandOptions {
        CommonBakeOptions common;
        AoOptions ao;
    };

    void run_ao(const AoCommandOptions& o)
    {
        MapDescription map;
        map.name = "ao";
        map.units = "1";
        map.description = "ambient occlusion: the unoccluded fraction of the cosine-weighted "
                          "hemisphere about the normal (1 = open)";
        map.baker = "ao";
        map.parameters = {{"rays", o.ao.rays}, {"max_distance", o.ao.max_distance}};
        const AoOptions ao = o.ao;
        run_bake(o.common, [ao](const BakeScene& s) { return std::make_unique<AoBaker>(s.scene, ao); },
                 map);
    }

}  // namespace

void register_ao_command(CLI::App& app)
{
    auto options = std::make_shared<AoCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "ao", "bake ambient occlusion: the fraction of cosine-weighted rays about the normal "
              "that escape the scene (channel 'ao', 1 = open)");
    add_common_bake_options(*cmd, options->common);
    cmd->add_option("--rays", options->ao.rays,
                    "rays per texel (split over its sub-samples, at least one each)")
        ->capture_default_str();  // checked by AoBaker, which names the option
    cmd->add_option("--max-distance", options->ao.max_distance,
                    "ignore occluders farther than this along a ray (m; default: no limit)");
    cmd->callback([options] { run_ao(*options); });
}

}  // namespace patina::texgen
