// The lattice of a mesh's surface (Dorsey & Hanrahan 1996 §3.3 "triangulations as texture
// maps", and §1: patterns must not stop at the cuts of a texture): the covered texels of
// its uv layout as nodes, joined to their left / right / up / down texels inside a uv island
// and, at an island's border, to the texel the same step lands on across the seam, found by
// walking over the mesh's 3D edge adjacency. A growth model run on it crosses seams as if
// the surface had none.
#pragma once

#include "core/mesh.h"
#include "texgen/growth/lattice.h"
#include "texgen/texels/texel_grid.h"

#include <span>
#include <vector>

namespace patina::texgen {

struct SurfaceLatticeOptions {
    int width = 1024;
    int height = 1024;
    int supersampling = 2;
};

/// rasterize_uv(mesh, {width, height, supersampling}) followed by the grids overload below.
/// Throws std::runtime_error naming the mesh when it has no uvs (and whatever rasterize_uv
/// throws for a bad layout).
Lattice build_surface_lattice(const TriangleMesh& mesh, const SurfaceLatticeOptions& options);

/// The surface lattice of `mesh` on tiles it was rasterised to (rasterize_uv(mesh, ...)).
///
/// Nodes and groups: node numbers run over the grids in order and, inside a grid, over its
/// texel groups in order (rasterize_uv numbers groups in texel scan order): node
/// base(g) + i is group i of grids[g], with base(g) the covered texels of the grids before
/// it. tiles[g].node_of_texel[texel] == base(g) + grids[g].group_of_texel[texel] (or -1).
/// Neighbour slots as in make_grid_lattice: +x, -x, +y, -y in the node's own image (+y is
/// down the image, -v).
///
/// Per node: its home triangle is the triangle of its sample nearest the texel centre (in
/// uv) and its island the uv island of that triangle (islands: triangles joined by 3D
/// edges whose two ends have the same uv on both sides). position = mean P of its samples
/// on that island; cell_size = mean 3D length of its links, or, for a node without links,
/// the mean 3D length of one texel step in its home triangle.
///
/// Links. A step inside an island is the texel next to it when that texel's home island is
/// the same and it lies within 3 expected steps in 3D. Otherwise (island border, uv tile
/// edge, or two islands packed into adjacent texels) the step is walked on the surface:
/// from the home sample along the step direction, across triangle edges found by welding
/// vertices by position (uv seams split vertices); across an edge whose uvs differ on the
/// two sides (a seam) the neighbouring triangle is unfolded about the edge into the plane of
/// the current one (keeping 3D lengths and angles) and the walk continues in its uv chart.
/// The link goes to the first texel other than the node's own, within 2 texel steps, whose
/// home island is the island being walked on; the far node's slot for it is the cardinal
/// direction pointing back along the walk. A walk that leaves an open boundary links nothing.
/// At a non-manifold edge the walk takes the lowest-numbered other triangle.
///
/// Symmetry: every proposed link (a, slot) <-> (b, slot') is a candidate, and candidates are
/// accepted nearest first in 3D (ties by node and slot numbers) while both slots are free and
/// the two nodes are not already linked; so links are symmetric, a slot claimed twice keeps
/// the nearer node, and the result is the same for any thread count.
///
/// Throws std::runtime_error naming the mesh when it has no uvs, and when `grids` do not
/// belong to it (sizes, triangle indices).
Lattice build_surface_lattice(const TriangleMesh& mesh, const std::vector<TexelGrid>& grids);

/// Per-node values -> per-group values of `grids` (one vector per grid, group-major, one
/// channel): the layout write_texel_map takes. Each covered texel takes the value of the
/// lattice node at that texel of the lattice's tile with the same UDIM; when the lattice was
/// built from these grids this is a plain copy through node_of_texel (value[g][i] =
/// node_values[base(g) + i]). For a lattice of another resolution the texel is scaled to the
/// nearest texel of the lattice's tile, and when that one is uncovered, the nearest covered
/// texel within a few texels is used. Throws std::runtime_error when node_values has the
/// wrong size, a UDIM is missing from the lattice or a texel has no node near it.
std::vector<std::vector<float>> lattice_to_groups(const Lattice& lattice,
                                                  std::span<const float> node_values,
                                                  const std::vector<TexelGrid>& grids);

} // namespace patina::texgen
