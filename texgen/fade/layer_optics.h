// Reflectance and transmittance of a whole (depth-varying) fading layer, for compositing
// it over any substrate: R from the top, T (the same both ways: the two-flux system is
// reciprocal), R from below, folded from the sublayers' Eqs. (22), (23) by the adding
// rules of Kubelka 1948. The reflectance over a substrate rho* is then
//   rho = R_top + T^2 rho* / (1 - R_bottom rho*),
// the top reflectance E^u_0 / E_0 of the two-flux system of §4.1.
#pragma once

#include <patina/shading/kubelka_munk.h>

#include <span>

namespace patina::texgen::fade {

struct LayerOpticsValue {
    double r_top = 0.0;
    double t = 1.0;
    double r_bottom = 0.0;
};

/// Fold N sublayers (top first) into the layer's R_top, T, R_bottom. Empty: {0, 1, 0}.
LayerOpticsValue fold_sublayers(std::span<const double> rho, std::span<const double> tau);

#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"  // Vec4 arguments of an inline template

/// Add one sublayer with rho = a / d, tau = t / d (sublayer_terms of two_flux.h) below the
/// stack (r_top, t_stack, r_bottom); T is double or Vec4. Interreflections between the
/// stack's bottom and the sublayer's top sum to 1 / (1 - R_bottom rho) = d / p with
/// p = d - R_bottom a (Kubelka 1948):
///   R_top += T^2 rho d / p = T^2 a / p,   T = T tau d / p = T t / p,
///   R_bottom = rho + tau^2 R_bottom d / p = (a p + t^2 R_bottom) / (d p).
template <class T>
[[gnu::always_inline]] inline void fold_sublayer(T& r_top, T& t_stack, T& r_bottom, T a, T t,
                                                 T d)
{
    const T p = d - r_bottom * a;
    const T inv_dp = 1.0 / (d * p);
    const T t_over_p = t_stack * (d * inv_dp);
    r_top += t_stack * t_over_p * a;
    r_bottom = (a * p + t * t * r_bottom) * inv_dp;
    t_stack = t_over_p * t;
}

#pragma GCC diagnostic pop

/// The layer over an opaque substrate of reflectance `substrate`.
inline double reflectance_over(const LayerOpticsValue& layer, double substrate)
{
    return shading::km_reflectance_over<double>({layer.r_top, layer.r_bottom, layer.t},
                                                substrate);
}

}  // namespace patina::texgen::fade
