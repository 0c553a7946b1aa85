// Writing triangle meshes through Assimp's exporters (OBJ, PLY, glTF, ...), atomically.
#pragma once

#include "core/mesh.h"

#include <filesystem>

namespace patina {

/// Write `mesh` (positions, normals and uvs when present) to `path`; the format follows the
/// extension (.obj without a material file, .ply, .glb, .gltf, .stl). Written under a
/// temporary name and renamed when complete; throws std::runtime_error naming the file
/// with Assimp's error text.
void save_mesh(const std::filesystem::path& path, const TriangleMesh& mesh);

}  // namespace patina
