// The depth-discretised two-flux model (Kimmel et al. 2013, §4.1): N sublayers of uniform
// absorption and scattering, each with Kubelka's reflectance and transmittance (Eqs. 22,
// 23); the irradiances E^u_i, E^d_i at the N + 1 sublayer boundaries solve the block
// tridiagonal system E = M E + E_0 (Eqs. 24-34), here in O(N) by block Thomas elimination
// (Isaacson & Keller 1994).
#pragma once

#include <span>

namespace patina::texgen::fade {

/// Reflectance rho and transmittance tau of one sublayer (the same from either side).
struct SublayerOptics {
    double rho = 0.0;
    double tau = 1.0;
};

/// Eqs. (22), (23) for absorption mu_a and scattering mu_s (1/m) and thickness dz (m),
/// with exact limits for mu_s = 0 (rho = 0, tau = exp(-mu_a dz)) and mu_a = 0
/// (rho = mu_s dz / (1 + mu_s dz)); no overflow for any optical thickness.
SublayerOptics sublayer_optics(double mu_a, double mu_s, double dz);

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
