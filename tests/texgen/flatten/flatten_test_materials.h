// Materials for the flatten tests, as a stack.toml records them ([patina.materials]): a
// layer's K and S per µm, linear in wavelength between 360 and 830 nm (so that every band
// sees another value), its specular reflectance and roughness; a metal's n and k.
#pragma once

#include "formats/texture_stack/texture_stack.h"
#include "texgen/flatten/band_optics.h"

#include <string>
#include <utility>
#include <vector>

namespace patina::test {

/// K and S of a test layer at 360 nm and at 830 nm.
struct LinearLayer {
    const char* name;
    double K_360, K_830, S_360, S_830, specular, roughness;
};

inline formats::MaterialOptics layer_optics(const LinearLayer& l)
{
    formats::MaterialOptics m;
    m.name = l.name;
    m.roughness = l.roughness;
    m.lambda_nm = {360.0, 830.0};
    m.absorption_per_um = {l.K_360, l.K_830};
    m.scattering_per_um = {l.S_360, l.S_830};
    m.specular = {l.specular, l.specular};
    return m;
}

/// A value linear between `at_360` and `at_830`, at `lambda_nm` (as the bands interpolate).
inline double linear_at(double at_360, double at_830, double lambda_nm)
{
    return at_360 + (at_830 - at_360) * (lambda_nm - 360.0) / (830.0 - 360.0);
}

/// Copper's complex index at 600 nm (Johnson & Christy 1972: n 0.25, k 3.42), constant.
inline formats::MaterialOptics copper_optics()
{
    formats::MaterialOptics m;
    m.name = "copper";
    m.metal = true;
    m.roughness = 0.15;
    m.lambda_nm = {360.0, 830.0};
    m.n = {0.25, 0.25};
    m.k = {3.42, 3.42};
    return m;
}

/// A dielectric base (a stone-like opaque ground), yellowish.
inline const LinearLayer kStone{"stone", 0.40, 0.08, 1.0, 1.0, 0.04, 0.6};
/// A green corrosion layer (absorbs at both ends).
inline const LinearLayer kGreen{"green", 0.30, 0.45, 0.35, 0.30, 0.04, 0.5};
/// A brown tarnish (absorbs blue most).
inline const LinearLayer kBrown{"brown", 2.0, 0.3, 1.2, 1.2, 0.08, 0.25};

/// The stack of `base` under `layers` (bottom to top), as a manifest records it.
inline texgen::BandStack test_stack(const formats::MaterialOptics& base,
                                    const std::vector<formats::MaterialOptics>& layers)
{
    formats::PatinaTable t;
    t.base = base.name;
    t.materials.emplace(base.name, base);
    for (const formats::MaterialOptics& l : layers) {
        formats::PatinaLayer entry;
        entry.material = l.name;
        t.layers.push_back(entry);
        t.materials.emplace(l.name, l);
    }
    return texgen::band_stack(t, "test/stack.toml");
}

}  // namespace patina::test
