// patina-farm: Patina's renders, bakes and simulations on a render farm (docs/farm.md).
#include "farm/frame_merge.h"

#include "core/cancel.h"
#include "core/cli_errors.h"
#include "core/manual_page.h"
#include "core/output_transaction.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct MergeOptions {
    std::vector<fs::path> parts;
    fs::path output;
    bool quiet = false;
};

void register_merge(CLI::App& app)
{
    auto o = std::make_shared<MergeOptions>();
    CLI::App* cmd = app.add_subcommand(
        "merge", "merge the parts of a frame a farm rendered — tiles or crops, and sample "
                 "ranges (--samples) — into one EXR, checking that they belong together");
    cmd->add_option("parts", o->parts, "the parts: EXRs written by patina-render")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("-o,--out", o->output, "the merged EXR")->required();
    cmd->add_flag("-q,--quiet", o->quiet, "no summary line");
    cmd->callback([o] {
        const patina::farm::MergeResult r = patina::farm::merge_render_parts(o->parts, o->output);
        if (!o->quiet)
            std::fprintf(stderr, "merge: %zu part(s), samples %d-%d, pixels [%d, %d) x [%d, %d) "
                                 "-> %s\n",
                         r.parts, r.sample_begin, r.sample_end, r.x, r.x + r.width, r.y,
                         r.y + r.height, o->output.string().c_str());
    });
    cmd->footer(patina::manual_footer("farm.md"));
}

}  // namespace

int main(int argc, char** argv)
{
    CLI::App app{"patina-farm: Patina's renders, bakes and simulations on a render farm"};
    app.set_version_flag("--version", std::string("patina-farm ") + PATINA_VERSION_STRING);
    app.require_subcommand(1);
    register_merge(app);
    app.footer(patina::manual_footer("farm.md"));

    patina::install_cancel_handler();
    try {
        patina::OutputTransaction outputs;
        const patina::CurrentOutputs current(outputs);
        app.parse(argc, argv);
        outputs.commit();
        return 0;
    } catch (const CLI::ParseError& e) {
        return patina::report_parse_error(app, e, "patina-farm", argc, argv);
    } catch (const patina::Cancelled& e) {
        std::fprintf(stderr, "\npatina-farm: %s; no output was written\n", e.what());
        return 130;
    } catch (const std::exception& e) {
        std::fprintf(stderr, "patina-farm: error: %s\n", patina::one_line(e.what()).c_str());
        return 1;
    }
}
