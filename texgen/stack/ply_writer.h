// Binary PLY output of a triangle mesh with extra float properties per vertex: the file of
// the per-vertex mode ("triangulations as texture maps", Dorsey & Hanrahan 1996 §3.3).
// Hand-written because Assimp's exporters cannot write custom vertex properties; PLY
// readers (Assimp, MeshLab, Blender, trimesh) skip properties they do not know.
#pragma once

#include "core/mesh.h"

#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace patina::texgen {

/// A PLY property name made of [A-Za-z0-9_] only: every other character becomes '_'
/// ("albedo.r" -> "albedo_r"); an empty name becomes "_".
std::string sanitize_ply_name(std::string_view name);

/// Write `mesh` to `path` as `format binary_little_endian 1.0`: vertex x y z, nx ny nz (if
/// the mesh has normals), u v (if it has uvs), then one `property float <name>` per entry of
/// `property_names` with `values` vertex-major (property_names.size() per vertex); faces as
/// `property list uchar int vertex_indices`. Each entry of `comments` becomes one
/// `comment` line (line breaks replaced by spaces). Names must be valid (see
/// sanitize_ply_name) and distinct from each other and from x y z nx ny nz u v; throws
/// std::runtime_error naming the file otherwise. Written under a temporary name and renamed.
void write_ply_with_vertex_values(const std::filesystem::path& path, const TriangleMesh& mesh,
                                  const std::vector<std::string>& property_names,
                                  const std::vector<float>& values,
                                  const std::vector<std::string>& comments);

}  // namespace patina::texgen
