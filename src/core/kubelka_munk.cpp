// Kubelka-Munk layers and subsurface compositing (Dorsey & Hanrahan 1996 §4.1-4.2).
#include "core/kubelka_munk.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace patina {
namespace {

    double non_negative(float v)
    {
        return v > 0.0f ? static_cast<double>(v) : 0.0;
    }

} // namespace

KmLayer km_layer(float K_in, float S_in, float d_in)
{
    const double K = non_negative(K_in), S = non_negative(S_in), d = non_negative(d_in);
    if (std::isinf(d))
        return {S > 0.0 ? km_r_infinity(static_cast<float>(K / S)) : 0.0f, 0.0f};
    // D&H 1996 §4.1: R = sinh(bSd) / (a sinh(bSd) + b cosh(bSd)),
    //                T = b / (a sinh(bSd) + b cosh(bSd)),  a = (S + K) / S, b = sqrt(a^2 - 1).
    // Multiplying through by S (Sa = S + K, Sb = beta = sqrt(K (K + 2S))) and by 2 e^-x / beta
    // with x = beta d gives a form without overflow or 0/0 that holds at S = 0 and K = 0:
    //   R = S g / ((S + K) g + 1 + e^-2x),  T = 2 e^-x / ((S + K) g + 1 + e^-2x),
    //   g = (1 - e^-2x) / beta  (-> 2d as beta -> 0).
    const double beta = std::sqrt(K * (K + 2.0 * S));
    const double x = beta * d;
    const double g = beta > 0.0 ? -std::expm1(-2.0 * x) / beta : 2.0 * d;
    const double denom = (S + K) * g + 1.0 + std::exp(-2.0 * x);
    return {static_cast<float>(S * g / denom), static_cast<float>(2.0 * std::exp(-x) / denom)};
}

float km_r_infinity(float k_over_s)
{
    const double q = non_negative(k_over_s);
    if (std::isinf(q))
        return 0.0f;
    // D&H 1996 §4.1: R_inf = 1 + K/S - sqrt((K/S)^2 + 2 K/S) (the minus sign was lost in the
    // text copy; DESIGN.md), evaluated as the equal 1 / (1 + K/S + sqrt(...)) to avoid
    // cancellation for large K/S.
    return static_cast<float>(1.0 / (1.0 + q + std::sqrt(q * q + 2.0 * q)));
}

float km_k_over_s(float r_infinity)
{
    if (!(r_infinity > 0.0f))
        return std::numeric_limits<float>::infinity();
    // D&H 1996 §4.1, R_inf inverted: K/S = (1 - R_inf)^2 / (2 R_inf).
    const double r = std::min(static_cast<double>(r_infinity), 1.0);
    return static_cast<float>((1.0 - r) * (1.0 - r) / (2.0 * r));
}

KmLayer km_composite(const KmLayer& top, const KmLayer& bottom)
{
    const double r1 = top.R, t1 = top.T, r2 = bottom.R, t2 = bottom.T;
    // 1 - R1 R2 is 0 only for two perfect non-absorbing infinite layers: then R = 1, T = 0.
    const double m = 1.0 - r1 * r2;
    if (m <= 0.0)
        return {1.0f, 0.0f};
    // D&H 1996 §4.2: R = R1 + T1^2 R2 / (1 - R1 R2), T = T1 T2 / (1 - R1 R2).
    return {static_cast<float>(r1 + t1 * t1 * r2 / m), static_cast<float>(t1 * t2 / m)};
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
