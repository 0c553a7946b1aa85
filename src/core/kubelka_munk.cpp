// Kubelka-Munk layers and subsurface compositing (Dorsey & Hanrahan 1996 §4.1-4.2).
#include "core/kubelka_munk.h"

#include <patina/shading/kubelka_munk.h>

#include <cmath>

namespace patina {

// The formulas are include/patina/shading/kubelka_munk.h (D&H 1996 §4.1-4.2), evaluated in
// double; these wrappers take and give the core's floats.

KmLayer km_layer(float K, float S, float d)
{
    if (std::isinf(d) && d > 0.0f) {
        // R∞ of K/S (in double, rounded to float).
        const double k = K > 0.0f ? K : 0.0f;
        return {S > 0.0f ? km_r_infinity(static_cast<float>(k / S)) : 0.0f, 0.0f};
    }
    const shading::KmLayers<double> l = shading::km_layer(K, S, d);
    return {static_cast<float>(l.r_top), static_cast<float>(l.t)};
}

float km_r_infinity(float k_over_s)
{
    return static_cast<float>(shading::km_r_infinity(k_over_s));
}

float km_k_over_s(float r_infinity)
{
    return static_cast<float>(shading::km_k_over_s(r_infinity));
}

KmLayer km_composite(const KmLayer& top, const KmLayer& bottom)
{
    // `top` is homogeneous: it reflects R from either side.
    const shading::KmLayers<double> l = shading::km_composite<double>(
        {top.R, top.R, top.T}, {bottom.R, bottom.R, bottom.T});
    return {static_cast<float>(l.r_top), static_cast<float>(l.t)};
}

KmLayer km_composite_stack(std::span<const KmLayer> top_to_bottom)
{
    // D&H 1996 §4.2: repeated pairwise compositing; bottom-up so every `top` is homogeneous.
    KmLayer acc; // R = 0, T = 1: the empty stack
    for (auto it = top_to_bottom.rbegin(); it != top_to_bottom.rend(); ++it)
        acc = km_composite(*it, acc);
    return acc;
}

float km_reflectance_over(std::span<const KmLayer> top_to_bottom, float base_R)
{
    // D&H 1996 §4.2: the opaque base is one more layer, with T = 0.
    KmLayer acc{base_R, 0.0f};
    for (auto it = top_to_bottom.rbegin(); it != top_to_bottom.rend(); ++it)
        acc = km_composite(*it, acc);
    return acc.R;
}

KmLayerSpectrum km_layer(const SampledSpectrum& K, const SampledSpectrum& S, float d)
{
    KmLayerSpectrum out{SampledSpectrum(K.count, 0.0f), SampledSpectrum(K.count, 1.0f)};
    for (int i = 0; i < K.count; ++i) {
        const KmLayer l = km_layer(K[i], S[i], d);
        out.R[i] = l.R;
        out.T[i] = l.T;
    }
    return out;
}

SampledSpectrum km_r_infinity(const SampledSpectrum& k_over_s)
{
    SampledSpectrum r = k_over_s;
    for (int i = 0; i < r.count; ++i)
        r[i] = km_r_infinity(k_over_s[i]);
    return r;
}

KmLayerSpectrum km_composite(const KmLayerSpectrum& top, const KmLayerSpectrum& bottom)
{
    KmLayerSpectrum out = top;
    for (int i = 0; i < top.R.count; ++i) {
        const KmLayer l = km_composite({top.R[i], top.T[i]}, {bottom.R[i], bottom.T[i]});
        out.R[i] = l.R;
        out.T[i] = l.T;
    }
    return out;
}

KmLayerSpectrum km_composite_stack(std::span<const KmLayerSpectrum> top_to_bottom)
{
    if (top_to_bottom.empty())
        return {};
    const int n = top_to_bottom.front().R.count;
    KmLayerSpectrum acc{SampledSpectrum(n, 0.0f), SampledSpectrum(n, 1.0f)};
    for (auto it = top_to_bottom.rbegin(); it != top_to_bottom.rend(); ++it)
        acc = km_composite(*it, acc);
    return acc;
}

SampledSpectrum km_reflectance_over(std::span<const KmLayerSpectrum> top_to_bottom,
                                    const SampledSpectrum& base_R)
{
    KmLayerSpectrum acc{base_R, SampledSpectrum(base_R.count, 0.0f)};
    for (auto it = top_to_bottom.rbegin(); it != top_to_bottom.rend(); ++it)
        acc = km_composite(*it, acc);
    return acc.R;
}

} // namespace patina
