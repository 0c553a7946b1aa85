// The texture stack of an output folder: the file names of its maps and `stack.toml`, the
// manifest that lists them (record_in_manifest, declared in map_output.h, writes it).
//
//   [stack]
//   format = 1
//   generator = "patina-texgen 0.1.0"
//
//   [maps.ao]
//   file = "ao.exr"                 # or: pattern = "ao.<UDIM>.exr" and tiles = [1001, 1002]
//   domain = "texel"                # "vertex" for the PLY of the per-vertex mode
//   channels = ["ao"]
//   units = "1"
//   colorspace = "raw"
//   baker = "ao"
//   description = "..."
//   resolution = [1024, 1024]       # texels per tile (texel maps only)
//   [maps.ao.parameters]
//   samples = 64
#pragma once

#include "formats/texture_stack/stack_format.h"

#include <toml++/toml.h>

#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen {

/// Version of the stack.toml layout; a manifest of a newer version is not rewritten.
using formats::kStackFormatVersion;

/// `<out_dir>/stack.toml`.
std::filesystem::path manifest_path(const std::filesystem::path& out_dir);

/// The file of one tile of a texel map: "<name>.exr" when the map is the lone tile 1001,
/// else "<name>.<udim>.exr".
std::string map_file_name(const std::string& name, int udim, bool lone_1001_tile);

/// The UDIM file pattern of a map, as renderers spell it: "<name>.<UDIM>.exr".
std::string map_file_pattern(const std::string& name);

/// The manifest at `path` (this run's own version when it wrote one already), or an empty
/// table when there is none, for a writer to update. Throws, naming file and line, for one
/// that does not parse, declares a newer `[stack] format` or whose `maps` is not a table:
/// rewriting it would lose or misread other entries.
toml::table read_manifest_for_update(const std::filesystem::path& path);

/// Write `root` as the manifest at `path` (staged in the run's output transaction): the one
/// serialization of stack.toml every writer uses (the bakers' maps, patina's [patina],
/// flatten's [flatten]): a comment saying what the file is, `[stack]` first, then the rest
/// in toml++'s order.
void write_manifest(const std::filesystem::path& path, const toml::table& root);

/// Read and check `<out_dir>/stack.toml` as record_in_manifest would, and reserve it in the
/// current output transaction: a manifest that cannot be updated fails before the bake.
void check_manifest_can_be_updated(const std::filesystem::path& out_dir);

/// Drop from `<out_dir>/stack.toml` every map whose baker is `baker` and, when `table` is
/// not empty, the top-level table of that name; returns the files of the dropped maps
/// (relative to out_dir). Nothing happens without a manifest; one that does not parse
/// throws like record_in_manifest and is left unchanged.
std::vector<std::string> forget_maps_of(const std::filesystem::path& out_dir,
                                        const std::string& baker, const std::string& table = {});

}  // namespace patina::texgen
