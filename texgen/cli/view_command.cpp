// `patina-texgen view SERIES.glb -o DIR`: the time-lapse viewer's folder (texgen/view).
#include "texgen/cli/commands.h"

#include "core/color_management.h"
#include "core/output_transaction.h"
#include "texgen/view/viewer_folder.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <cstdio>
#include <memory>

namespace patina::texgen {

void register_view_command(CLI::App& app)
{
    auto o = std::make_shared<ViewerOptions>();
    auto quiet = std::make_shared<bool>(false);
    CLI::App* cmd = app.add_subcommand(
        "view", "write a static folder that shows an exported glTF time series in a browser: "
                "an age slider blending the steps, a before/after split, the OCIO display "
                "transforms of patina-render (open index.html, or serve the folder)");
    cmd->add_option("model", o->model, "the .glb of `patina-texgen export` (a series: a "
                                       "material variant per age)")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("-o,--out", o->out, "the folder to write")->required();
    cmd->add_option("--title", o->title, "the page's title (default: the model's name)");
    cmd->add_flag("-q,--quiet", *quiet, "no summary line");
    cmd->callback([o, quiet] {
        reserve_output(o->out / "index.html");
        const ColorManager colors(ColorManager::default_config_path());
        const ViewerSummary s = write_viewer(*o, colors);
        if (!*quiet)
            std::fprintf(stderr, "view: %zu ages (%s), views %s -> %s/index.html\n",
                         s.ages.size(), fmt::format("{}", fmt::join(s.ages, ", ")).c_str(),
                         fmt::format("{}", fmt::join(s.views, ", ")).c_str(),
                         o->out.string().c_str());
    });
}

}  // namespace patina::texgen
