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

/// The scene file's fingerprint (FNV-1a 64 of its bytes, 16 hex digits), written as
/// patina:scene_hash so that a merge can refuse parts of different scenes.
std::string scene_hash(const std::filesystem::path& scene_file);

/// Convert the film's XYZ to the working space, write `exr` (and `<stem>.png` when the scene
/// asks), each through a temporary name.
void write_film(const Scene& scene, const FilmResult& film, const std::filesystem::path& exr,
                const std::filesystem::path& scene_file, const ColorManager& colors);

}  // namespace patina::render
