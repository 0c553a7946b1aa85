// Materials for the flatten tests, made in code the way the copper library makes them
// (D&H 1996 §4.1: R_inf of a thick layer, an assumed S, K = S (1 - R_inf)^2 / (2 R_inf)).
#pragma once

#include "core/kubelka_munk.h"
#include "texgen/patina/material_library.h"

namespace patina::test {

inline texgen::PatinaMaterial layer_material(const char* name, Imath::V3f r_inf, float S,
                                             float roughness, float specular)
{
    texgen::PatinaMaterial m;
    m.name = name;
    m.color = r_inf;
    m.scattering = Imath::V3f(S);
    for (int c = 0; c < 3; ++c)
        m.absorption[c] = km_k_over_s(r_inf[c]) * S;
    m.roughness = roughness;
    m.specular = Imath::V3f(specular);
    return m;
}

/// Copper as shaders/patina/copper.toml gives it (linear Rec.709 normal-incidence colour).
inline texgen::PatinaMaterial copper_material()
{
    texgen::PatinaMaterial m;
    m.name = "copper";
    m.is_metal = true;
    m.color = Imath::V3f(0.955f, 0.638f, 0.538f);
    m.specular = m.color;
    m.roughness = 0.15f;
    return m;
}

/// A dielectric base (a stone-like opaque ground) with R_inf (0.6, 0.5, 0.4).
inline texgen::PatinaMaterial stone_material()
{
    texgen::PatinaMaterial m = layer_material("stone", {0.6f, 0.5f, 0.4f}, 1.0f, 0.6f, 0.04f);
    return m;
}

inline texgen::PatinaMaterial green_material()
{
    return layer_material("green", {0.22f, 0.52f, 0.38f}, 0.35f, 0.5f, 0.04f);
}

inline texgen::PatinaMaterial brown_material()
{
    return layer_material("brown", {0.42f, 0.13f, 0.09f}, 1.2f, 0.25f, 0.08f);
}

}  // namespace patina::test
