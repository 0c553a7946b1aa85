// `patina-texgen export` of a baked texture stack: the maps `patina-texgen flatten` wrote
// (gltf_base_color, gltf_metallic_roughness, gltf_clearcoat, normal, height), read back
// and encoded by the writers every export shares (export_asset.h), without flattening
// again — for a pipeline that keeps the flattened maps, edits them, or no longer has the
// thickness maps. The geometry is the stack they came from (its strip or mesh).
#pragma once

#include "core/color_management.h"
#include "texgen/export/export_patina.h"

#include <filesystem>

namespace patina::texgen {

/// True when `input` (a folder or its stack.toml) holds flatten's maps and no patina stack
/// (a folder with both is exported from its stack, which flattens the same maps afresh).
bool is_flattened_stack(const std::filesystem::path& input);

/// Exports the flattened maps at `input` to `output`. The colour map is read in the colour
/// space its manifest entry declares. Throws std::runtime_error naming the file for a
/// missing map, maps of different sizes, a NaN texel, or a mesh that cannot be found.
ExportResult export_flattened(const std::filesystem::path& input,
                              const std::filesystem::path& output, const ExportOptions& options,
                              const ColorManager& colors);

}  // namespace patina::texgen
