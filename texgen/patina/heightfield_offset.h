// The `offset radius` operator on a flat strip (Dorsey & Hanrahan 1996 §3.2: "applies a
// material to a surface by first applying a thick coat and then removing the part accessible
// to a sphere of a given radius ... We have implemented both versions of [Miller's]
// operator: one computes the largest tangent sphere, the other forms a positive and then a
// negative offset surface and compares that to the height of the original surface").
//
// The surface is a height field: heights[y * width + x] (µm, row 0 first, the Lattice tile
// convention) sampled at the centres of square cells `cell_size_um` wide. Both variants see
// the surface as its samples (a ball touches the surface at cell centres) and continue the
// field beyond its border by its edge values (a strip is a piece of a larger sheet; a groove
// that meets the border runs on). The result is the thickness of material the ball cannot
// reach, per cell (µm, >= 0), to pass to offset() (operators.h) as a layer.
//
// On a mesh the same quantities come from the accessibility bakers (texgen/accessibility):
// OffsetSurfaceBaker's "offset_height" is the closing depth of variant 2, and
// TangentSphereBaker's "accessibility_radius" goes through fill_from_tangent_radius below.
#pragma once

#include "texgen/growth/lattice.h"

#include <span>
#include <vector>

namespace patina::texgen {

/// Miller's second variant ("a positive and then a negative offset surface ... compared to
/// the height of the original surface"): the morphological closing of the height field by a
/// ball of radius `radius_um`, less the height. Dilating by the ball (the positive offset)
/// gives D(p) = max_q h(q) + c(p - q), eroding that by the ball (the negative offset) gives
/// C(p) = min_q D(q) - c(p - q), with c(d) = sqrt(r^2 - |d|^2) the ball's cap over the cells
/// within r; C is the lower envelope of the balls resting on the surface, and C - h >= 0 is
/// the depth of the crevices the ball cannot enter: 0 on flat and convex ground and where
/// the ball touches a concave wall (curvature radius >= r), > 0 in crevices narrower than
/// the ball. Exact on the grid (the ball's true cap at every cell offset, no separable
/// approximation); O(cells * (r / cell)^2), parallel over rows, deterministic.
/// Throws std::invalid_argument ("offset: ...") for sizes that do not match, a cell size or
/// radius that is not positive and finite, or a radius over 128 cells (too slow: coarsen
/// the grid).
/// With `boundary` periodic the field continues beyond each edge from the opposite one (a
/// periodic strip, lattice.h) instead of by its edge values.
std::vector<float> closing_fill(std::span<const float> heights_um, int width, int height,
                                float cell_size_um, float radius_um,
                                GridBoundary boundary = GridBoundary::open);

/// The radius (µm) of the largest sphere tangent to the height field at each cell (centre
/// on the cell's upward unit normal, from central differences) that holds no sample of the
/// surface strictly inside, capped at `max_radius_um`. A sample q excludes exactly the
/// spheres larger than |q - p|^2 / (2 n.(q - p)) (those whose centre p + rho n comes within
/// rho of q), so the radius is the minimum of that over the samples within 2 max_radius:
/// no bisection is needed on a sampled surface. Flat and convex ground reach the cap; a
/// concave cylinder of radius R gives about R; a sharp crease gives about a cell (the
/// sampled surface's resolution). At most O(cells * (max_radius / cell)^2), far less where the scan
/// can stop early (flat ground with nothing higher near costs O(1)); parallel over rows.
std::vector<float> tangent_sphere_radius(std::span<const float> heights_um, int width, int height,
                                         float cell_size_um, float max_radius_um,
                                         GridBoundary boundary = GridBoundary::open);

/// Miller's first variant as a fill thickness: where the largest tangent sphere at a point
/// has radius rho < r, the point lies in a crevice a ball of radius r cannot touch, and it
/// receives the thickness (along its normal) of the fillet such a ball leaves in a
/// right-angled crease at the point whose tangent sphere is rho: in a 90-degree crease the
/// largest tangent sphere at distance s from the edge has rho = s, and the r-ball touching
/// both faces stands r - sqrt(r^2 - (r - s)^2) above the face there, so
///     fill = r - sqrt(rho (2 r - rho))   for rho < r,   0 for rho >= r.
/// It falls from r at a sharp crease (rho = 0) to 0 where the r-ball touches (rho = r), and
/// depends only on rho, so a mesh (TangentSphereBaker's radius) and a height field
/// (tangent_sphere_radius) map the same way. Any length unit, the same for both arguments
/// and the result (the mesh baker's metres: multiply the result by 1e6 for µm).
float fill_from_tangent_radius(float tangent_radius, float radius);

/// fill_from_tangent_radius of tangent_sphere_radius(heights, ..., radius_um) at every cell:
/// 0 on flat and convex ground and where an r-ball touches, > 0 only in crevices narrower
/// than r. Same errors as closing_fill.
std::vector<float> tangent_sphere_fill(std::span<const float> heights_um, int width, int height,
                                       float cell_size_um, float radius_um,
                                       GridBoundary boundary = GridBoundary::open);

}  // namespace patina::texgen
