// Kubelka-Munk absorption and scattering coefficients from reflectance measurements
// (Kimmel et al. 2013, Appendix A, after Johnston-Feller 2001), and the patina paper's
// route (Dorsey & Hanrahan 1996 §4.1): K/S from the reflectance of an optically thick
// layer R_inf, with an assumed S.
#pragma once

#include <patina/shading/kubelka_munk.h>

namespace patina::texgen::fade {

struct KmCoefficients {
    double absorption_per_m = 0.0;  ///< mu_a (KM K), 1/m
    double scattering_per_m = 0.0;  ///< mu_s (KM S), 1/m
};

/// Eq. (37): reflectance of a layer of thickness Z (m) over a substrate rho_g. Exact limits
/// for mu_a = 0 and mu_s = 0 (rho = rho_g exp(-2 mu_a Z)).
double km_layer_reflectance(double mu_a, double mu_s, double thickness_m, double rho_g);

/// Appendix A, Eqs. (38)-(48): mu_a and mu_s of a layer of thickness Z from its
/// reflectance rho_0 over a black substrate of reflectance rho_b and rho_1 over a white
/// standard of reflectance rho_w (the paper assumes 1). Throws std::runtime_error naming the
/// values when they admit no solution (e.g. rho_0 not between rho_b's and rho_1's effect,
/// reflectances outside [0, 1), or a non-scattering layer: rho_0 = 0 over a black ground).
KmCoefficients invert_black_white(double rho_0, double rho_b, double rho_1, double thickness_m,
                                  double rho_w = 1.0);

/// R_inf = 1 + K/S - sqrt((K/S)^2 + 2 K/S) and its inverse K/S = (1 - R_inf)^2 / (2 R_inf)
/// (patina/shading/kubelka_munk.h).
using shading::km_k_over_s;
using shading::km_r_infinity;

/// K from R_inf with an assumed S (the patina paper's route; §5.3's route for cork, whose
/// thick sample gives only K/S). Throws for R_inf outside (0, 1] or S < 0.
KmCoefficients from_r_infinity(double r_infinity, double assumed_scattering_per_m);

}  // namespace patina::texgen::fade
