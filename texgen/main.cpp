// patina-texgen: bakes per-texel maps (accessibility, exposure, wetness, ...) onto UV-mapped
// meshes, as tiled mip-mapped EXR texture stacks.
#include "texgen/cli/commands.h"
#include "texgen/cli/farm_plan.h"

#include "core/cancel.h"
#include "core/cli_errors.h"
#include "core/manual_page.h"
#include "core/output_transaction.h"
#include "core/progress.h"
#include "texgen/patina/script_error.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

int main(int argc, char** argv)
{
    // First of all: a SIGINT or SIGTERM that arrives while the options are read or the
    // plugins load must cancel the run (exit 130, nothing written), not kill it untidily.
    patina::install_cancel_handler();
    namespace pt = patina::texgen;
    CLI::App app{"patina-texgen: bake weathering maps onto UV-mapped meshes"};
    app.set_version_flag("--version", std::string("patina-texgen ") + PATINA_VERSION_STRING);
    app.require_subcommand(1);

    // Keep this list in the order of `patina-texgen --help`.
    pt::register_mesh_command(app);
    pt::register_uv_check_command(app);
    pt::register_unwrap_command(app);
    pt::register_ao_command(app);
    pt::register_accessibility_command(app);
    pt::register_sun_command(app);
    pt::register_sky_command(app);
    pt::register_exposure_command(app);
    pt::register_wetness_command(app);
    pt::register_deposit_command(app);
    pt::register_patina_command(app);
    pt::register_stone_command(app);
    pt::register_flatten_command(app);
    pt::register_fade_command(app);
    pt::register_forecast_command(app);
    pt::register_restore_command(app);
    pt::register_export_command(app);
    pt::register_view_command(app);

    // Each command's --help ends with its page of the manual.
    app.footer(patina::manual_footer("texgen.md"));
    for (const auto& [command, page] :
         {std::pair{"mesh", "texgen.md"}, std::pair{"uv-check", "texgen.md"}, std::pair{"unwrap", "your-asset.md"},
          std::pair{"ao", "texgen-ao.md"}, std::pair{"accessibility", "texgen-ao.md"},
          std::pair{"sun", "texgen-exposure.md"}, std::pair{"sky", "lookdev.md"}, std::pair{"exposure", "texgen-exposure.md"},
          std::pair{"wetness", "texgen-wetness.md"}, std::pair{"deposit", "texgen-wetness.md"},
          std::pair{"patina", "patina-script.md"}, std::pair{"stone", "stone.md"},
          std::pair{"flatten", "flatten.md"}, std::pair{"fade", "fading.md"},
          std::pair{"forecast", "forecast.md"}, std::pair{"restore", "forecast.md"},
          std::pair{"export", "export.md"}, std::pair{"view", "viewer.md"}})
        app.get_subcommand(command)->footer(patina::manual_footer(page));

    patina::refuse_non_finite_numbers(app);  // NaN and infinities, for every option
    try {
        // Every file the command writes is staged, and moves into place only when the
        // command has finished without error: all of its outputs, or none.
        patina::OutputTransaction outputs;
        const patina::CurrentOutputs current(outputs);
        pt::set_command_line(argc, argv);  // --plan's tasks repeat it
        app.parse(argc, argv);
        outputs.commit();
        return 0;
    } catch (const CLI::ParseError& e) {
        return patina::report_parse_error(app, e, "patina-texgen", argc, argv);
    } catch (const patina::CheckpointWritten& e) {
        std::fprintf(stderr, "\npatina-texgen: %s\n", e.what());
        return 130;
    } catch (const patina::Cancelled& e) {
        std::fprintf(stderr, "\npatina-texgen: %s; no output was written\n", e.what());
        return 130;
    } catch (const pt::ScriptError& e) {
        patina::end_progress_line();
        // Like a compiler: the script's file, line and column first.
        if (e.location().line > 0)
            std::fprintf(stderr, "patina-texgen: error: %s:%d:%d: %s\n",
                         patina::one_line(e.file()).c_str(), e.location().line,
                         e.location().column, patina::one_line(e.message()).c_str());
        else
            std::fprintf(stderr, "patina-texgen: error: %s: %s\n",
                         patina::one_line(e.file()).c_str(), patina::one_line(e.message()).c_str());
        return 1;
    } catch (const std::exception& e) {
        patina::end_progress_line();  // the message on a line of its own
        std::fprintf(stderr, "patina-texgen: error: %s\n", patina::one_line(e.what()).c_str());
        return 1;
    }
}
