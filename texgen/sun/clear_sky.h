// Broadband solar irradiance above the atmosphere and under a cloudless sky.
//
// Clear sky: Ineichen & Perez 2002, "A new airmass independent formulation for the Linke
// turbidity coefficient", Solar Energy 73(3) 151-157, §2 (the form without the
// exp(0.01 AM^1.8) factor of their p. 311 variant, which rises again near the horizon),
// with the relative optical air mass of Kasten & Young 1989. One parameter, the Linke
// turbidity TL (about 2 for a very clean cold sky, 3-4 for typical mid-latitude sites,
// 5-7 for hazy or polluted air).
#pragma once

namespace patina::texgen {

/// The solar constant, W/m^2 (Kopp & Lean 2011, "A new, lower value of total solar
/// irradiance", GRL 38 L01706: 1360.8 +/- 0.5; IAU 2015 Resolution B3 nominal 1361).
constexpr double kSolarConstant = 1361.0;

/// Extraterrestrial normal irradiance at Earth-sun distance `r_au` (inverse square law).
double extraterrestrial_normal_irradiance(double r_au);

/// Relative optical air mass at true zenith angle `zenith_deg` (Kasten & Young 1989,
/// Applied Optics 28(22) 4735-4738): 1 at the zenith, about 38 at the horizon; 0 for a
/// sun at or below the horizon (zenith >= 90).
double relative_air_mass(double zenith_deg);

struct ClearSkyIrradiance {
    double ghi = 0.0;  ///< global horizontal, W/m^2
    double dni = 0.0;  ///< direct normal, W/m^2
    double dhi = 0.0;  ///< diffuse horizontal, W/m^2 (ghi = dni cos z + dhi)
};

struct ClearSkyParameters {
    double linke_turbidity = 3.0;  ///< TL at air mass 2
    double elevation_m = 0.0;      ///< site altitude above sea level
};

/// Ineichen-Perez clear-sky irradiance for a sun at `zenith_deg` with extraterrestrial
/// normal irradiance `i0` (W/m^2). All zero when the sun is at or below the horizon.
ClearSkyIrradiance ineichen_perez(double zenith_deg, double i0, const ClearSkyParameters& p);

}  // namespace patina::texgen
