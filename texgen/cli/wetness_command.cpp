// `patina-texgen wetness`: how wet each texel gets under rain (rain direction and spread,
// visibility, inclination, drying by an exposure map, water at the base); the formula is in
// texgen/wetness/wetness_baker.h.
#include "texgen/cli/commands.h"

#include "core/cli_errors.h"
#include "texgen/cli/bake_command.h"
#include "texgen/wetness/wetness_baker.h"

#include <fmt/format.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

namespace patina::texgen {

namespace {

    struct WetnessCommandOptions {
        CommonBakeOptions common;
        WetnessParameters wetness;
        std::vector<float> rain_dir; ///< empty: -up
        float base_level = 0.0f;
        bool base_level_given = false;
    };

    std::string vec_text(const Imath::V3f& v)
    {
        return fmt::format("{} {} {}", v.x, v.y, v.z);
    }

    void run_wetness(WetnessCommandOptions o)
    {
        WetnessParameters& p = o.wetness;
        p.up = Imath::V3f(0.0f, 1.0f, 0.0f);  // the mesh is read into +Y up (--up, --unit)
        p.rain_direction = o.rain_dir.size() == 3
                               ? Imath::V3f(o.rain_dir[0], o.rain_dir[1], o.rain_dir[2])
                               : Imath::V3f(0.0f) - p.up; // not -up: no "-0" in the header
        if (o.base_level_given)
            p.base_level = o.base_level;
        p.validate();

        MapDescription map;
        map.name = "wetness";
        map.units = "1";
        map.description = "wetness in [0, 1]: clamp((rain caught * max(0, N.up)^inclination_power "
                          "+ base) * (1 - drying * exposure / exposure_scale))";
        map.baker = "wetness";
        map.parameters = {
            {"rain_dir", vec_text(p.rain_direction)},
            {"up", vec_text(p.up)},
            {"spread_deg", p.spread_deg},
            {"inclination_power", p.inclination_power},
            {"rays", p.rays},
            {"max_distance", p.max_distance},
            {"exposure", p.exposure_map.string()},
            {"exposure_channel", p.exposure_channel.empty() ? std::string("exposure or irradiance")
                                                            : p.exposure_channel},
            {"drying", p.exposure_map.empty() ? 0.0f : p.drying},
            {"exposure_scale", p.exposure_scale > 0.0f ? fmt::format("{}", p.exposure_scale)
                                                       : std::string("map maximum")},
            {"base_height", p.base_height},
            {"base_amount", p.base_amount},
            {"base_level", p.base_level ? fmt::format("{}", *p.base_level)
                                        : std::string("lowest point of the mesh")},
        };
        run_bake(
            o.common,
            [p](const BakeScene& s) {
                return std::make_unique<WetnessBaker>(s.scene, s.target, p);
            },
            map);
    }

} // namespace

void register_wetness_command(CLI::App& app)
{
    auto o = std::make_shared<WetnessCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "wetness",
        "bake wetness under rain: rain caught with visibility (Dorsey et al. 1999 §6), wetter "
        "on horizontal surfaces, dried by an exposure map, wetter near the base (Dorsey & "
        "Hanrahan 1996 §5.2-5.3); channel 'wetness' in [0, 1]");
    add_common_bake_options(*cmd, o->common);
    WetnessParameters& p = o->wetness;
    cmd->add_option("--rain-dir", o->rain_dir,
                    "X Y Z: the direction the rain travels, in Patina's world (+Y up, "
                    "north -Z; default: straight down)")
        ->expected(3);
    cmd->add_option("--spread-deg", p.spread_deg,
                    "half-angle of the cone of rain directions, degrees in [0, 90)")
        ->capture_default_str();
    cmd->add_option("--inclination-power", p.inclination_power,
                    "wetness times max(0, N.up)^power: water runs off steep surfaces "
                    "(0: off)")
        ->capture_default_str();
    cmd->add_option("--rays", p.rays,
                    "rain rays per texel (split over its sub-samples, at least one each; one "
                    "without spread)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--max-distance", p.max_distance,
                    "ignore shelter farther than this along a ray (m; default: no limit)")
        ->check(patina::positive);
    cmd->add_option("--exposure", p.exposure_map,
                    "exposure map from `patina-texgen exposure` (EXR; NAME.<UDIM>.exr for tile "
                    "sets): wetness *= 1 - drying * clamp(exposure / exposure-scale)");
    cmd->add_option("--exposure-channel", p.exposure_channel,
                    "channel of the exposure map (default: 'exposure', else 'irradiance')");
    cmd->add_option("--drying", p.drying, "how much the most exposed point dries, in [0, 1]")
        ->capture_default_str();
    cmd->add_option("--exposure-scale", p.exposure_scale,
                    "exposure that counts as fully exposed (map units; default: the map's "
                    "maximum)");
    cmd->add_option("--base-height", p.base_height,
                    "extra wetness near the base, falling linearly to 0 at this height above "
                    "the base level (m; 0: off)")
        ->capture_default_str();
    cmd->add_option("--base-amount", p.base_amount, "extra wetness at the base level")
        ->capture_default_str();
    cmd->add_option_function<float>(
        "--base-level",
        [o](float v) {
            o->base_level = v;
            o->base_level_given = true;
        },
        "coordinate of the base along the up axis (m; default: the mesh's lowest point)");
    cmd->callback([o] { run_wetness(*o); });
}

} // namespace patina::texgen
