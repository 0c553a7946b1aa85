#include "texgen/fade/layer_optics.h"

#include <cassert>

namespace patina::texgen::fade {

LayerOpticsValue fold_sublayers(std::span<const double> rho, std::span<const double> tau)
{
    assert(rho.size() == tau.size());
    // Adding a sublayer (rho, tau) below the stack (Kubelka 1948): interreflections between
    // the stack's bottom and the sublayer's top sum to 1 / (1 - R_bottom rho).
    LayerOpticsValue v;
    for (size_t i = 0; i < rho.size(); ++i) {
        const double inv = 1.0 / (1.0 - v.r_bottom * rho[i]);
        const double t_inv = v.t * inv;
        v.r_top += v.t * t_inv * rho[i];
        v.r_bottom = rho[i] + tau[i] * tau[i] * v.r_bottom * inv;
        v.t = t_inv * tau[i];
    }
    return v;
}

}  // namespace patina::texgen::fade
