#include "texgen/forecast/lamp_photometry.h"

#include "core/spectrum.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen::forecast {

namespace {

/// ∫ f over [lo, hi] ∩ the lamp's band, trapezoids of at most 1 nm.
template <class F>
double integrate(const fade::Illuminant& lamp, double lo, double hi, F f)
{
    lo = std::max(lo, lamp.band_min_nm);
    hi = std::min(hi, lamp.band_max_nm);
    if (!(hi > lo))
        return 0.0;
    const int n = std::max(1, static_cast<int>(std::ceil(hi - lo)));
    const double h = (hi - lo) / n;
    double sum = 0.0;
    for (int i = 0; i <= n; ++i) {
        const double nm = lo + i * h;
        sum += (i == 0 || i == n ? 0.5 : 1.0) * h * lamp.relative.at(nm) * f(nm);
    }
    return sum;
}

}  // namespace

LampPhotometry lamp_photometry(const fade::Illuminant& lamp)
{
    const double band = integrate(lamp, lamp.band_min_nm, lamp.band_max_nm, [](double) { return 1.0; });
    const double visual = integrate(lamp, lamp.band_min_nm, lamp.band_max_nm,
                                    [](double nm) { return cie_y(static_cast<float>(nm)); });
    const double uv = integrate(lamp, 300.0, 400.0, [](double) { return 1.0; });
    const double damage = integrate(lamp, 300.0, 600.0, [](double nm) {
        return std::exp(-kDamageSlopePerNm * (nm - 300.0));
    });
    if (!(visual > 0.0))
        throw std::runtime_error("lamp '" + lamp.name + "' emits no light (no power where the "
                                 "eye sees, 360-830 nm): it has no illuminance to scale");
    const double lumens = kMaxLuminousEfficacy * visual;
    LampPhotometry p;
    p.luminous_efficacy_lm_per_w = lumens / band;
    p.uv_uw_per_lm = uv / lumens * 1e6;
    p.damage_factor_w_per_lm = damage / lumens;
    return p;
}

}  // namespace patina::texgen::forecast
