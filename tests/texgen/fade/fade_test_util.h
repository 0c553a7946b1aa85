// Materials made in code for the fading tests.
#pragma once

#include "texgen/fade/fade_material.h"

#include <string>

namespace patina::texgen::fade::test {

/// A colorant with flat absorption and scattering per unit fraction (1/m) and a flat β
/// (reference 500 nm, cut-off far away, so β is λ/500 times `beta`).
inline Colorant flat_colorant(const std::string& name, double absorption, double scattering,
                              double beta)
{
    Colorant c;
    c.name = name;
    c.absorption_per_m = TabulatedSpectrum::constant(absorption);
    c.scattering_per_m = TabulatedSpectrum::constant(scattering);
    c.fading = {beta, 500.0, 1e9};
    return c;
}

inline FadeMaterial material_of(std::vector<Colorant> colorants, std::vector<double> fractions,
                                double thickness_m, double substrate)
{
    FadeMaterial m;
    m.name = "test";
    m.thickness_m = thickness_m;
    m.colorants = std::move(colorants);
    m.initial_fractions = std::move(fractions);
    m.substrate_reflectance = TabulatedSpectrum::constant(substrate);
    return m;
}

}  // namespace patina::texgen::fade::test
