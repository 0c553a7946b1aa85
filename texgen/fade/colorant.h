// A colorant of the spectral fading model (Kimmel et al. 2013, §3): its absorption and
// scattering per unit volume fraction, its volumetric fading rate β and, optionally, the
// colorant it breaks down into with the breakdown rate γ (Eq. 15, lignin -> o-quinone).
//
// Absorption per unit volume fraction: the absorption coefficient of the colorant at volume
// fraction f is mu_a = f * absorption(λ) (Eq. 12 sums these over colorants). The time step
// (Eq. 35) uses absorption(λ) = mu_a / f, constant for a colorant, so fading is first order
// in f (the kinetics the paper cites, Johnston-Feller et al. 1984) and not second order as
// Eq. (35) with the current mu_a would make it (DESIGN.md, "The models").
#pragma once

#include "texgen/fade/spectral_grid.h"

#include <optional>
#include <string>

namespace patina::texgen::fade {

/// A rate proportional to wavelength up to a cut-off (§3.1.2: β is proportional to the
/// number of photons absorbed, so to λ; no reaction beyond λmax):
///   rate(λ) = rate_m3_per_j * λ / reference_nm   for λ <= cutoff_nm, else 0.
/// Tables II and III quote β, γ at 400 nm; Table V at 500 nm.
struct WavelengthRate {
    double rate_m3_per_j = 0.0;
    double reference_nm = 400.0;
    double cutoff_nm = 700.0;

    double at(double lambda_nm) const
    {
        return lambda_nm <= cutoff_nm ? rate_m3_per_j * lambda_nm / reference_nm : 0.0;
    }
};

/// Eq. (15): absorption by this colorant turns it into `product` at the rate γ.
struct Breakdown {
    std::string product;  ///< name of the product colorant (in the same material)
    WavelengthRate rate;  ///< γ (m^3/J)
};

struct Colorant {
    std::string name;
    TabulatedSpectrum absorption_per_m;  ///< mu_a / f, 1/m
    TabulatedSpectrum scattering_per_m;  ///< mu_s / f (KM backscattering), 1/m
    WavelengthRate fading;                ///< β (m^3/J); rate 0: lightfast
    std::optional<Breakdown> breakdown;
    std::string description;
};

}  // namespace patina::texgen::fade
