// The sun's position seen from a site: NREL's Solar Position Algorithm (Reda & Andreas 2004,
// "Solar Position Algorithm for Solar Radiation Applications", NREL/TP-560-34302, revised
// 2008), uncertainty +/-0.0003 degrees for the years -2000 to 6000. Angles in degrees.
#pragma once

#include <Imath/ImathVec.h>

#include <optional>

namespace patina::texgen {

/// Where and in what air the sun is observed.
struct SolarSite {
    double latitude_deg = 0.0;    ///< geodetic, north positive
    double longitude_deg = 0.0;   ///< east positive (Greenwich 0)
    double elevation_m = 0.0;     ///< above sea level
    double pressure_mbar = 1013.25;  ///< annual mean local pressure, for refraction
    double temperature_c = 15.0;     ///< annual mean local temperature, for refraction
    /// TT - UT in seconds (about 64 s in 2000, 69 s in 2020; see the IERS bulletins);
    /// unset, the Espenak & Meeus (2006) polynomials at the date (sun/delta_t.h).
    std::optional<double> delta_t_s;
    /// Refraction of the sun at sunrise/sunset, degrees (SPA's atmos_refract).
    double atmospheric_refraction_deg = 0.5667;
};

/// Every intermediate and final quantity of the SPA (the names of Reda & Andreas §3).
struct SolarPosition {
    double julian_day = 0;           ///< JD (UT), Eq. 4
    double delta_t_s = 0;             ///< TT − UT used, s (the site's, or from the date)
    double julian_ephemeris_day = 0;  ///< JDE, Eq. 5
    double heliocentric_longitude_deg = 0;  ///< L, Eq. 9-12 (0..360)
    double heliocentric_latitude_deg = 0;   ///< B
    double earth_radius_vector_au = 0;      ///< R, Earth-sun distance in AU
    double nutation_longitude_deg = 0;      ///< delta psi, Eq. 20
    double nutation_obliquity_deg = 0;      ///< delta epsilon, Eq. 21
    double true_obliquity_deg = 0;          ///< epsilon, Eq. 25
    double aberration_deg = 0;              ///< delta tau, Eq. 26
    double apparent_longitude_deg = 0;      ///< lambda, Eq. 27
    double apparent_sidereal_time_deg = 0;  ///< nu, Eq. 29
    double right_ascension_deg = 0;         ///< alpha (geocentric), Eq. 30
    double declination_deg = 0;             ///< delta (geocentric), Eq. 31
    double hour_angle_deg = 0;              ///< H (observer local, geocentric), Eq. 32, 0..360
    double topocentric_right_ascension_deg = 0;  ///< alpha', Eq. 38
    double topocentric_declination_deg = 0;      ///< delta', Eq. 39
    double topocentric_hour_angle_deg = 0;       ///< H', Eq. 40
    double elevation_no_refraction_deg = 0;      ///< e0, Eq. 41
    double refraction_deg = 0;                   ///< delta e, Eq. 42
    double elevation_deg = 0;   ///< e, topocentric, refraction included, Eq. 43
    double zenith_deg = 0;      ///< theta = 90 - e, Eq. 44
    double azimuth_deg = 0;     ///< Phi, eastward from north, 0..360, Eq. 45-46
};

/// The SPA at Julian day `jd_ut` (UT) for `site` (Reda & Andreas 2004 §3.1-3.15).
SolarPosition solar_position(double jd_ut, const SolarSite& site);

/// Angle between the sun and the normal of a surface tilted `slope_deg` from the
/// horizontal, whose normal's azimuth is `surface_azimuth_rotation_deg` measured from south,
/// positive towards west (Reda & Andreas Eq. 47).
double incidence_angle_deg(const SolarPosition& sun, double slope_deg,
                           double surface_azimuth_rotation_deg);

/// The unit direction towards the sun in Patina's world frame: +y up, north -z, east +x
/// (the renderer's [sun] convention), for a zenith and an azimuth eastward from north.
Imath::V3d sun_direction(double zenith_deg, double azimuth_deg);

}  // namespace patina::texgen
