// `patina-texgen deposit`: where airborne deposits settle, from accessibility combined with
// visibility to deposit sources (Dorsey et al. 1999 §6); the formula is in
// texgen/deposit/deposit_baker.h, the source syntax in texgen/deposit/deposit_sources.h.
#include "texgen/cli/commands.h"

#include "core/cli_errors.h"
#include "texgen/cli/bake_command.h"
#include "texgen/deposit/deposit_baker.h"

#include <fmt/format.h>

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace patina::texgen {

namespace {

    struct DepositCommandOptions {
        CommonBakeOptions common;
        DepositParameters deposit;
        std::vector<std::string> sources;
        std::filesystem::path sources_file;
        std::string combine = "sum";
    };

    void run_deposit(DepositCommandOptions o)
    {
        DepositParameters& p = o.deposit;
        if (!o.sources_file.empty())
            p.sources = load_sources_file(o.sources_file);
        for (const std::string& text : o.sources)
            p.sources.push_back(parse_source_option(text));
        p.combine = o.combine == "product" ? DepositParameters::Combine::Product
                                           : DepositParameters::Combine::Sum;
        p.validate();

        std::string sources;
        for (const DepositSource& s : p.sources)
            sources += (sources.empty() ? "" : "; ") + s.describe();
        MapDescription map;
        map.name = "deposit";
        map.units = "1";
        map.description =
            o.combine == "product"
                ? "deposit in [0, 1]: (1 - accessibility)^accessibility_power * source visibility"
                : "deposit in [0, 1]: accessibility_weight * (1 - "
                  "accessibility)^accessibility_power "
                  "+ visibility_weight * source visibility";
        map.baker = "deposit";
        map.parameters = {
            {"sources", sources},
            {"sources_file", o.sources_file.string()},
            {"rays", p.rays},
            {"max_distance", p.max_distance},
            {"accessibility", p.accessibility_map.empty() ? std::string("inline ambient occlusion")
                                                          : p.accessibility_map.string()},
            {"accessibility_channel", p.accessibility_channel},
            {"access_rays", p.access_rays},
            {"access_distance", p.access_distance > 0.0f
                                    ? fmt::format("{}", p.access_distance)
                                    : std::string("0.1 x scene bounding-box diagonal")},
            {"accessibility_power", p.accessibility_power},
            {"accessibility_weight", p.accessibility_weight},
            {"visibility_weight", p.visibility_weight},
            {"combine", o.combine},
        };
        run_bake(
            o.common,
            [p](const BakeScene& s) {
                return std::make_unique<DepositBaker>(s.scene, s.bounds, p);
            },
            map);
    }

} // namespace

void register_deposit_command(CLI::App& app)
{
    auto o = std::make_shared<DepositCommandOptions>();
    CLI::App* cmd = app.add_subcommand(
        "deposit",
        "bake deposits: accessibility combined with visibility to deposit sources (Dorsey et "
        "al. 1999 §6); channel 'deposit' in [0, 1]");
    add_common_bake_options(*cmd, o->common);
    DepositParameters& p = o->deposit;
    cmd->add_option("--source", o->sources,
                    "a deposit source (repeatable): 'sphere center=X,Y,Z radius=R', 'disc "
                    "center=X,Y,Z normal=X,Y,Z radius=R', 'rectangle corner=X,Y,Z edge1=X,Y,Z "
                    "edge2=X,Y,Z' or 'directional direction=X,Y,Z spread_deg=A', each with an "
                    "optional strength=S");
    cmd->add_option("--sources", o->sources_file,
                    "TOML file of [[source]] tables (type = \"sphere\", ... the same keys)");
    cmd->add_option("--rays", p.rays,
                    "shadow rays per texel and source (split over its sub-samples)")
        ->capture_default_str()
        ->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--max-distance", p.max_distance,
                    "shadow-ray length for directional sources (m; default: no limit)")
        ->check(patina::positive);
    cmd->add_option("--accessibility", p.accessibility_map,
                    "accessibility map from `patina-texgen accessibility` (EXR; "
                    "NAME.<UDIM>.exr for tile sets); without it accessibility is estimated "
                    "inline as cosine-weighted ambient occlusion");
    cmd->add_option("--accessibility-channel", p.accessibility_channel,
                    "channel of the accessibility map")
        ->capture_default_str();
    cmd->add_option("--access-rays", p.access_rays, "inline accessibility estimate: rays per texel")
        ->capture_default_str()
        ->check(CLI::Range(1, 1 << 20));
    cmd->add_option("--access-distance", p.access_distance,
                    "inline accessibility estimate: ray length (m; default: a tenth of the "
                    "scene's bounding-box diagonal)");
    cmd->add_option("--accessibility-power", p.accessibility_power,
                    "exponent a of (1 - accessibility)^a")
        ->capture_default_str();
    cmd->add_option("--accessibility-weight", p.accessibility_weight,
                    "weight of (1 - accessibility)^a in the sum")
        ->capture_default_str();
    cmd->add_option("--visibility-weight", p.visibility_weight,
                    "weight of the source visibility in the sum")
        ->capture_default_str();
    cmd->add_option("--combine", o->combine,
                    "sum: weighted sum of the two terms; product: their product")
        ->capture_default_str()
        ->check(CLI::IsMember({"sum", "product"}));
    cmd->callback([o] { run_deposit(*o); });
}

} // namespace patina::texgen
