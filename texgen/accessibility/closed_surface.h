// Miller's offset-surface accessibility (Miller 1994; Dorsey & Hanrahan 1996 §3.2, "offset
// radius": "forms a positive and then a negative offset surface and compares that to the
// height of the original surface"). Offsetting the free space's boundary out by r and back
// in by r is a morphological closing: the closed surface is the boundary of U, the union of
// every ball of radius r that meets no geometry. It lies on the surface where an r-ball
// can touch it and bridges crevices narrower than the ball; its height above a point along
// the normal is the crevice depth the ball cannot reach.
//
// Computed on a voxel grid over the scene bounds (padded by r and two voxels):
//  1. D(v), the exact distance from each voxel centre v to the triangles, by bounded
//     closest-point queries (capped at rho_max = r + 2 sqrt(3) voxels).
//  2. U is also the union of the balls B(c, D(c)) over all c with D(c) >= r (each is a
//     union of r-balls with centres in the free set, by the 1-Lipschitz D). Sampled at the
//     voxel centres, U_h = union of B(v, min(D(v), rho_max)) over those v is an inner
//     approximation of U whose boundary is within a voxel of U's.
//  3. x lies in U_h iff min_v |x - v|^2 - rho_v^2 <= 0: a squared distance transform of the
//     sampled function f(v) = -rho_v^2 (the lower envelope of parabolas works for any f),
//     computed exactly on the grid with Felzenszwalb & Huttenlocher 2012, "Distance
//     Transforms of Sampled Functions", Theory of Computing 8, Alg. 1, one axis at a time,
//     keeping each voxel's minimising centre.
//  4. height(P, n): march along P + t n, testing x against the minimising centres of the 8
//     voxels around it, and bisect the first crossing into U_h.
#pragma once

#include "texgen/accessibility/closest_point.h"

#include <Imath/ImathBox.h>
#include <Imath/ImathVec.h>

#include <cstdint>
#include <vector>

namespace patina::texgen {

class ClosedSurface {
public:
    /// Voxelise `bounds` (the scene's) with `voxels` cells along its longest side (8 to
    /// 2048) for a ball of radius `radius` (m, > 0). Parallel (TBB), deterministic.
    /// Throws std::runtime_error naming --radius / --voxels on bad values, or when the grid
    /// would exceed 2^31 voxels.
    ClosedSurface(const ClosestPointScene& scene, const Imath::Box3f& bounds, float radius,
                  int voxels);

    /// Height of the closed surface above P along the unit normal n: the smallest t >= 0
    /// with P + t n inside U_h (0 where an r-ball touches P). Accurate to about a voxel.
    /// Returns max_height() when the ray never enters U_h within the grid.
    float height(const Imath::V3f& P, const Imath::V3f& n) const;

    /// True if the world point x lies inside U (the union of free r-balls); points outside
    /// the grid are farther than r from all geometry, so they are inside.
    bool inside(const Imath::V3f& x) const;

    float radius() const { return radius_; }
    float voxel_size() const { return h_; }
    Imath::V3i dimensions() const { return {nx_, ny_, nz_}; }
    float max_height() const { return max_height_; }

private:
    size_t index(int x, int y, int z) const
    {
        return (static_cast<size_t>(z) * ny_ + y) * nx_ + x;
    }

    float radius_;
    float h_;             // voxel edge (m)
    Imath::V3f origin_;   // world position of voxel (0, 0, 0)'s lower corner
    int nx_, ny_, nz_;
    float max_height_;
    std::vector<float> rho2_;    // per voxel: (ball radius / h)^2, or -1 when D < r
    std::vector<int32_t> site_;  // per voxel: the ball centre minimising the power distance
};

}  // namespace patina::texgen
