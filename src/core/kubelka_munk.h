// Kubelka-Munk diffuse reflectance and transmittance of layers and their subsurface
// compositing (Dorsey & Hanrahan 1996, "Modeling and Rendering of Metallic Patinas", §4.1
// and §4.2; Kubelka 1948 for the layer formulas).
//
// Units: K (absorption) and S (backscattering) per unit length and the thickness d in the
// reciprocal of that unit (e.g. K, S in 1/µm with d in µm); only the products Kd, Sd matter.
// Negative K, S or d are treated as 0.
#pragma once

#include "core/spectrum.h"

#include <span>

namespace patina {

/// Diffuse reflectance R and transmittance T of a layer, both in [0, 1]. A homogeneous
/// layer reflects the same from either side; so does every result of km_composite_stack
/// seen from its top, which is the side R refers to.
struct KmLayer {
    float R = 0.0f;
    float T = 1.0f;
};

/// R and T of a homogeneous layer of thickness d. Exact limits: S = 0 (pure absorber,
/// R = 0, T = exp(-K d)); K = 0 (R = S d / (1 + S d), T = 1 / (1 + S d)); d = 0 (R = 0,
/// T = 1); d -> infinity (R = R_inf, T = 0). No overflow for any thickness.
KmLayer km_layer(float K, float S, float d);

/// Reflectance of an infinitely thick layer from K/S: R_inf = 1 + K/S - sqrt((K/S)^2 + 2 K/S).
float km_r_infinity(float k_over_s);
/// Its inverse: K/S = (1 - R_inf)^2 / (2 R_inf); +infinity for R_inf <= 0.
float km_k_over_s(float r_infinity);

/// `top` over `bottom` (subsurface compositing, all interreflections between the two).
/// `bottom` may itself be a composite; `top` must be homogeneous or symmetric (its
/// reflectance from below is taken equal to R).
KmLayer km_composite(const KmLayer& top, const KmLayer& bottom);

/// A stack ordered from the top (the layer light enters first) to the bottom. It is folded
/// from the bottom up, so that only reflectances seen from above are needed: a composite
/// reflects differently from below, which KmLayer does not store. Empty stack: {0, 1}.
KmLayer km_composite_stack(std::span<const KmLayer> top_to_bottom);

/// Reflectance of a stack (top to bottom) over an opaque base of reflectance base_R (the
/// base is a layer with R = base_R, T = 0).
float km_reflectance_over(std::span<const KmLayer> top_to_bottom, float base_R);

// ---------------------------------------------------------------------------------------
// Spectral versions: the same formulas at every wavelength of a path (K and S vary with
// wavelength, D&H §4.1).
// ---------------------------------------------------------------------------------------

struct KmLayerSpectrum {
    SampledSpectrum R, T;
};

KmLayerSpectrum km_layer(const SampledSpectrum& K, const SampledSpectrum& S, float d);
SampledSpectrum km_r_infinity(const SampledSpectrum& k_over_s);
KmLayerSpectrum km_composite(const KmLayerSpectrum& top, const KmLayerSpectrum& bottom);
KmLayerSpectrum km_composite_stack(std::span<const KmLayerSpectrum> top_to_bottom);
SampledSpectrum km_reflectance_over(std::span<const KmLayerSpectrum> top_to_bottom,
                                    const SampledSpectrum& base_R);

} // namespace patina
