// The surface's own topology, as uv-check reports it: open and non-manifold edges, and faces
// wound against their neighbours (a flipped face bakes its inside: the rays of AO and
// exposure leave from the wrong side).
#pragma once

#include "core/mesh.h"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace patina::texgen {

struct MeshTopology {
    /// Edges (between vertices welded by equal position) that one triangle uses: the border
    /// of an open surface.
    size_t boundary_edges = 0;
    /// Edges that three or more triangles share.
    size_t non_manifold_edges = 0;
    /// Triangles wound against the majority of the connected piece they belong to (pieces
    /// joined through edges that exactly two triangles share); 0 for a consistently wound
    /// mesh.
    size_t flipped_faces = 0;
    /// Connected pieces (through any shared edge).
    size_t pieces = 0;
};

/// Per vertex, the lowest index of a vertex at exactly the same position: the surface's own
/// vertices, whatever seams of uvs or normals split them in the file.
std::vector<uint32_t> welded_vertices(const TriangleMesh& mesh);

/// The topology of `mesh`, its vertices welded by exact position (loaders split vertices
/// at uv seams and hard edges; that is no border of the surface).
MeshTopology mesh_topology(const TriangleMesh& mesh);

} // namespace patina::texgen
