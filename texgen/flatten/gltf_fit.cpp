#include "texgen/flatten/gltf_fit.h"

#include "texgen/flatten/flat_texel.h"

#include <algorithm>

namespace patina::texgen {

using shading::kGaussMeanWeight;
using shading::kGaussNodes;

TwoLobe fit_gltf(const GltfAlbedo& model, GltfTarget target, const AlbedoParts& albedo,
                 const TwoLobe& start)
{
    TwoLobe out = start;
    // The terms are affine in the coat weight: at w = 0 and w = 1, then interpolated.
    const GltfAlbedo::Terms t0 =
        model.terms(target, out.roughness, out.metallic, 0.0f, out.coat_roughness);
    const GltfAlbedo::Terms t1 =
        model.terms(target, out.roughness, out.metallic, 1.0f, out.coat_roughness);
    auto lerp = [](float a, float b, float w) { return a + w * (b - a); };
    float w = start.coat_weight;
    Imath::V3f c = start.base_color;
    for (int round = 0; round < 2; ++round) {
        // The colour given w: min Σ W [(c Pd − D)² + (c Ps + Q − S)²] per channel.
        for (int k = 0; k < 3; ++k) {
            double num = 0.0, den = 0.0;
            for (int g = 0; g < kGaussNodes; ++g) {
                const double pd = lerp(t0.Pd[g], t1.Pd[g], w), ps = lerp(t0.Ps[g], t1.Ps[g], w);
                const double q = lerp(t0.Q[g], t1.Q[g], w);
                const double total = albedo.diffuse[g][k] + albedo.glossy[g][k];
                num += kGaussMeanWeight[g] * (pd * albedo.diffuse[g][k] + (pd + ps) * (total - q));
                den += kGaussMeanWeight[g] * (pd * pd + (pd + ps) * (pd + ps));
            }
            c[k] = den > 0.0 ? std::clamp(static_cast<float>(num / den), 0.0f, 1.0f) : c[k];
        }
        // w given the colour: every residual is r0 + w r1, so w = −Σ W r0 r1 / Σ W r1².
        double num = 0.0, den = 0.0;
        for (int k = 0; k < 3; ++k)
            for (int g = 0; g < kGaussNodes; ++g) {
                const double d0 = c[k] * t0.Pd[g] - albedo.diffuse[g][k];
                const double d1 = c[k] * (t1.Pd[g] - t0.Pd[g]);
                const double s0 = c[k] * (t0.Pd[g] + t0.Ps[g]) + t0.Q[g] -
                                  (albedo.diffuse[g][k] + albedo.glossy[g][k]);
                const double s1 = c[k] * (t1.Pd[g] - t0.Pd[g] + t1.Ps[g] - t0.Ps[g]) +
                                  (t1.Q[g] - t0.Q[g]);
                num -= kGaussMeanWeight[g] * (d0 * d1 + s0 * s1);
                den += kGaussMeanWeight[g] * (d1 * d1 + s1 * s1);
            }
        if (den > 0.0)
            w = std::clamp(static_cast<float>(num / den), 0.0f, 1.0f);
    }
    // The colour for the final w.
    for (int k = 0; k < 3; ++k) {
        double num = 0.0, den = 0.0;
        for (int g = 0; g < kGaussNodes; ++g) {
            const double pd = lerp(t0.Pd[g], t1.Pd[g], w), ps = lerp(t0.Ps[g], t1.Ps[g], w);
            const double q = lerp(t0.Q[g], t1.Q[g], w);
            const double total = albedo.diffuse[g][k] + albedo.glossy[g][k];
            num += kGaussMeanWeight[g] * (pd * albedo.diffuse[g][k] + (pd + ps) * (total - q));
            den += kGaussMeanWeight[g] * (pd * pd + (pd + ps) * (pd + ps));
        }
        c[k] = den > 0.0 ? std::clamp(static_cast<float>(num / den), 0.0f, 1.0f) : c[k];
    }
    out.base_color = c;
    out.coat_weight = w;
    return out;
}

std::array<Imath::V3f, kGaussNodes> gltf_albedo_of(const GltfAlbedo& model, GltfTarget target,
                                                   const TwoLobe& material)
{
    const GltfAlbedo::Terms t = model.terms(target, material.roughness, material.metallic,
                                            material.coat_weight, material.coat_roughness);
    std::array<Imath::V3f, kGaussNodes> a;
    for (int g = 0; g < kGaussNodes; ++g)
        for (int c = 0; c < 3; ++c)
            a[g][c] = material.base_color[c] * (t.Pd[g] + t.Ps[g]) + t.Q[g];
    return a;
}

}  // namespace patina::texgen
