// A uv layout for weathering, made by a real, maintained unwrapper: Blender's Smart UV Project
// or Lightmap Pack, run headless (data/blender/unwrap.py). The mesh is read as Patina reads it
// (axes, unit), handed to Blender as glTF, and comes back as a .glb with a new uv set,
// "patina", after the artist's own: every surface point its own texels, all meshes packed
// into tile 1001. The bakers bake into it with --uv-set; export keeps the artist's set as
// TEXCOORD_0 and puts the weathering maps on the new one (texCoord 1).
#pragma once

#include "core/mesh_convention.h"

#include <filesystem>
#include <string>

namespace patina::texgen {

struct UnwrapOptions {
    std::string method = "smart"; ///< "smart" (Smart UV Project) or "lightmap" (Lightmap Pack)
    /// smart: faces meeting at more than this start new islands. Blender's default, 66, leaves
    /// islands that fold over themselves on fluted shapes (0.19 % of the project's statue
    /// overlaps); 45 leaves none there.
    double angle_limit_deg = 45.0;
    double margin = 0.005;           ///< space between islands, a fraction of the tile
    int resolution = 1024;           ///< texels per side the report's utilisation is for
    std::string blender = "blender"; ///< the Blender to run
};

/// How good the new layout is, measured by Patina on the file Blender wrote.
struct UnwrapReport {
    int uv_set = 0; ///< the new set's index (the bakers' --uv-set)
    size_t triangles = 0;
    size_t islands = 0;
    /// Covered texels' share of the tile at `resolution` (sub-sample centres inside a triangle).
    double utilisation = 0.0;
    double overlap_fraction = 0.0; ///< of the covered area: 0 for a unique layout
    /// Texel density (texels per m^2) of the least and most dense triangles over the mean,
    /// and the area-weighted RMS of log2(density / mean): 0 when every triangle gets the same
    /// texels per square metre, 1 when they typically differ by a factor of 2.
    double density_min_over_mean = 0.0, density_max_over_mean = 0.0;
    double stretch_rms_log2 = 0.0;
    double blender_seconds = 0.0;
};

/// Write `output` (.glb): `input`'s meshes in Patina's world (+Y up, metres, read with
/// `convention`), their uvs, normals and material names, plus the new uv set. Throws
/// std::runtime_error naming what to install when Blender is missing, with Blender's last
/// lines when it fails, and naming the file for a mesh Patina cannot read. The output is
/// staged in the current output transaction (nothing half-written is left).
UnwrapReport unwrap_mesh(const std::filesystem::path& input,
                         const MeshConventionOptions& convention,
                         const std::filesystem::path& output, const UnwrapOptions& options);

/// The report as uv-check prints its lines.
std::string format_unwrap_report(const UnwrapReport& report);

} // namespace patina::texgen
