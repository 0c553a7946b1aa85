// A fading material made in code for the fade-map and spectral_km tests: a 20 µm layer of
// a white, lightfast binder (scatters, does not absorb) holding a magenta-like pigment
// (an absorption band around 530 nm and in the near UV) that fades, over a grey substrate.
// Its numbers are chosen to give a half-transparent layer (S d ~ 1) and visible fading at
// doses of 1e5-1e7 J/m²; they are not a real pigment.
#pragma once

#include "texgen/fade/dose_table.h"
#include "texgen/fade/fade_material.h"
#include "texgen/fade/illuminant.h"

#include <cmath>

namespace patina::test {

inline texgen::fade::FadeMaterial fading_test_material(double substrate = 0.7)
{
    using namespace texgen::fade;
    TabulatedSpectrum band;
    for (double nm = 300.0; nm <= 830.0; nm += 10.0) {
        band.nm.push_back(nm);
        // 2e5 1/m peak at 530 nm, a UV tail below 400 nm
        const double visible = std::exp(-0.5 * std::pow((nm - 530.0) / 40.0, 2.0));
        const double uv = nm < 400.0 ? (400.0 - nm) / 100.0 : 0.0;
        band.value.push_back(2e5 * (visible + 0.5 * uv));
    }
    Colorant pigment;
    pigment.name = "test_magenta";
    pigment.absorption_per_m = band;
    pigment.scattering_per_m = TabulatedSpectrum::constant(1e4);
    pigment.fading = {2e-10, 500.0, 700.0};
    Colorant binder;
    binder.name = "test_binder";
    binder.absorption_per_m = TabulatedSpectrum::constant(0.0);
    binder.scattering_per_m = TabulatedSpectrum::constant(6e4);
    binder.fading = {0.0, 500.0, 700.0};

    FadeMaterial m;
    m.name = "test_magenta_layer";
    m.description = "fade-map test material";
    m.thickness_m = 20e-6;
    m.colorants = {pigment, binder};
    m.initial_fractions = {0.3, 0.7};
    m.substrate_reflectance = TabulatedSpectrum::constant(substrate);
    return m;
}

/// 300-830 nm every 10 nm: coarse enough for fast tests, fine enough for D65's shape.
inline texgen::fade::WavelengthGrid fading_test_grid()
{
    return texgen::fade::WavelengthGrid::uniform(300.0, 830.0, 10.0);
}

}  // namespace patina::test
