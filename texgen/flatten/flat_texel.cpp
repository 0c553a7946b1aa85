#include "texgen/flatten/flat_texel.h"

#include <patina/shading/layer_stack.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen {

FlatTexel flatten_texel(const PatinaMaterial& base, std::span<const PatinaMaterial* const> layers,
                        std::span<const float> thickness_um)
{
    if (layers.size() != thickness_um.size())
        throw std::invalid_argument("flatten_texel: one thickness per layer");
    const size_t n = layers.size();
    FlatTexel out;
    out.interfaces.resize(n + 1);
    for (size_t i = 0; i < n; ++i)
        out.height_um += thickness_um[i];

    // One walk from the top down, the three channels in the lanes of one register
    // (patina/shading/layer_stack.h, §4.2-4.3), as the layered_km shader walks its
    // wavelengths: interface k (the top of layer k - 1) is seen through the layers above it;
    // a layer of the material above it continues that layer and has no interface.
    using shading::simd::V4;
    auto lanes = [](const Imath::V3f& v) { return V4{v.x, v.y, v.z, 0.0f}; };
    shading::LayersAbove<V4> above;
    const PatinaMaterial* material_above = nullptr;
    for (size_t k = n; k-- > 0;) {
        const float d = thickness_um[k];
        const PatinaMaterial& m = *layers[k];
        InterfaceLobe& lobe = out.interfaces[k + 1];
        lobe.roughness = m.roughness;
        if (d > 0.0f && shading::has_interface(&m, material_above)) {
            // §4.3: the specular colour "multiplied twice by diffuse transmittance of the
            // intervening layers calculated using the KM equations".
            const V4 attenuation = above.attenuation(shading::interface_fade(d));
            for (int c = 0; c < 3; ++c)
                lobe.specular[c] = m.specular[c] * attenuation[c];
        }
        if (d > 0.0f)
            material_above = &m;
        // KM R and T of layer k (§4.1), added under the layers above.
        above.add(lanes(m.absorption), lanes(m.scattering), d);
    }
    // The base's own interface, under every layer.
    const V4 base_attenuation = above.attenuation();
    for (int c = 0; c < 3; ++c)
        out.interfaces[0].specular[c] = base.specular[c] * base_attenuation[c];
    out.interfaces[0].roughness = base.roughness;
    // Diffuse: the whole stack over the opaque base (§4.2); a metal's once-through
    // reflection is the base lobe.
    const V4 diffuse = above.diffuse_over(lanes(base.color), base.is_metal);
    for (int c = 0; c < 3; ++c)
        out.diffuse[c] = std::max(0.0f, diffuse[c]);

    int top = 0;
    for (size_t i = n; i > 0; --i)
        if (thickness_um[i - 1] > 0.0f) {
            top = static_cast<int>(i);
            break;
        }
    out.two_lobe = reduce_to_two_lobes(base, out.diffuse, out.interfaces, top);
    return out;
}

TwoLobe reduce_to_two_lobes(const PatinaMaterial& base, const Imath::V3f& diffuse,
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
    const Imath::V3f metal = base.is_metal ? f0 : Imath::V3f(0.0f);
    const float lum_metal = luminance(metal), lum_diffuse = luminance(diffuse);
    two.base_color = diffuse + metal;
    two.metallic = lum_metal + lum_diffuse > 0.0f ? lum_metal / (lum_metal + lum_diffuse) : 0.0f;
    for (int c = 0; c < 3; ++c)
        two.base_color[c] = std::clamp(two.base_color[c], 0.0f, 1.0f);
    return two;
}

}  // namespace patina::texgen
