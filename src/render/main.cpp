// patina-render: renders a Patina scene through the shading plugins, or lists the shaders.
#include "render/plugin_setup.h"
#include "render/renderer.h"

#include "core/cancel.h"
#include "core/cli_errors.h"
#include "core/manual_page.h"
#include "core/progress.h"
#include "host/host.h"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

int main(int argc, char** argv)
{
    // First of all: a SIGINT or SIGTERM that arrives while the options are read or the
    // plugins load must cancel the run (exit 130, nothing written), not kill it untidily.
    patina::install_cancel_handler();
    namespace pr = patina::render;
    CLI::App app{"patina-render: spectral path tracer with Patina shading plugins"};
    app.set_version_flag("--version", std::string("patina-render ") + PATINA_VERSION_STRING);
    app.footer(patina::manual_footer("render.md") + "; scenes: docs/scene-format.md");

    std::string scene_file;
    bool list = false;
    pr::PluginSearch search;
    std::vector<std::string> plugin_paths;
    bool no_bundled = false;
    pr::RenderOptions options;

    app.add_option("scene", scene_file, "scene file (TOML; '#' runs become the frame number with --frames)");
    app.add_flag("--list-shaders", list, "print every shader the plugins provide, with parameters");
    std::string list_format = "text";
    app.add_option("--format", list_format,
                   "with --list-shaders: text, or markdown (the shader reference, docs/shaders.md)")
        ->check(CLI::IsMember({"text", "markdown"}))
        ->needs("--list-shaders");
    app.add_option("--plugin-path", plugin_paths,
                   "a folder of plugins to load (repeatable; also $PATINA_PLUGIN_PATH)");
    app.add_flag("--allow-scene-plugins", search.allow_scene_plugins,
                 "load the plugin folders a scene's [plugins] path names (native code: only for "
                 "scenes you trust; see also the trust file)");
    app.add_flag("--no-bundled-plugins", no_bundled,
                 "do not load the plugins shipped next to patina-render");
    app.add_option("-o,--output", options.output,
                   "output EXR (a display PNG is written beside it); default from the scene");
    app.add_option("--spp", options.spp, "samples per pixel (overrides the scene)")
        ->check(patina::positive)
        ->check(CLI::Range(1, 1 << 20));
    app.add_option("--seed", options.seed, "random seed (overrides the scene)");
    app.add_option("--threads", options.threads, "worker threads (0 = all cores)")
        ->check(patina::non_negative);
    app.add_option("--resolution", options.resolution,
                   "width and height, 1 to 32768 each, as in the scene (overrides the scene)")
        ->expected(2)->check(CLI::Range(1, 1 << 15));
    app.add_option("--crop", options.crop, "render only pixels [x0, x1) x [y0, y1) of the frame")
        ->expected(4);
    app.add_option("--tile", options.tile,
                   "render farm tile i of n (0-based bands of rows); merge the tiles with "
                   "oiiotool --add");
    app.add_option("--frames", options.frames,
                   "frame range first-last; a run of '#' in the scene and output paths becomes "
                   "the zero-padded frame number");
    app.add_option("--time-limit", options.time_limit,
                   "seconds; stop after the sample pass that crosses it (spp in the EXR header)")
        ->check(patina::positive);
    app.add_option("--samples", options.samples,
                   "A-B: render samples A to B - 1 of every pixel (the same random streams as "
                   "the whole render), for a farm's sample split; excludes --spp");
    app.add_flag("--checkpoint", options.checkpoint,
                 "keep the film's exact sums in the EXR (a part \"sums\") so that the render "
                 "can be continued with --resume");
    app.add_option("--resume", options.resume,
                   "continue the render of this EXR (written with --checkpoint) to the scene's "
                   "or --spp's samples: bitwise the render that never stopped")
        ->check(CLI::ExistingFile);
    app.add_flag("--quiet", options.quiet, "no progress on stderr");

    patina::refuse_non_finite_numbers(app);  // NaN and infinities, for every option
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError& e) {
        return patina::report_parse_error(app, e, "patina-render", argc, argv);
    }
    if (!list && scene_file.empty()) {
        std::fprintf(stderr, "patina-render: error: give a scene file or --list-shaders (see --help)\n");
        return 2;
    }

    try {
        search.bundled = !no_bundled;
        search.command_line.assign(plugin_paths.begin(), plugin_paths.end());
        if (list) {
            patina::PluginRegistry registry(patina::default_host().c_host());
            pr::load_plugins(registry, search);
            const std::string text = list_format == "markdown"
                                         ? pr::list_shaders_markdown(registry)
                                         : pr::list_shaders(registry);
            std::fputs(text.c_str(), stdout);
            return 0;
        }
        pr::render_scene_file(scene_file, search, options);
        return 0;
    } catch (const pr::CheckpointWritten& e) {
        std::fprintf(stderr, "\npatina-render: %s\n", e.what());
        return 130;
    } catch (const patina::Cancelled& e) {
        std::fprintf(stderr, "\npatina-render: %s; the interrupted frame's outputs were not "
                             "written, earlier files are as they were\n", e.what());
        return 130;
    } catch (const std::exception& e) {
        patina::end_progress_line();  // the message on a line of its own
        std::fprintf(stderr, "patina-render: error: %s\n", patina::one_line(e.what()).c_str());
        return 1;
    }
}
