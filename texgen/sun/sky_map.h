// A lat-long sky for a scene's [environment]: the luminance distribution of a CIE sky
// (cie_sky.h) scaled by the Ineichen-Perez clear-sky irradiances (clear_sky.h), with the
// sun as the scene's [sun] beside it (sharp shadows; importance sampled). Normalised so that
// sky and sun together give a horizontal surface the irradiance pi: a white Lambertian floor
// has radiance 1, whatever the sun's height (docs/lookdev.md "Sky").
#pragma once

#include "texgen/sun/cie_sky.h"
#include "texgen/sun/clear_sky.h"

#include <Imath/ImathVec.h>

#include <vector>

namespace patina::texgen {

struct SkyMapOptions {
    CieSky sky = cie_standard_sky(12);   ///< the CIE standard clear sky
    double sun_elevation_deg = 35.0;
    double sun_azimuth_deg = 150.0;      ///< eastward from north (the [sun] convention)
    double linke_turbidity = 3.0;
    double ground_albedo = 0.2;          ///< the ground below the horizon: a Lambertian floor
    int width = 512;                     ///< height = width / 2
};

struct SkyMap {
    int width = 0, height = 0;
    std::vector<float> radiance;          ///< one grey value per texel, top row the zenith
    Imath::V3d sun_direction;             ///< towards the sun (world: +y up, north -z)
    double sun_irradiance = 0.0;          ///< normal irradiance of the [sun], same scale
    double sky_horizontal = 0.0;          ///< the map's horizontal irradiance, same scale
    ClearSkyIrradiance physical;          ///< W/m^2 before the normalisation
};

/// The sky of `options` as a function of direction: the radiance of any direction on the
/// scale of make_sky_map, and the sun that goes with it.
class SkyModel {
public:
    /// Throws as make_sky_map does.
    explicit SkyModel(const SkyMapOptions& options);
    double radiance(const Imath::V3d& direction) const;
    const Imath::V3d& sun_direction() const { return sun_direction_; }
    double sun_irradiance() const { return sun_irradiance_; }
    double sky_horizontal() const { return sky_horizontal_; }
    const ClearSkyIrradiance& physical() const { return physical_; }

private:
    CieSky sky_;
    Imath::V3d sun_direction_;
    double sun_irradiance_ = 0.0, sky_horizontal_ = 0.0, zenith_radiance_ = 0.0, ground_ = 0.0;
    ClearSkyIrradiance physical_;
};

/// The map and its sun. The overcast sky has no direct sun (all of the horizontal
/// irradiance is the sky's). Throws std::runtime_error for a sun at or below the horizon
/// of a sky with a sun, a width below 8 or an albedo outside [0, 1].
SkyMap make_sky_map(const SkyMapOptions& options);

/// The unit direction of lat-long texel centre (i, j) of a width x height map, as the
/// renderer's [environment] reads it (environment_light.cpp, rotation 0): the top row the
/// zenith, the centre column looking along -z, u = 0.75 towards +x.
Imath::V3d lat_long_direction(int i, int j, int width, int height);

}  // namespace patina::texgen
