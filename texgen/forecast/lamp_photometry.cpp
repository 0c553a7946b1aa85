#include "texgen/forecast/lamp_photometry.h"

#include "core/spectrum.h"

#include <cmath>
#include <stdexcept>

namespace patina::texgen::forecast {

LampPhotometry lamp_photometry(const fade::Illuminant& lamp)
{
    // Trapezoid sums at 1 nm over the band (the tables are at 5 nm and linear between).
    const int n = std::max(1, static_cast<int>(std::ceil(lamp.band_max_nm - lamp.band_min_nm)));
    const double h = (lamp.band_max_nm - lamp.band_min_nm) / n;
    double band = 0.0, visual = 0.0, uv = 0.0, damage = 0.0;
    for (int i = 0; i <= n; ++i) {
        const double nm = lamp.band_min_nm + i * h;
        const double w = (i == 0 || i == n ? 0.5 : 1.0) * h;
        const double s = lamp.relative.at(nm);
        band += w * s;
        visual += w * s * cie_y(static_cast<float>(nm));
        if (nm >= 300.0 && nm <= 400.0)
            uv += w * s;
        if (nm >= 300.0 && nm <= 600.0)
            damage += w * s * std::exp(-kDamageSlopePerNm * (nm - 300.0));
    }
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
