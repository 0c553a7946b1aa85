// The patina stack a `patina-texgen patina` run wrote (stack_writer.h): its stack.toml
// `[patina]` table (base material, layers bottom to top with their thickness maps) and the
// files of those maps, per UDIM tile, as `[maps.<name>]` lists them.
#pragma once

#include "formats/texture_stack/texture_stack.h"

#include "core/mesh_convention.h"

#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace patina::texgen {

/// One layer of a stack on disk: its material's name, its thickness map's files (one per
/// tile, in PatinaStackFiles::udims order) and the channel holding its thickness (the
/// layer's `channel`, "thickness" when it has none).
struct StackLayerFiles {
    std::string material;
    std::string map;
    std::vector<std::filesystem::path> files;
    std::string channel = "thickness";  ///< the layer's `channel` by name (the map's first by default)
};

struct PatinaStackFiles {
    std::filesystem::path manifest;   ///< the stack.toml read
    std::string base;                 ///< the base material's name
    double time_years = 0.0;
    std::vector<StackLayerFiles> layers;  ///< bottom to top
    std::vector<int> udims;               ///< the tiles, e.g. {1001}
    int width = 0, height = 0;            ///< texels per tile (the maps' `resolution`)
    /// Side of a flat strip in metres (the maps' parameter strip_size_m); 0 for a mesh.
    double strip_size_m = 0.0;
    /// The mesh the stack was grown on (the maps' parameter `mesh`, resolved against the
    /// manifest's folder), or empty: a strip, or a stack written before the path was kept.
    std::filesystem::path mesh;
    /// The up axis and unit the mesh was read with (the maps' `mesh_up`,
    /// `mesh_metres_per_unit`); empty for a strip or a stack that does not record them.
    MeshConventionOptions mesh_convention;
    /// Whether its uvs outside the UDIM tiles were folded into tile 1001 (the maps'
    /// `uv_wrap`; texels/uv_wrap.h).
    bool uv_wrap = false;
    /// The source materials nothing grew on (the maps' `keep_off`, patina --keep-off).
    std::vector<std::string> keep_off;
    /// The maps' parameter `domain`: "strip", or the file name of the mesh.
    std::string domain;
    /// The optics the stack records for its base and layers ([patina.materials]).
    std::map<std::string, formats::MaterialOptics> materials;
};

/// Read the stack at `stack` (a folder holding stack.toml, or the stack.toml itself) with
/// the one stack reader, formats::read_texture_stack (its errors name file, line and key),
/// and check the total thickness map too: listed, its files there, on the layers' tiles.
PatinaStackFiles read_patina_stack(const std::filesystem::path& stack);

}  // namespace patina::texgen
