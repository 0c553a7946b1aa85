// Writing a rendered film: working-space EXR (beauty and AOV channels, a crop or tile as the
// data window of the full frame) and the display PNG through an OCIO view.
#pragma once

#include "render/renderer.h"
#include "render/scene.h"

#include "core/color_management.h"

#include <filesystem>
#include <string>
#include <vector>

namespace patina::render {

/// Throws when `exr` is not an .exr path in an existing folder.
void check_output_path(const std::filesystem::path& exr);

/// The files write_film writes for `exr`: the EXR, and the PNG beside it when the scene
/// asks for one.
std::vector<std::filesystem::path> film_files(const Scene& scene, const std::filesystem::path& exr);

/// The scene file's fingerprint (core/file_fingerprint.h), written as patina:scene_hash so
/// that a merge can refuse parts of different scenes.
std::string scene_hash(const std::filesystem::path& scene_file);

/// What a continued render needs from an EXR written with --checkpoint: its part "sums"
/// (the film's per-pixel sums, each double as the two 32-bit halves of its bits: channels
/// d<NN>.hi, d<NN>.lo, NN counting the xyz, albedo, normal and depth sums of a pixel in
/// that order) and the header fields that say which render it is.
struct Checkpoint {
    FilmSums sums;
    int sample_begin = 0, sample_end = 0;
    std::string scene_hash;
    int seed = 0;
    int full_width = 0, full_height = 0;
    Region region;
};

/// Reads `exr`'s checkpoint; throws std::runtime_error naming the file when it has no part
/// "sums" (it was not written with --checkpoint) or a malformed one.
Checkpoint read_checkpoint(const std::filesystem::path& exr);

/// Convert the film's XYZ to the working space, write `exr` (and `<stem>.png` when the scene
/// asks), each through a temporary name. `plugins` (scene_plugin_set) goes into the header
/// as patina:plugins. When the film kept its sums, they go into a second part "sums".
void write_film(const Scene& scene, const FilmResult& film, const std::filesystem::path& exr,
                const std::filesystem::path& scene_file, const std::string& plugins,
                const ColorManager& colors);

}  // namespace patina::render
