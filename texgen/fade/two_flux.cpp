// Comparisons here raise no floating-point exception anyone looks at: with that known,
// the selects of sublayer_optics become branch-free and its loop vectorises.
#pragma GCC optimize("no-trapping-math")

#include "texgen/fade/two_flux.h"

#include <cassert>
#include <cmath>
#include <vector>

namespace patina::texgen::fade {

void sublayer_optics(const double* mu_a, const double* mu_s, double dz, double* rho,
                     double* tau, size_t n)
{
    for (size_t k = 0; k < n; ++k) {
        const SublayerOptics o = sublayer_optics(mu_a[k], mu_s[k], dz);
        rho[k] = o.rho;
        tau[k] = o.tau;
    }
}

void solve_two_flux(std::span<const double> rho, std::span<const double> tau,
                    const TwoFluxBoundary& boundary, std::span<double> down,
                    std::span<double> up)
{
    const size_t n = rho.size();
    assert(tau.size() == n && down.size() == n + 1 && up.size() == n + 1);
    // Block Thomas elimination of (I - M) x = E_0 with x_i = (E^u_i, E^d_i) and the 2x2
    // blocks of Eqs. (32)-(34):
    //   diagonal D_i = I - R_i = [[1, -rho_i], [-rho_{i-1}, 1]]  (rho_{-1} = 0, rho_N = rho*)
    //   upper    U_i = -T^u_i  = [[-tau_i, 0], [0, 0]]
    //   lower    L_i = -T^d_{i-1} = [[0, 0], [0, -tau_{i-1}]].
    // Forward: W_i = D_i - L_i C_{i-1}, C_i = W_i^-1 U_i, g_i = W_i^-1 (b_i - L_i g_{i-1});
    // back: x_N = g_N, x_i = g_i - C_i x_{i+1}. U_i has one non-zero entry, so C_i has one
    // non-zero column (c0, c1) and L_i C_{i-1} one non-zero entry, at (1, 0).
    thread_local std::vector<double> scratch;
    scratch.resize(4 * (n + 1));
    double* c0 = scratch.data();
    double* c1 = c0 + (n + 1);
    double* g0 = c1 + (n + 1);
    double* g1 = g0 + (n + 1);

    double prev_c1 = 0.0, prev_g1 = 0.0, prev_tau = 0.0;
    for (size_t i = 0; i <= n; ++i) {
        const double rho_above = i > 0 ? rho[i - 1] : 0.0;
        const double rho_here = i < n ? rho[i] : boundary.ground_reflectance;
        // W = [[1, -rho_i], [w10, 1]] with w10 = -rho_{i-1} + tau_{i-1} c1_{i-1}.
        const double w01 = -rho_here;
        const double w10 = -rho_above + prev_tau * prev_c1;
        const double inv_det = 1.0 / (1.0 - w01 * w10);
        // Right-hand side b_i - L_i g_{i-1}: b_0 = (0, E_0), b_N = (E_below, 0).
        const double r0 = i == n ? boundary.bottom_irradiance : 0.0;
        const double r1 = (i == 0 ? boundary.top_irradiance : 0.0) + prev_tau * prev_g1;
        // W^-1 = [[1, -w01], [-w10, 1]] / det.
        g0[i] = (r0 - w01 * r1) * inv_det;
        g1[i] = (r1 - w10 * r0) * inv_det;
        const double t = i < n ? tau[i] : 0.0;
        c0[i] = -t * inv_det;
        c1[i] = t * w10 * inv_det;
        prev_c1 = c1[i];
        prev_g1 = g1[i];
        prev_tau = t;
    }
    up[n] = g0[n];
    down[n] = g1[n];
    for (size_t i = n; i-- > 0;) {
        up[i] = g0[i] - c0[i] * up[i + 1];
        down[i] = g1[i] - c1[i] * up[i + 1];
    }
}

void sublayer_fluence_rate(std::span<const double> down, std::span<const double> up,
                           std::span<double> fluence)
{
    const size_t n = fluence.size();
    assert(down.size() == n + 1 && up.size() == n + 1);
    // §4.1, fluence rate estimation: F = E^d + E^u at the boundaries, averaged per sublayer.
    for (size_t i = 0; i < n; ++i)
        fluence[i] = 0.5 * (down[i] + up[i] + down[i + 1] + up[i + 1]);
}

}  // namespace patina::texgen::fade
