// All meshes of a file as one TriangleMesh: the bakers see one surface, whatever the file's
// node graph looks like.
#pragma once

#include "core/mesh.h"

#include <filesystem>
#include <vector>

namespace patina::texgen {

/// Concatenate `meshes` (as load_meshes returns them from `file`) into one mesh, each
/// triangle keeping its source material (triangle_material, materials: names in order of
/// first appearance). A mesh
/// without normals gets area-weighted vertex normals (compute_vertex_normals) when any mesh
/// has normals, so the merged normals stay per vertex; uvs are kept. The result is named
/// after the only mesh, or after the file's stem when there are several. Throws
/// std::runtime_error naming `file` when `meshes` is empty or when some meshes have uvs and
/// others have none (one texel grid cannot hold both).
TriangleMesh merge_meshes(const std::vector<TriangleMesh>& meshes,
                          const std::filesystem::path& file);

/// load_meshes(file, convention) merged by merge_meshes; `applied`, when given, receives the
/// convention used (mesh_convention.h).
TriangleMesh load_merged_mesh(const std::filesystem::path& file,
                              const MeshConventionOptions& convention = {},
                              MeshConvention* applied = nullptr);

}  // namespace patina::texgen
