// The layered model of a patina stack at one shading point (Dorsey & Hanrahan 1996 §4),
// written once for all its users: the layered_km shader (four wavelengths in the lanes of a
// register), flatten and export (linear Rec.709 in the lanes of one register) and the
// stack's preview. In the style of pbrt-v4's util/scattering.h: the formulas here, the
// tables and lookups with the caller.
//
// A stack is walked from its top layer down. LayersAbove holds the Kubelka-Munk composite
// of the layers passed so far (§4.2): the lobe of the next interface down is that
// interface's specular colour times T_above² (§4.3, "multiplied twice by diffuse
// transmittance of the intervening layers"), and at the bottom the composite over the base
// gives the stack's diffuse reflectance. Which layers have an interface of their own:
//   - a layer of thickness 0 is absent (it has none, and composites as nothing);
//   - a layer of the same material as the nearest present layer above it continues that
//     layer: no interface between them (one material has no boundary with itself);
//   - an interface's lobe fades in over the first kInterfaceFadeUm of its layer
//     (interface_fade): a film far thinner than a wavelength is no separate reflecting
//     surface, and a filtered coverage edge shows no sudden gloss.
// Header-only and free of the renderer: plugins include it.
#pragma once

#include <patina/shading/fresnel.h>
#include <patina/shading/kubelka_munk.h>

#include <algorithm>
#include <cmath>

namespace patina::shading {

/// The thickness (µm) over which a layer's interface fades in.
inline constexpr float kInterfaceFadeUm = 0.05f;

/// The weight of the interface on top of a layer `thickness_um` thick: linear up to
/// kInterfaceFadeUm, 1 beyond, 0 for an absent layer.
inline float interface_fade(float thickness_um)
{
    return thickness_um > 0.0f ? std::min(1.0f, thickness_um / kInterfaceFadeUm) : 0.0f;
}

/// Whether a present layer of `material` has an interface of its own, under the nearest
/// present layer above it (`material_above`, nullptr at the top).
template <class Material>
inline bool has_interface(const Material* material, const Material* material_above)
{
    return material != material_above;
}

/// The reflectance an opaque base returns to diffuse light from the layers above it, for
/// a dielectric base of absorption K and scattering S (an infinitely thick layer: R∞ of
/// §4.1, 1 / (1 + q + sqrt(q² + 2q)) with q = K/S; 1 for K = S = 0, 0 for S = 0 < K).
inline float base_reflectance_dielectric(double K, double S)
{
    const double q = S > 0.0 ? K / S : (K > 0.0 ? 1e30 : 0.0);
    return static_cast<float>(1.0 / (1.0 + q + std::sqrt(q * q + 2.0 * q)));
}

/// The same for a smooth metal of complex index n + ik: its hemispherical reflectance
/// 2 ∫ F(μ) μ dμ (midpoint rule, 64 nodes), what light arriving diffusely from the layers
/// above sees.
inline float base_reflectance_metal(float n, float k)
{
    double sum = 0.0;
    for (int q = 0; q < 64; ++q) {
        const float mu = (q + 0.5f) / 64.0f;
        sum += fresnel_conductor(mu, n, k) * mu;
    }
    return static_cast<float>(2.0 * sum / 64.0);
}

/// A layer's Kubelka-Munk R and T (§4.1) for the lanes a walk works in.
inline KmLayers<simd::V4> km_layer_lanes(simd::V4 K, simd::V4 S, float d)
{
    return km_layer4(K, S, d);
}
inline KmLayers<double> km_layer_lanes(double K, double S, double d)
{
    return km_layer(K, S, d);
}

/// The layers above the current depth of a walk from the top down, as one composite.
template <class T>
class LayersAbove {
public:
    /// fade T_above² (§4.3): how much of an interface's reflection here, weighted by its
    /// interface_fade, comes back out of the top (T_above on the way in and out). Times the
    /// interface's specular colour, its lobe's weight.
    T attenuation(float fade = 1.0f) const { return fade * above_.t * above_.t; }

    /// A layer of absorption K and scattering S (per µm, per lane) and thickness d (µm)
    /// added under the layers above (§4.1, §4.2). d <= 0 leaves the composite as it is.
    void add(T K, T S, float d)
    {
        if (d > 0.0f)
            above_ = km_composite(above_, km_layer_lanes(K, S, d));
    }

    /// The stack's diffuse reflectance over an opaque base of reflectance `rho` (§4.2, the
    /// base a layer with T = 0). Over a metal, the light it reflects once through the layers,
    /// T_above² rho, is the base's own glossy lobe and is taken out (a bare metal has no
    /// diffuse part); `metal` false keeps it (the whole reflectance, as a preview shows it).
    T diffuse_over(T rho, bool metal) const
    {
        const T r = km_reflectance_over(above_, rho);
        return metal ? r - above_.t * above_.t * rho : r;
    }

    const KmLayers<T>& composite() const { return above_; }

private:
    KmLayers<T> above_;
};

}  // namespace patina::shading
