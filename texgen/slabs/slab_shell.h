// Slabs (Dorsey et al. 1999 §4.1): a surface-aligned shell of trilinear volumes around a
// closed triangle mesh, built automatically.
//
// The paper fits slabs to a quadrilateral mesh covering a simplified object, extrudes each
// face along the averaged surface normals and fixes self-intersections by hand. Here the
// quadrilaterals come from splitting every triangle of the base mesh into three (vertex, edge
// midpoints, centroid: the topological step of Catmull-Clark, positions kept on the
// triangles), so any closed triangle mesh works and adjacent slabs share four corners and a
// bilinear face. Each point is extruded inwards along its angle-weighted normal by a depth
// limited so that the shell cannot fold or overlap itself:
//   - at most `clearance` (0.45) of the distance an inward ray travels to the opposite wall,
//   - at most the local radius of curvature estimated on every quad edge
//     (d <= 0.7 |e|^2 / (e . (n_b - n_a)) where the normals converge inwards),
//   - Lipschitz-smoothed (|d_a - d_b| <= 0.5 |e|) so the inner surface stays smooth,
//   - then every slab's Jacobian is checked at 27 points; a slab that folds has its inner
//     corners pulled towards the surface until none does.
// The same limits apply to a small outward margin (so the surface lies inside the shell and
// its voxels get fractional density). Slab coordinates: u, v along the base quad, w from the
// outer face (w = 0, outside the surface by the margin) to the inner face (w = 1).
#pragma once

#include "core/mesh.h"

#include <Imath/ImathVec.h>

#include <array>
#include <vector>

namespace patina::texgen::stone {

/// The eight corners of a slab; corner index iu + 2 iv + 4 iw (iw = 0 outer face).
using SlabCorners = std::array<Imath::V3d, 8>;

struct ShellOptions {
    double depth = 0.1;         ///< nominal extrusion depth inwards (m)
    double outer_margin = 0.0;  ///< extrusion outwards beyond the surface (m)
    double clearance = 0.45;    ///< fraction of the inward ray distance a depth may use
};

struct SlabShell {
    std::vector<SlabCorners> slabs;
    /// The base quads' points (welded vertices, edge midpoints, centroids) and, per slab,
    /// its four points (u,v) = (0,0), (1,0), (1,1), (0,1).
    std::vector<Imath::V3d> points;
    std::vector<Imath::V3d> normals;       ///< unit extrusion direction (outward) per point
    std::vector<double> depths;            ///< inward extrusion per point after the limits
    std::vector<double> margins;           ///< outward extrusion per point
    std::vector<std::array<int, 4>> quads;
    /// Per slab and edge (0: v = 0, 1: u = 1, 2: v = 1, 3: u = 0), the slab across it or -1.
    std::vector<std::array<int, 4>> neighbours;
    int folded_fixes = 0;                  ///< slabs whose inner corners had to be pulled in
};

/// Build the shell of `base` (closed, outward-wound triangles; duplicated vertices such as
/// uv seams are welded). Throws std::runtime_error when the mesh has no usable triangle or
/// a bad option.
SlabShell build_slab_shell(const TriangleMesh& base, const ShellOptions& options);

/// Determinant of the slab's Jacobian at (u, v, w); negative inside a valid slab (u x v
/// points outwards, w inwards).
double slab_jacobian_determinant(const SlabCorners& c, const Imath::V3d& uvw);

} // namespace patina::texgen::stone
