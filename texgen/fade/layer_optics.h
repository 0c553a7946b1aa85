// Reflectance and transmittance of a whole (depth-varying) fading layer, for compositing
// it over any substrate: R from the top, T (the same both ways: the two-flux system is
// reciprocal), R from below, folded from the sublayers' Eqs. (22), (23) by the adding
// rules of Kubelka 1948. The reflectance over a substrate rho* is then
//   rho = R_top + T^2 rho* / (1 - R_bottom rho*),
// the top reflectance E^u_0 / E_0 of the two-flux system of §4.1.
#pragma once

#include <span>

namespace patina::texgen::fade {

struct LayerOpticsValue {
    double r_top = 0.0;
    double t = 1.0;
    double r_bottom = 0.0;
};

/// Fold N sublayers (top first) into the layer's R_top, T, R_bottom. Empty: {0, 1, 0}.
LayerOpticsValue fold_sublayers(std::span<const double> rho, std::span<const double> tau);

/// The layer over an opaque substrate of reflectance `substrate`.
inline double reflectance_over(const LayerOpticsValue& layer, double substrate)
{
    const double denom = 1.0 - layer.r_bottom * substrate;
    return layer.r_top + (denom > 0.0 ? layer.t * layer.t * substrate / denom : 0.0);
}

}  // namespace patina::texgen::fade
