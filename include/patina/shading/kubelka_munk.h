// Kubelka-Munk layers and their subsurface compositing, written once for every user: the
// core library and texgen (double), the layered_km shader (four float lanes) and the
// spectral_km shader (float). Dorsey & Hanrahan 1996 §4.1 (one layer) and §4.2 (layers over
// layers); Kubelka 1948 for the closed forms; the same as Kimmel et al. 2013 Eqs. 22-27.
//
// The fading solver (texgen/fade/two_flux.h) evaluates the same layer in unnormalised terms
// (R = a/d, T = t/d) fused into its adding method, for speed; its tests compare it with
// these.
//
// Units: K (absorption) and S (backscattering) per unit length and the thickness d in the
// reciprocal of that unit (K, S in 1/µm with d in µm); only Kd and Sd matter. Negative K, S
// or d count as 0. Header-only and free of the renderer: plugins include it.
#pragma once

#include <patina/shading/lanes.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace patina::shading {

/// A layer, or a stack of layers seen as one, by the light it returns: its diffuse
/// reflectance lit from above (r_top) and from below (r_bottom), and its diffuse
/// transmittance (t, the same both ways). A homogeneous layer has r_top = r_bottom. T is
/// double, float or simd::V4 (four wavelengths).
template <class T>
struct KmLayers {
    T r_top{};
    T r_bottom{};
    T t = T{} + 1;  ///< the empty stack: nothing reflected, everything through
};

/// `top` over `bottom`, all interreflections between them summed (§4.2, Kubelka 1948):
///   r_top    = top.r_top + top.t² bottom.r_top / (1 − top.r_bottom bottom.r_top)
///   r_bottom = bottom.r_bottom + bottom.t² top.r_bottom / (1 − ...)
///   t        = top.t bottom.t / (1 − ...)
/// The denominator vanishes only between two lossless mirrors (r = 1, so t = 0): then the
/// limits r_top = top.r_top, r_bottom = bottom.r_bottom, t = 0 are returned (lane by lane).
template <class T>
inline KmLayers<T> km_composite(const KmLayers<T>& top, const KmLayers<T>& bottom)
{
    const T m = 1 - top.r_bottom * bottom.r_top;
    const auto ok = m > T{};
    return {ok ? top.r_top + top.t * top.t * bottom.r_top / m : top.r_top,
            ok ? bottom.r_bottom + bottom.t * bottom.t * top.r_bottom / m : bottom.r_bottom,
            ok ? top.t * bottom.t / m : T{}};
}

/// The reflectance of `layers` over an opaque ground of reflectance `ground` (a layer with
/// t = 0): km_composite(layers, ground).r_top.
template <class T>
inline T km_reflectance_over(const KmLayers<T>& layers, T ground)
{
    return km_composite(layers, KmLayers<T>{ground, ground, T{}}).r_top;
}

/// Reflectance of an infinitely thick layer from K/S (§4.1):
///   R∞ = 1 + K/S − sqrt((K/S)² + 2 K/S),
/// evaluated as the equal 1 / (1 + K/S + sqrt(...)), without cancellation for large K/S.
inline double km_r_infinity(double k_over_s)
{
    const double q = k_over_s > 0.0 ? k_over_s : 0.0;
    if (std::isinf(q))
        return 0.0;
    return 1.0 / (1.0 + q + std::sqrt(q * q + 2.0 * q));
}

/// R∞ inverted: K/S = (1 − R∞)² / (2 R∞); +infinity for R∞ <= 0, 0 for R∞ >= 1.
inline double km_k_over_s(double r_infinity)
{
    if (!(r_infinity > 0.0))
        return std::numeric_limits<double>::infinity();
    const double r = std::min(r_infinity, 1.0);
    return (1.0 - r) * (1.0 - r) / (2.0 * r);
}

/// A homogeneous layer of thickness d, in double (§4.1):
///   R = sinh(bSd) / (a sinh(bSd) + b cosh(bSd)),  T = b / (a sinh(bSd) + b cosh(bSd)),
///   a = (S + K) / S,  b = sqrt(a² − 1).
/// Multiplied through by S (Sa = S + K, Sb = β = sqrt(K (K + 2S))) and by 2 e^−x / β with
/// x = βd, it has no overflow or 0/0 and holds at S = 0 and K = 0:
///   R = S g / ((S + K) g + 1 + e^−2x),  T = 2 e^−x / ((S + K) g + 1 + e^−2x),
///   g = (1 − e^−2x) / β  (→ 2d as β → 0).
/// Exact limits: S = 0 (R = 0, T = e^−Kd), K = 0 (R = Sd / (1 + Sd), T = 1 / (1 + Sd)),
/// d = 0 (R = 0, T = 1), d = ∞ (R = R∞, T = 0).
inline KmLayers<double> km_layer(double K, double S, double d)
{
    K = K > 0.0 ? K : 0.0;
    S = S > 0.0 ? S : 0.0;
    d = d > 0.0 ? d : 0.0;
    if (std::isinf(d)) {
        const double r = S > 0.0 ? km_r_infinity(K / S) : 0.0;
        return {r, r, 0.0};
    }
    const double beta = std::sqrt(K * (K + 2.0 * S));
    const double x = beta * d;
    const double g = beta > 0.0 ? -std::expm1(-2.0 * x) / beta : 2.0 * d;
    const double denom = (S + K) * g + 1.0 + std::exp(-2.0 * x);
    const double r = S * g / denom;
    return {r, r, 2.0 * std::exp(-x) / denom};
}

/// km_layer for four wavelengths in float lanes (the layered_km shader): the same closed
/// form with one transcendental per lane. Above x = 0.25, e = e^−x and 1 − e² keeps its
/// accuracy (≥ 0.39); below, e = 1 + expm1(−x) and 1 − e² = −expm1(−x) (1 + e); below
/// x = 1e−4 the series e = 1 − x, g = 2d (1 − x). Relative error a few float ulps.
inline KmLayers<simd::V4> km_layer4(simd::V4 K, simd::V4 S, float d)
{
    using namespace simd;
    const V4 zero = splat(0.0f);
    K = K > zero ? K : zero;
    S = S > zero ? S : zero;
    if (!(d > 0.0f))
        return {zero, zero, splat(1.0f)};
    const V4 beta = sqrt4(K * (K + 2.0f * S));
    const V4 x = beta * d;
    V4 t = zero;
    for (int l = 0; l < kLanes; ++l)
        t[l] = x[l] > 0.25f ? std::exp(-x[l]) : (x[l] > 1e-4f ? std::expm1(-x[l]) : 0.0f);
    const I4 big = x > splat(0.25f), mid = x > splat(1e-4f);
    const V4 e = big ? t : (mid ? 1.0f + t : 1.0f - x);
    const V4 g = big ? (1.0f - e * e) / beta : (mid ? -t * (1.0f + e) / beta : 2.0f * d * (1.0f - x));
    const V4 denom = (S + K) * g + 1.0f + e * e;
    const V4 r = S * g / denom;
    return {r, r, 2.0f * e / denom};
}

}  // namespace patina::shading
