// patina-render's top level: load a scene file, load the plugins it needs, render, write.
#pragma once

#include "render/plugin_setup.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <vector>

namespace patina::render {

/// Command-line overrides of the scene's [film] and [output] settings.
struct RenderOptions {
    std::filesystem::path output;    ///< EXR path; empty = the scene's [output] file
    std::optional<int> spp;
    std::optional<uint64_t> seed;
    int threads = 0;                 ///< 0 = every core
    std::vector<int> resolution;     ///< {} or {width, height}
    bool quiet = false;
};

/// Render `scene_file` and write its outputs (scene-linear EXR + display PNG). Throws
/// std::exception with a message naming the file, line and key on any error; writes
/// nothing unless the render completed.
void render_scene_file(const std::filesystem::path& scene_file, PluginSearch search,
                       const RenderOptions& options);

}  // namespace patina::render

namespace patina::render {
struct Scene;
/// Render to an interleaved CIE XYZ (D65, Y = 1 for a unit white) float image.
std::vector<float> render_xyz(const Scene& scene, int threads, bool quiet);
}  // namespace patina::render
