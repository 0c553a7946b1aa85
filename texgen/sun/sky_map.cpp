#include "texgen/sun/sky_map.h"

#include "texgen/sun/solar_position.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace patina::texgen {

Imath::V3d lat_long_direction(int i, int j, int width, int height)
{
    const double u = (i + 0.5) / width, v = (j + 0.5) / height;
    const double theta = M_PI * v, phi = 2.0 * M_PI * u;
    return {-std::sin(theta) * std::sin(phi), std::cos(theta), std::sin(theta) * std::cos(phi)};
}

SkyMap make_sky_map(const SkyMapOptions& o)
{
    if (o.width < 8 || o.width % 2 != 0)
        throw std::runtime_error(fmt::format("sky: --resolution {} must be even and at least 8",
                                             o.width));
    if (!(o.ground_albedo >= 0.0 && o.ground_albedo <= 1.0))
        throw std::runtime_error(fmt::format("sky: --ground-albedo {} must lie in [0, 1]",
                                             o.ground_albedo));
    const bool overcast = o.sky.type == 0;
    if (!overcast && !(o.sun_elevation_deg > 0.0))
        throw std::runtime_error(fmt::format(
            "sky: the sun at {} degrees is not above the horizon (a clear sky needs it there)",
            o.sun_elevation_deg));
    SkyMap m;
    m.width = o.width;
    m.height = o.width / 2;
    const double zenith = 90.0 - o.sun_elevation_deg;
    m.sun_direction = sun_direction(zenith, o.sun_azimuth_deg);
    ClearSkyParameters p;
    p.linke_turbidity = o.linke_turbidity;
    m.physical = ineichen_perez(std::min(zenith, 89.9), kSolarConstant, p);
    // Horizontal irradiance pi in all: the sun's share is DNI cos z / GHI of it.
    const double cos_z = std::cos(zenith * M_PI / 180.0);
    const double sun_share = overcast || m.physical.ghi <= 0.0
                                 ? 0.0
                                 : m.physical.dni * cos_z / m.physical.ghi;
    m.sky_horizontal = M_PI * (1.0 - sun_share);
    m.sun_irradiance = sun_share > 0.0 ? M_PI * sun_share / cos_z : 0.0;
    // The zenith radiance that gives the sky its share (cie_sky.h horizontal_integral).
    const double zenith_radiance = m.sky_horizontal / horizontal_integral(o.sky, m.sun_direction);
    // Below the horizon a Lambertian ground lit by the whole horizontal irradiance.
    const double ground = o.ground_albedo;
    m.radiance.resize(static_cast<size_t>(m.width) * m.height);
    for (int j = 0; j < m.height; ++j)
        for (int i = 0; i < m.width; ++i) {
            const Imath::V3d d = lat_long_direction(i, j, m.width, m.height);
            m.radiance[static_cast<size_t>(j) * m.width + i] = static_cast<float>(
                d.y > 0.0 ? zenith_radiance * relative_luminance(o.sky, d, m.sun_direction)
                          : ground);
        }
    return m;
}

}  // namespace patina::texgen
