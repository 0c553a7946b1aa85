// Shared by the renderer tests: scenes written to the build tree, loaded with the built
// plugins, and small measurements of rendered films.
#pragma once

#include "render/renderer.h"
#include "render/scene.h"

#include "core/color_management.h"
#include "host/host.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>

#include <unistd.h>

namespace fs = std::filesystem;
namespace pr = patina::render;

namespace render_test {

inline fs::path write_scene(const std::string& name, const std::string& text)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "render_scenes";
    fs::create_directories(dir);
    const fs::path p = dir / (name + ".toml");
    // Under a name of this process's own, then renamed: tests that run side by side (ctest
    // -j) write the same scene, and one must never read another's half-written file.
    const fs::path tmp = dir / (name + ".tmp" + std::to_string(::getpid()) + ".toml");
    std::ofstream(tmp) << text;
    fs::rename(tmp, p);
    return p;
}

struct Loaded {
    patina::PluginRegistry registry{patina::default_host().c_host()};
    pr::Scene scene;
};

inline std::unique_ptr<Loaded> load(const fs::path& path)
{
    auto l = std::make_unique<Loaded>();
    const pr::SceneFile file = pr::parse_scene_file(path);
    pr::PluginSearch search;
    search.bundled = false;
    search.environment = false;
    search.command_line = {PATINA_TEST_PLUGIN_DIR};
    search.scene = file.plugin_dirs;
    pr::load_plugins(l->registry, search);
    l->scene = pr::build_scene(file, l->registry, patina::default_host());
    return l;
}

inline std::string error_of(const std::string& name, const std::string& text)
{
    try {
        load(write_scene(name, text));
    } catch (const std::exception& e) {
        return e.what();
    }
    ADD_FAILURE() << "no error for scene " << name;
    return {};
}

inline const char* kWhiteFurnace = R"(
[film]
width = 24
height = 16
spp = 32
seed = 7
[camera]
from = [0, 0, 4]
to = [0, 0, 0]
fov_deg = 40
[environment]
color = [1, 1, 1]
[[shader]]
name = "white"
type = "lambert"
reflectance = 1.0
[[object]]
shape = "sphere"
radius = 1.0
bsdf = "white"
)";

inline double mean_y(const std::vector<float>& xyz)
{
    double sum = 0.0;
    for (size_t i = 0; i < xyz.size(); i += 3)
        sum += xyz[i + 1];
    return sum / static_cast<double>(xyz.size() / 3);
}

}  // namespace render_test
