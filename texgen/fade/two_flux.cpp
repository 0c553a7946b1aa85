// Comparisons here raise no floating-point exception anyone looks at: with that known,
// the selects of sublayer_optics become branch-free and its loop vectorises.
#pragma GCC optimize("no-trapping-math")

#include "texgen/fade/two_flux.h"

#include <cassert>
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
    // The adding method is the block elimination of (I - M) x = E_0 (blocks of Eqs. 32-34)
    // from the ground up: R_i and src_i are what eliminating rows i + 1..N leaves of row i.
    thread_local std::vector<double> scratch;
    scratch.resize(4 * (n + 1));
    double* r = scratch.data();
    double* src = r + (n + 1);
    double* t_over_p = src + (n + 1);
    double* a_over_p = t_over_p + (n + 1);
    r[n] = boundary.ground_reflectance;
    src[n] = boundary.bottom_irradiance;
    for (size_t i = n; i-- > 0;) {
        const AddingStep<double> s = adding_step(SublayerTerms<double>{rho[i], tau[i], 1.0},
                                                 r[i + 1]);
        r[i] = s.r;
        t_over_p[i] = s.t_over_p;
        a_over_p[i] = s.a_over_p;
        src[i] = s.t_over_p * src[i + 1];
    }
    down[0] = boundary.top_irradiance;
    for (size_t i = 0; i < n; ++i)
        down[i + 1] = t_over_p[i] * down[i] + a_over_p[i] * src[i + 1];
    for (size_t i = 0; i <= n; ++i)
        up[i] = r[i] * down[i] + src[i];
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
