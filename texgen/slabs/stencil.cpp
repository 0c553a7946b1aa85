#include "texgen/slabs/stencil.h"

#include <Imath/ImathMatrix.h>

#include <cmath>
#include <stdexcept>

namespace patina::texgen::stone {

InverseMetric inverse_metric(const Imath::V3d& u, const Imath::V3d& v, const Imath::V3d& w)
{
    // G = M^T M (the metric tensor of the lattice), inverted by cofactors.
    const double g00 = u.dot(u), g11 = v.dot(v), g22 = w.dot(w);
    const double g01 = u.dot(v), g12 = v.dot(w), g02 = u.dot(w);
    const double a00 = g11 * g22 - g12 * g12, a11 = g00 * g22 - g02 * g02,
                 a22 = g00 * g11 - g01 * g01;
    const double a01 = g02 * g12 - g01 * g22, a12 = g01 * g02 - g00 * g12,
                 a02 = g01 * g12 - g02 * g11;
    const double det = g00 * a00 + g01 * a01 + g02 * a02;
    if (!(std::abs(det) > 1e-300))
        throw std::runtime_error("13-point stencil: degenerate lattice (lattice vectors are "
                                 "coplanar)");
    InverseMetric h;
    h.h00 = a00 / det;
    h.h11 = a11 / det;
    h.h22 = a22 / det;
    h.h01 = a01 / det;
    h.h12 = a12 / det;
    h.h02 = a02 / det;
    return h;
}

StencilSigns shorter_diagonals(const Imath::V3d& u, const Imath::V3d& v, const Imath::V3d& w)
{
    StencilSigns s;
    s.s[0] = u.dot(v) > 0.0 ? -1 : 1;
    s.s[1] = v.dot(w) > 0.0 ? -1 : 1;
    s.s[2] = u.dot(w) > 0.0 ? -1 : 1;
    return s;
}

StencilWeights thirteen_point_weights(const InverseMetric& h, const StencilSigns& signs)
{
    // sum_d c_d e_d e_d^T = H: a diagonal e_a + s e_b contributes s c to H_ab and c to H_aa
    // and H_bb; an axis e_a contributes c to H_aa only.
    StencilWeights w;
    w.c[3] = signs.s[0] * h.h01;
    w.c[4] = signs.s[1] * h.h12;
    w.c[5] = signs.s[2] * h.h02;
    w.c[0] = h.h00 - w.c[3] - w.c[5];
    w.c[1] = h.h11 - w.c[3] - w.c[4];
    w.c[2] = h.h22 - w.c[4] - w.c[5];
    return w;
}

StencilWeights thirteen_point_weights(const Imath::V3d& u, const Imath::V3d& v,
                                      const Imath::V3d& w, const StencilSigns& signs)
{
    return thirteen_point_weights(inverse_metric(u, v, w), signs);
}

Imath::V3d stencil_offset(int d, const Imath::V3d& u, const Imath::V3d& v, const Imath::V3d& w,
                          const StencilSigns& signs)
{
    switch (d) {
    case 0: return u;
    case 1: return v;
    case 2: return w;
    case 3: return u + double(signs.s[0]) * v;
    case 4: return v + double(signs.s[1]) * w;
    default: return u + double(signs.s[2]) * w;
    }
}

InverseMetric metric_from_weights(const StencilWeights& weights, const StencilSigns& signs)
{
    const auto& c = weights.c;
    InverseMetric h;
    h.h01 = signs.s[0] * c[3];
    h.h12 = signs.s[1] * c[4];
    h.h02 = signs.s[2] * c[5];
    h.h00 = c[0] + c[3] + c[5];
    h.h11 = c[1] + c[3] + c[4];
    h.h22 = c[2] + c[4] + c[5];
    return h;
}

} // namespace patina::texgen::stone
