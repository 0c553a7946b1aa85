#include "texgen/fade/layer_optics.h"

#include <cassert>

namespace patina::texgen::fade {

LayerOpticsValue fold_sublayers(std::span<const double> rho, std::span<const double> tau)
{
    assert(rho.size() == tau.size());
    // The same formulas as the simulation's vector fold (a = rho, t = tau, d = 1).
    LayerOpticsValue v;
    for (size_t i = 0; i < rho.size(); ++i)
        fold_sublayer(v.r_top, v.t, v.r_bottom, rho[i], tau[i], 1.0);
    return v;
}

}  // namespace patina::texgen::fade
