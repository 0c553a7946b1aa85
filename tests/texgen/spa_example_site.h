// The site of the SPA report's worked example (Reda & Andreas 2004, NREL/TP-560-34302,
// rev. 2008, Table A5.1): Golden, Colorado. Shared by the sun and exposure tests.
#pragma once

#include "texgen/sun/solar_position.h"

namespace patina::test {

inline texgen::SolarSite spa_example_site()
{
    texgen::SolarSite site;
    site.latitude_deg = 39.742476;
    site.longitude_deg = -105.1786;
    site.elevation_m = 1830.14;
    site.pressure_mbar = 820.0;
    site.temperature_c = 11.0;
    site.delta_t_s = 67.0;
    site.atmospheric_refraction_deg = 0.5667;
    return site;
}

}  // namespace patina::test
