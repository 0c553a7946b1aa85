#include "texgen/fade/km_inversion.h"

#include "texgen/fade/layer_optics.h"
#include "texgen/fade/two_flux.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace patina::texgen::fade {

double km_layer_reflectance(double mu_a, double mu_s, double thickness_m, double rho_g)
{
    // Eq. (37) is the layer's own R, T (Eqs. 22, 23 for the whole layer) composited over
    // the ground; evaluated that way it has no 0/0 at mu_a = 0 or mu_s = 0.
    const SublayerOptics o = sublayer_optics(mu_a, mu_s, thickness_m);
    return reflectance_over({o.rho, o.tau, o.rho}, rho_g);
}

KmCoefficients invert_black_white(double rho_0, double rho_b, double rho_1, double thickness_m,
                                  double rho_w)
{
    auto fail = [&](const char* why) {
        throw std::runtime_error(fmt::format(
            "KM inversion (Appendix A): {} (rho_0 = {}, rho_b = {}, rho_1 = {}, rho_w = {}, "
            "Z = {} m)",
            why, rho_0, rho_b, rho_1, rho_w, thickness_m));
    };
    if (!(thickness_m > 0.0))
        fail("the thickness must be > 0");
    if (!(rho_0 >= 0.0 && rho_0 < 1.0 && rho_1 > 0.0 && rho_1 < 1.0 && rho_b >= 0.0 &&
          rho_w > rho_b && rho_w <= 1.0))
        fail("reflectances must lie in [0, 1) with the white ground brighter than the black");
    // Eq. (46), with a white ground of reflectance rho_w (the paper: 1):
    //   [rho_b rho_0; rho_w rho_1] (x1, x2) = (1 + rho_0 rho_b, 1 + rho_1 rho_w).
    const double det = rho_b * rho_1 - rho_0 * rho_w;
    if (std::abs(det) < 1e-300)
        fail("singular system (the layer hides nothing and reflects as over either ground?)");
    const double y0 = 1.0 + rho_0 * rho_b;
    const double y1 = 1.0 + rho_1 * rho_w;
    const double x1 = (y0 * rho_1 - rho_0 * y1) / det;
    const double x2 = (rho_b * y1 - rho_w * y0) / det;
    // Eq. (42), (39).
    const double a = 0.5 * (x1 + x2);
    if (!(a >= 1.0 - 1e-12))
        fail("no solution: a = (x1 + x2)/2 < 1");
    if (a - 1.0 <= 1e-12) {
        // Non-absorbing layer (a = 1, b = 0): b coth(b S Z) -> 1 / (S Z) in Eq. (41).
        if (!(x2 - a > 0.0))
            fail("no solution: x2 <= a");
        return {0.0, 1.0 / (thickness_m * (x2 - a))};
    }
    const double b = std::sqrt(a * a - 1.0);
    // Eq. (47): mu_s = arccoth((x2 - a) / b) / (b Z); arccoth y = atanh(1/y), y > 1.
    const double y = (x2 - a) / b;
    if (!(y > 1.0))
        fail("no solution: coth(b mu_s Z) = (x2 - a)/b <= 1");
    const double mu_s = std::atanh(1.0 / y) / (b * thickness_m);
    // Eq. (48).
    return {(a - 1.0) * mu_s, mu_s};
}

KmCoefficients from_r_infinity(double r_infinity, double assumed_scattering_per_m)
{
    if (!(r_infinity > 0.0 && r_infinity <= 1.0) || !(assumed_scattering_per_m >= 0.0))
        throw std::runtime_error(fmt::format(
            "K from R_inf: need 0 < R_inf <= 1 and S >= 0 (R_inf = {}, S = {} 1/m)",
            r_infinity, assumed_scattering_per_m));
    return {km_k_over_s(r_infinity) * assumed_scattering_per_m, assumed_scattering_per_m};
}

}  // namespace patina::texgen::fade
