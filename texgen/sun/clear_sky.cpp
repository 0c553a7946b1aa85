#include "texgen/sun/clear_sky.h"

#include <algorithm>
#include <cmath>

namespace patina::texgen {

namespace {
constexpr double kDegToRad = 3.14159265358979323846 / 180.0;
}

double extraterrestrial_normal_irradiance(double r_au)
{
    return kSolarConstant / (r_au * r_au);
}

double relative_air_mass(double zenith_deg)
{
    if (!(zenith_deg < 90.0))
        return 0.0;
    // Kasten & Young 1989 Eq. 3 with the elevation gamma = 90 - z in degrees.
    const double elevation = 90.0 - zenith_deg;
    return 1.0 / (std::sin(elevation * kDegToRad) +
                  0.50572 * std::pow(elevation + 6.07995, -1.6364));
}

ClearSkyIrradiance ineichen_perez(double zenith_deg, double i0, const ClearSkyParameters& p)
{
    ClearSkyIrradiance out;
    const double cos_z = std::cos(zenith_deg * kDegToRad);
    if (!(zenith_deg < 90.0) || cos_z <= 0.0)
        return out;
    const double am = relative_air_mass(zenith_deg);
    const double tl = p.linke_turbidity;
    const double h = p.elevation_m;
    // Altitude corrections (Ineichen & Perez 2002 §2): scale heights of the
    // Rayleigh and aerosol extinctions.
    const double fh1 = std::exp(-h / 8000.0);
    const double fh2 = std::exp(-h / 1250.0);
    const double cg1 = 5.09e-5 * h + 0.868;
    const double cg2 = 3.92e-5 * h + 0.0387;
    // Global horizontal (Ineichen & Perez 2002 §2, Gc).
    out.ghi = cg1 * i0 * cos_z * std::exp(-cg2 * am * (fh1 + fh2 * (tl - 1.0)));
    // Beam normal (their Bnc), bounded by the beam fraction of the global (their Bnc') so
    // that the diffuse part never goes negative at low sun.
    const double b = 0.664 + 0.163 / fh1;
    const double beam = b * i0 * std::exp(-0.09 * am * (tl - 1.0));
    const double beam_limit =
        out.ghi * (1.0 - (0.1 - 0.2 * std::exp(-tl)) / (0.1 + 0.882 / fh1)) / cos_z;
    out.dni = std::max(0.0, std::min(beam, beam_limit));
    out.dhi = std::max(0.0, out.ghi - out.dni * cos_z);
    return out;
}

}  // namespace patina::texgen
