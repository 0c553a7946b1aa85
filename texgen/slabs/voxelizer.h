// The voxeliser (Dorsey et al. 1999 §4.2): stone density in every slab voxel from the signed
// distance to the input mesh, 1 inside, 0 outside, fractional where the surface passes
// through the voxel: density = clamp(1/2 + signed distance / h, 0, 1), h the voxel's depth
// step. The sign comes from the crossings of the mesh along the voxel's column (a column is
// a straight segment: at fixed (u, v) the trilinear map is linear in w; its outer end lies
// outside the stone), the distance from a closest-point query. Each column also records where
// it meets the surface (position, normal, uv): the point whose wetness and deposit maps drive
// the column's boundary conditions.
#pragma once

#include "core/mesh.h"
#include "texgen/slabs/slab_lattice.h"

#include <Imath/ImathVec.h>

#include <vector>

namespace patina::texgen::stone {

/// Where a slab column (slab s, voxel column (i, j)) meets the stone surface.
struct ColumnSurface {
    Imath::V3f P{0.0f};
    Imath::V3f N{0.0f, 1.0f, 0.0f};  ///< unit outward normal
    Imath::V2f uv{0.0f};
    bool hit = false;                ///< false: the column misses the surface (P, N of the slab)
};

/// Column index of (s, i, j): (s * n_t + j) * n_t + i.
inline size_t column_index(const SlabGrid& g, int s, int i, int j)
{
    return (size_t(s) * g.n_t + size_t(j)) * g.n_t + size_t(i);
}

/// Density per cell (halo left 0) and the surface point of every column of `lattice` for
/// the closed mesh `mesh` (world space).
void voxelize(const SlabLattice& lattice, const TriangleMesh& mesh, std::vector<float>& density,
              std::vector<ColumnSurface>& columns);

} // namespace patina::texgen::stone
