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

SkyModel::SkyModel(const SkyMapOptions& o) : sky_(o.sky)
{
    if (!(o.ground_albedo >= 0.0 && o.ground_albedo <= 1.0))
        throw std::runtime_error(fmt::format("sky: --ground-albedo {} must lie in [0, 1]",
                                             o.ground_albedo));
    const bool overcast = o.sky.type == 0;
    if (!overcast && !(o.sun_elevation_deg > 0.0))
        throw std::runtime_error(fmt::format(
            "sky: the sun at {} degrees is not above the horizon (a clear sky needs it there)",
            o.sun_elevation_deg));
    const double zenith = 90.0 - o.sun_elevation_deg;
    sun_direction_ = texgen::sun_direction(zenith, o.sun_azimuth_deg);
    ClearSkyParameters p;
    p.linke_turbidity = o.linke_turbidity;
    physical_ = ineichen_perez(std::min(zenith, 89.9), kSolarConstant, p);
    // Horizontal irradiance pi in all: the sun's share is DNI cos z / GHI of it.
    const double cos_z = std::cos(zenith * M_PI / 180.0);
    const double sun_share =
        overcast || physical_.ghi <= 0.0 ? 0.0 : physical_.dni * cos_z / physical_.ghi;
    sky_horizontal_ = M_PI * (1.0 - sun_share);
    sun_irradiance_ = sun_share > 0.0 ? M_PI * sun_share / cos_z : 0.0;
    // The zenith radiance that gives the sky its share (cie_sky.h horizontal_integral).
    zenith_radiance_ = sky_horizontal_ / horizontal_integral(sky_, sun_direction_);
    // Below the horizon a Lambertian ground lit by the whole horizontal irradiance pi.
    ground_ = o.ground_albedo;
}

double SkyModel::radiance(const Imath::V3d& d) const
{
    return d.y > 0.0 ? zenith_radiance_ * relative_luminance(sky_, d, sun_direction_) : ground_;
}

SkyMap make_sky_map(const SkyMapOptions& o)
{
    if (o.width < 8 || o.width % 2 != 0)
        throw std::runtime_error(fmt::format("sky: --resolution {} must be even and at least 8",
                                             o.width));
    const SkyModel model(o);
    SkyMap m;
    m.width = o.width;
    m.height = o.width / 2;
    m.sun_direction = model.sun_direction();
    m.sun_irradiance = model.sun_irradiance();
    m.sky_horizontal = model.sky_horizontal();
    m.physical = model.physical();
    m.radiance.resize(static_cast<size_t>(m.width) * m.height);
    for (int j = 0; j < m.height; ++j)
        for (int i = 0; i < m.width; ++i)
            m.radiance[static_cast<size_t>(j) * m.width + i] =
                static_cast<float>(model.radiance(lat_long_direction(i, j, m.width, m.height)));
    return m;
}

}  // namespace patina::texgen
