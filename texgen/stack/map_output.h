// Writing baked values: tiled, mip-mapped EXR maps (one per UDIM tile) after push-pull
// padding, the per-vertex PLY, and the stack.toml manifest of an output folder.
#pragma once

#include "formats/texture_stack/texture_stack.h"

#include "core/image_io.h"
#include "core/mesh.h"
#include "texgen/texels/texel_grid.h"

#include <OpenImageIO/typedesc.h>

#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen {

/// The coverage channel every texel map carries (formats/texture_stack/texture_stack.h).
using formats::kCoverageChannel;

/// What a map is, for its file header and the manifest.
struct MapDescription {
    std::string name;                   ///< file stem and manifest key, e.g. "ao"
    std::vector<std::string> channels;  ///< channel names, e.g. {"ao"}
    std::string units;                  ///< "1" (dimensionless), "m", "J/m^2", "W/m^2"
    std::string description;            ///< one line: what the value means
    std::string baker;                  ///< sub-command that made it, e.g. "accessibility"
    Metadata parameters;                ///< every parameter of the bake (EXR header + manifest)
};

struct MapOutputOptions {
    int padding = 16;  ///< texels of push-pull padding around covered texels; -1: all
    OIIO::TypeDesc format = OIIO::TypeDesc::FLOAT;  ///< FLOAT or HALF
    int tile_size = 64;
};

/// Write one tiled, mip-mapped EXR per tile: `<out_dir>/<name>.exr` when the only tile is
/// 1001, else `<out_dir>/<name>.<UDIM>.exr` per tile. `values[i]` holds tiles[i]'s groups,
/// group-major with map.channels.size() channels (as bake_groups returns). The file holds
/// those channels, padded (MapOutputOptions::padding), then the coverage channel
/// kCoverageChannel from the tile's coverage, unpadded. Returns the files written. Every
/// file is written under a temporary name and renamed.
std::vector<std::filesystem::path> write_texel_map(const std::filesystem::path& out_dir,
                                                   const MapDescription& map,
                                                   const std::vector<TexelGrid>& tiles,
                                                   const std::vector<std::vector<float>>& values,
                                                   const MapOutputOptions& options);

/// Write `mesh` as a binary PLY with one float vertex property per channel of `map`
/// (values vertex-major), atomically.
void write_vertex_map(const std::filesystem::path& ply_path, const TriangleMesh& mesh,
                      const MapDescription& map, const std::vector<float>& values);

/// Add or replace `map`'s entry in `<out_dir>/stack.toml` (created if missing): file name
/// or UDIM pattern, tiles, channels, units, colour space "raw", baker and parameters.
/// Other entries are kept. Written atomically.
void record_in_manifest(const std::filesystem::path& out_dir, const MapDescription& map,
                        const std::vector<std::filesystem::path>& files,
                        const std::vector<TexelGrid>& tiles);

}  // namespace patina::texgen
