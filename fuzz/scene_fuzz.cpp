// libFuzzer harness: the scene reader of patina-render (src/render/scene.h), parse and build
// with the bundled plugins. Bad input must end in an exception (the tool's one-line error);
// a crash or a sanitizer report is a bug. Meshes, textures and plugin folders a mutated scene
// names are refused like any missing file.
#include "render/plugin_setup.h"
#include "render/scene.h"

#include "host/host.h"
#include "host/plugin_registry.h"

#include <unistd.h>

#include <cstddef>
#include <cstdlib>
#include <cstdint>
#include <exception>
#include <fstream>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    static patina::PluginRegistry* registry = [] {
        ::setenv("OCIO", PATINA_FUZZ_OCIO_CONFIG, 0);  // the source tree's config
        auto* r = new patina::PluginRegistry(patina::default_host().c_host());
        patina::render::PluginSearch search;
        search.bundled = false;
        search.environment = false;
        search.command_line = {PATINA_FUZZ_PLUGIN_DIR};
        patina::render::load_plugins(*r, search);
        return r;
    }();
    static const std::string path = "/tmp/patina_fuzz_scene_" + std::to_string(::getpid()) + ".toml";
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    try {
        const patina::render::SceneFile file = patina::render::parse_scene_file(path);
        // Scene plugin folders are never loaded here (the renderer refuses them by default).
        if (file.plugin_dirs.empty())
            patina::render::build_scene(file, *registry, patina::default_host());
    } catch (const std::exception&) {
    }
    patina::default_host().take_errors();
    return 0;
}
