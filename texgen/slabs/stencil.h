// The 13-point least-squares Laplacian of Dorsey et al. 1999 §4.3.5 on a distorted lattice.
//
// At a lattice point the three lattice vectors u, v, w (world offsets to the next voxel along
// each index axis) define the stencil 0, ±u, ±v, ±w and the six diagonals ±(u + s_uv v),
// ±(v + s_vw w), ±(u + s_uw w). The paper's text lists "eight points consisting of sums of
// any two of ±u, ±v, ±w" but counts thirteen points in all; 1 + 6 + 6 = 13 is the only count
// that adds up, so we take one diagonal pair per plane, the shorter one (s = -sign(a.b)).
//
// The paper imposes fourteen conditions in a least-squares manner: L x² = L y² = L z² = 2
// and L f = 0 for 1, x, y, z, xy, xz, yz, x³, x²y, xy², z³. A stencil whose weights are
// equal on ±d satisfies the odd conditions identically, and for the even ones
//   sum_d c_d (f(p + d) + f(p - d) - 2 f(p)) = sum_d c_d d^T A d = trace(A)
// (A the Hessian of a quadratic f) holds exactly when sum_d c_d d d^T = I. Written in the
// lattice basis M = [u v w] this is sum_d c_d e_d e_d^T = (M^T M)^-1 = H, six equations for
// six unknown weights with the closed-form solution below: the least-squares problem has a
// zero residual, so the stencil is exact for every quadratic on any non-degenerate lattice.
#pragma once

#include <Imath/ImathVec.h>

#include <array>

namespace patina::texgen::stone {

/// The index offsets of the six stencil directions: axes 0, 1, 2 are e_u, e_v, e_w;
/// diagonals 3, 4, 5 are e_u + s[0] e_v, e_v + s[1] e_w, e_u + s[2] e_w.
struct StencilSigns {
    std::array<int, 3> s{1, 1, 1};
};

/// Weights of the six directions (each applied to f(p + d) + f(p - d) - 2 f(p)).
struct StencilWeights {
    std::array<double, 6> c{};
    /// Weight of the centre point: -2 sum c.
    double centre() const { return -2.0 * (c[0] + c[1] + c[2] + c[3] + c[4] + c[5]); }
};

/// The inverse metric H = (M^T M)^-1 of the lattice vectors, M = [u v w] (columns).
/// Also what turns index-space differences into world gradients' dot products:
/// grad f . grad g = (Df)^T H (Dg) with Df the central differences along the index axes.
struct InverseMetric {
    double h00 = 0, h11 = 0, h22 = 0, h01 = 0, h12 = 0, h02 = 0;
};

InverseMetric inverse_metric(const Imath::V3d& u, const Imath::V3d& v, const Imath::V3d& w);

/// Shorter diagonal per plane: s = -1 where the two lattice vectors make an acute angle.
StencilSigns shorter_diagonals(const Imath::V3d& u, const Imath::V3d& v, const Imath::V3d& w);

/// The §4.3.5 weights for the lattice (u, v, w) with diagonal signs `signs`.
StencilWeights thirteen_point_weights(const InverseMetric& h, const StencilSigns& signs);
StencilWeights thirteen_point_weights(const Imath::V3d& u, const Imath::V3d& v,
                                      const Imath::V3d& w, const StencilSigns& signs);

/// The world offset of direction d (0..5) of the stencil.
Imath::V3d stencil_offset(int d, const Imath::V3d& u, const Imath::V3d& v, const Imath::V3d& w,
                          const StencilSigns& signs);

/// H recovered from the weights (what the simulation stores per voxel instead of H).
InverseMetric metric_from_weights(const StencilWeights& weights, const StencilSigns& signs);

} // namespace patina::texgen::stone
