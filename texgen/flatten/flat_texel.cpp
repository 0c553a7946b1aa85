#include "texgen/flatten/flat_texel.h"

#include "texgen/flatten/gltf_fit.h"

#include <patina/shading/layer_stack.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <stdexcept>

namespace patina::texgen {

namespace {

    using shading::simd::V4;

    /// The walk of one texel from the top down, every band group at once
    /// (patina/shading/layer_stack.h, §4.2-4.3), as the layered_km shader walks its
    /// wavelengths. `on_interface(k, attenuation)` is called for each layer k (0-based,
    /// bottom to top) with an interface of its own: present, and not continuing the layer
    /// above it (the same material has no boundary with itself).
    template <class OnInterface>
    std::array<shading::LayersAbove<V4>, kBandGroups>
    walk(const BandStack& stack, std::span<const float> thickness_um, OnInterface on_interface)
    {
        if (stack.layers.size() != thickness_um.size())
            throw std::invalid_argument("flatten_texel: one thickness per layer");
        std::array<shading::LayersAbove<V4>, kBandGroups> above;
        const BandMaterial* material_above = nullptr;
        for (size_t k = stack.layers.size(); k-- > 0;) {
            const float d = thickness_um[k];
            if (!(d > 0.0f))
                continue;
            const BandMaterial& m = *stack.layers[k];
            if (shading::has_interface(&m, material_above))
                on_interface(k, above, shading::interface_fade(d));
            material_above = &m;
            // KM R and T of layer k (§4.1), added under the layers above.
            for (int g = 0; g < kBandGroups; ++g)
                above[g].add(m.absorption[g], m.scattering[g], d);
        }
        return above;
    }

    Bands diffuse_over_base(const std::array<shading::LayersAbove<V4>, kBandGroups>& above,
                            const BandMaterial& base, bool metal)
    {
        Bands out;
        for (int g = 0; g < kBandGroups; ++g)
            out[g] = shading::simd::clamp4(above[g].diffuse_over(base.base_reflectance[g], metal),
                                           0.0f, 1.0f);
        return out;
    }

}  // namespace

Bands stack_diffuse(const BandStack& stack, std::span<const float> thickness_um,
                    bool keep_metal_reflection)
{
    const auto above = walk(stack, thickness_um, [](size_t, const auto&, float) {});
    return diffuse_over_base(above, *stack.base, stack.base->metal && !keep_metal_reflection);
}

FlatTexel flatten_texel(const BandStack& stack, std::span<const float> thickness_um,
                        const BandsToRgb& to_rgb, const GltfFitting& fitting)
{
    FlatTexel out;
    flatten_texel(stack, thickness_um, to_rgb, fitting, out);
    return out;
}

void flatten_texel(const BandStack& stack, std::span<const float> thickness_um,
                   const BandsToRgb& to_rgb, const GltfFitting& fitting, FlatTexel& out)
{
    const size_t n = stack.layers.size();
    out.diffuse = Imath::V3f(0.0f);
    out.height_um = 0.0f;
    out.interfaces.assign(n + 1, InterfaceLobe{});
    for (size_t i = 0; i < n && i < thickness_um.size(); ++i) {
        out.height_um += thickness_um[i];
        out.interfaces[i + 1].roughness = stack.layers[i]->roughness;
    }
    // §4.3: each interface's specular reflectance "multiplied twice by diffuse
    // transmittance of the intervening layers calculated using the KM equations".
    auto set_lobe = [&](InterfaceLobe& lobe, const BandMaterial& m, const auto& above, float fade) {
        Bands a, s;
        for (int g = 0; g < kBandGroups; ++g) {
            a[g] = above[g].attenuation(fade);
            s[g] = m.specular[g] * a[g];
        }
        lobe.specular = to_rgb(s);
        lobe.material = &m;
        if (fitting.model)
            lobe.attenuation = to_rgb(a);
    };
    const auto above = walk(stack, thickness_um, [&](size_t k, const auto& layers_above, float fade) {
        set_lobe(out.interfaces[k + 1], *stack.layers[k], layers_above, fade);
    });
    // The base's own interface, under every layer.
    const BandMaterial& base = *stack.base;
    set_lobe(out.interfaces[0], base, above, 1.0f);
    out.interfaces[0].roughness = base.roughness;
    // Diffuse: the whole stack over the opaque base (§4.2); a metal's once-through
    // reflection is the base lobe.
    const Imath::V3f diffuse = to_rgb(diffuse_over_base(above, base, base.metal));
    for (int c = 0; c < 3; ++c)
        out.diffuse[c] = std::max(0.0f, diffuse[c]);

    int top = 0;
    for (size_t i = n; i > 0; --i)
        if (thickness_um[i - 1] > 0.0f) {
            top = static_cast<int>(i);
            break;
        }
    out.two_lobe = reduce_to_two_lobes(base.metal, out.diffuse, out.interfaces, top);
    if (fitting.model)
        out.two_lobe = fit_gltf(*fitting.model, fitting.target, texel_albedo(out), out.two_lobe);
}

AlbedoParts texel_albedo(const FlatTexel& texel)
{
    using shading::kGaussNodes;
    using shading::simd::splat;
    using shading::simd::V4;
    // layered_km's albedo (LayeredModel::albedo, setup_thickness), per channel (the lanes):
    // the lobes from the top interface down, each seen through the coupling of the
    // dielectric lobes above it, 1 − a E; under them the diffuse lobe R_d / (1 − R_d ḡ) of
    // albedo (1 − g(μ)) (1 − ḡ), with g = 1 − Π (1 − a E) and ḡ its cosine-weighted mean.
    AlbedoParts parts;
    std::array<V4, kGaussNodes> pass;
    pass.fill(splat(1.0f));
    for (size_t j = texel.interfaces.size(); j-- > 0;) {
        const InterfaceLobe& lobe = texel.interfaces[j];
        if (!lobe.material)
            continue;
        const V4 a{lobe.attenuation.x, lobe.attenuation.y, lobe.attenuation.z, 0.0f};
        const bool coupled = !lobe.material->metal;  // a metal base's reflection is not taken from below
        for (int g = 0; g < kGaussNodes; ++g) {
            const V4 ae = a * lobe.material->lobe_albedo[static_cast<size_t>(g)];
            parts.glossy[static_cast<size_t>(g)] += pass[static_cast<size_t>(g)] * ae;
            if (coupled)
                pass[static_cast<size_t>(g)] *= 1.0f - ae;
        }
    }
    V4 pass_mean = splat(0.0f);
    for (int g = 0; g < kGaussNodes; ++g)
        pass_mean += shading::kGaussMeanWeight[g] * pass[static_cast<size_t>(g)];
    const V4 g_mean = shading::simd::clamp4(1.0f - pass_mean, 0.0f, 1.0f);
    const V4 rd{texel.diffuse.x, texel.diffuse.y, texel.diffuse.z, 0.0f};
    const V4 denom = 1.0f - rd * g_mean;
    const V4 diffuse_albedo = denom > splat(1e-6f) ? rd / denom * (1.0f - g_mean) : splat(0.0f);
    for (int g = 0; g < kGaussNodes; ++g)
        parts.diffuse[static_cast<size_t>(g)] = pass[static_cast<size_t>(g)] * diffuse_albedo;
    return parts;
}

TwoLobe reduce_to_two_lobes(bool metal_base, const Imath::V3f& diffuse,
                            std::span<const InterfaceLobe> interfaces, int top_interface)
{
    TwoLobe two;
    const InterfaceLobe& top = interfaces[static_cast<size_t>(top_interface)];
    // The coat: the exposed layer's interface, absent over bare base.
    two.coat_roughness = top.roughness;
    two.coat_weight =
        top_interface > 0 ? std::clamp(luminance(top.specular) / kClearcoatF0, 0.0f, 1.0f) : 0.0f;

    // The base's specular lobe: every interface under the coat (the top one itself when
    // the base is bare), F0 summed, GGX alphas averaged with F0 luminance as weight.
    const int last = top_interface > 0 ? top_interface - 1 : 0;
    Imath::V3f f0(0.0f);
    double weight = 0.0, alpha = 0.0;
    for (int k = 0; k <= last; ++k) {
        const InterfaceLobe& lobe = interfaces[static_cast<size_t>(k)];
        f0 += lobe.specular;
        const double w = luminance(lobe.specular);
        weight += w;
        alpha += w * lobe.roughness * lobe.roughness;
    }
    two.roughness = weight > 0.0 ? static_cast<float>(std::sqrt(alpha / weight))
                                 : interfaces[static_cast<size_t>(last)].roughness;

    // glTF's metallic blend carries the diffuse albedo and the metal's F0 in one colour.
    // Over a dielectric base the lower lobes are left to glTF's fixed 0.04 F0.
    const Imath::V3f metal = metal_base ? f0 : Imath::V3f(0.0f);
    const float lum_metal = luminance(metal), lum_diffuse = luminance(diffuse);
    two.base_color = diffuse + metal;
    two.metallic = lum_metal + lum_diffuse > 0.0f ? lum_metal / (lum_metal + lum_diffuse) : 0.0f;
    for (int c = 0; c < 3; ++c)
        two.base_color[c] = std::clamp(two.base_color[c], 0.0f, 1.0f);
    return two;
}

}  // namespace patina::texgen
