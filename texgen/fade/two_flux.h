// The depth-discretised two-flux model (Kimmel et al. 2013, §4.1): N sublayers of uniform
// absorption and scattering, each with Kubelka's reflectance and transmittance (Eqs. 22,
// 23); the irradiances E^u_i, E^d_i at the N + 1 sublayer boundaries solve the block
// tridiagonal system E = M E + E_0 (Eqs. 24-34), here in O(N) by block Thomas elimination
// (Isaacson & Keller 1994).
#pragma once

#include <cstddef>
#include <span>

namespace patina::texgen::fade {

/// Reflectance rho and transmittance tau of one sublayer (the same from either side).
struct SublayerOptics {
    double rho = 0.0;
    double tau = 1.0;
};

/// exp(y) for y <= 0 (y < -708 gives ~1e-308, not 0), relative error < 4e-16, without
/// branches or library calls, so that loops over wavelengths vectorise: y = n ln2 + r,
/// |r| <= ln2/2, e^r by its Taylor polynomial to degree 12 (remainder < 2e-16), 2^n from
/// the exponent bits.
[[gnu::always_inline]] inline double exp_nonpositive(double y)
{
    // Plain selects and builtins, not std:: wrappers: they inline into callers compiled with
    // other floating-point options (fading_simulation.cpp) and keep the loops vectorisable.
    y = y < -708.0 ? -708.0 : y;
    y = y > 0.0 ? 0.0 : y;
    constexpr double kShift = 6755399441055744.0;  // 1.5 * 2^52: rounds to an integer
    const double t = y * 1.4426950408889634 + kShift;
    const double n = t - kShift;
    // ln 2 split as in fdlibm (Cody-Waite): n * kLn2Hi is exact for |n| < 2^11.
    const double r = (y - n * 6.93147180369123816490e-01) - n * 1.90821492927058770002e-10;
    double p = 1.0 / 479001600.0;
    p = p * r + 1.0 / 39916800.0;
    p = p * r + 1.0 / 3628800.0;
    p = p * r + 1.0 / 362880.0;
    p = p * r + 1.0 / 40320.0;
    p = p * r + 1.0 / 5040.0;
    p = p * r + 1.0 / 720.0;
    p = p * r + 1.0 / 120.0;
    p = p * r + 1.0 / 24.0;
    p = p * r + 1.0 / 6.0;
    p = p * r + 0.5;
    p = p * r + 1.0;
    p = p * r + 1.0;
    // The low bits of t hold n; 2^n = (n + 1023) << 52.
    const long long bits_t = __builtin_bit_cast(long long, t);
    const long long n_int = bits_t - __builtin_bit_cast(long long, kShift);
    return p * __builtin_bit_cast(double, (n_int + 1023) << 52);
}

/// sqrt(v) for v >= 0 (relative error < 1e-15), without the errno branch of std::sqrt:
/// 1/sqrt from the exponent bits (error < 4%), four Newton steps (quadratic: < 1e-20),
/// times v.
[[gnu::always_inline]] inline double sqrt_nonnegative(double v)
{
    v = v > 0.0 ? v : 0.0;
    const double safe = v > 1e-300 ? v : 1e-300;
    double y = __builtin_bit_cast(double, 0x5fe6eb50c7b537a9LL -
                                              (__builtin_bit_cast(long long, safe) >> 1));
    const double half = 0.5 * safe;
    y = y * (1.5 - half * y * y);
    y = y * (1.5 - half * y * y);
    y = y * (1.5 - half * y * y);
    y = y * (1.5 - half * y * y);
    return v * y;
}

/// Eqs. (22), (23) for absorption mu_a and scattering mu_s (1/m) and thickness dz (m).
/// With K = mu_a, S = mu_s, b S = sqrt(K^2 + 2 K S), x = b S dz, e = exp(-x) and
/// q = (1 - e^2) / x (its series for x < 1e-2):
///   rho = S q dz / D, tau = 2 e / D, D = (K + S) q dz + 1 + e^2,
/// Kubelka's formulas multiplied through by 2 e / x: finite for S = 0 (rho = 0,
/// tau = exp(-K dz)) and K = 0 (rho = S dz / (1 + S dz)), no overflow for any thickness,
/// and branch-free so that loops over wavelengths vectorise.
[[gnu::always_inline]] inline SublayerOptics sublayer_optics(double mu_a, double mu_s, double dz)
{
    const double K = mu_a > 0.0 ? mu_a : 0.0;
    const double S = mu_s > 0.0 ? mu_s : 0.0;
    const double d = dz > 0.0 ? dz : 0.0;
    const double x = sqrt_nonnegative(K * (K + 2.0 * S)) * d;
    const double e = exp_nonpositive(-x);
    const double e2 = e * e;
    // 2 e sinh(x) / x: (1 - e^2)/x, or 2 e (1 + x^2/6 + x^4/120 + x^6/5040) near 0.
    const double x2 = x * x;
    const double series = 2.0 * e * (1.0 + x2 * (1.0 / 6.0 + x2 * (1.0 / 120.0 + x2 / 5040.0)));
    // Both computed, then selected: no branch (and no division by x = 0 that counts).
    const double big = (1.0 - e2) / (x < 1e-2 ? 1e-2 : x);
    const double q = x < 1e-2 ? series : big;
    const double inv = 1.0 / ((K + S) * q * d + 1.0 + e2);
    return {S * q * d * inv, 2.0 * e * inv};
}

/// sublayer_optics for n values at once (a loop that vectorises; the per-wavelength
/// blocks of the fading simulation).
void sublayer_optics(const double* mu_a, const double* mu_s, double dz, double* rho,
                     double* tau, size_t n);

/// The boundary conditions: irradiance E_0 entering at the top (Eq. 24), an optional
/// irradiance entering from below through the ground (illumination from both sides; 0 for
/// an opaque substrate), and the ground reflectance rho_N = rho* (Eq. 27).
struct TwoFluxBoundary {
    double top_irradiance = 1.0;
    double bottom_irradiance = 0.0;
    double ground_reflectance = 0.0;
};

/// Solve Eqs. (24)-(27) for the N + 1 boundary irradiances (index 0: top surface) in O(N).
/// rho and tau hold the N sublayers (top first); down and up have N + 1 entries.
/// Row i of (I - M) E = E_0, unknowns x_i = (E^u_i, E^d_i):
///   E^u_i - rho_i E^d_i - tau_i E^u_{i+1} = 0   (i < N; i = N: E^u_N - rho* E^d_N = E_below)
///   E^d_i - rho_{i-1} E^u_i - tau_{i-1} E^d_{i-1} = 0   (i > 0; i = 0: E^d_0 = E_0)
void solve_two_flux(std::span<const double> rho, std::span<const double> tau,
                    const TwoFluxBoundary& boundary, std::span<double> down,
                    std::span<double> up);

/// The mean fluence rate in every sublayer (§4.1): F = E^d + E^u at the boundaries,
/// averaged over the two boundaries of a sublayer. `fluence` has N entries.
void sublayer_fluence_rate(std::span<const double> down, std::span<const double> up,
                           std::span<double> fluence);

}  // namespace patina::texgen::fade
