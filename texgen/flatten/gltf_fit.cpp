#include "texgen/flatten/gltf_fit.h"

#include "texgen/flatten/flat_texel.h"

#include <algorithm>

namespace patina::texgen {

using shading::kGaussMeanWeight;
using shading::kGaussNodes;

TwoLobe fit_gltf(const GltfAlbedo& model, GltfTarget target, const AlbedoParts& albedo,
                 const TwoLobe& start)
{
    // Every term is affine in the coat weight w: X(w) = X0 + w dX (gltf_albedo.h). The
    // residuals at cosine g, per channel (the lanes), both weighted by W_g = 2 μ_g w_g:
    //   diffuse  c Pd − D              whole  c (Pd + Ps) + Q − (D + S)
    using shading::simd::splat;
    using shading::simd::V4;
    const GltfAlbedo::AffineTerms t =
        model.affine_terms(target, start.roughness, start.metallic, start.coat_roughness);
    const auto& W = kGaussMeanWeight;
    std::array<V4, kGaussNodes> whole;
    for (int g = 0; g < kGaussNodes; ++g)
        whole[g] = albedo.diffuse[g] + albedo.glossy[g];

    // The colour for a coat weight: per channel c = Σ W (pd D + pt (A − q)) / Σ W (pd² + pt²).
    auto colour = [&](float w, V4 previous) {
        float den = 0.0f;
        V4 num = splat(0.0f);
        for (int g = 0; g < kGaussNodes; ++g) {
            const float pd = t.at0.Pd[g] + w * t.per_w.Pd[g];
            const float pt = pd + t.at0.Ps[g] + w * t.per_w.Ps[g];
            const float q = t.at0.Q[g] + w * t.per_w.Q[g];
            num += W[g] * (pd * albedo.diffuse[g] + pt * (whole[g] - q));
            den += W[g] * (pd * pd + pt * pt);
        }
        return den > 0.0f ? shading::simd::clamp4(num / den, 0.0f, 1.0f) : previous;
    };
    // The coat weight for a colour: each residual is r0 + w r1, so w = −Σ W r0 r1 / Σ W r1².
    auto coat = [&](V4 c, float previous) {
        V4 num = splat(0.0f), den = splat(0.0f);
        for (int g = 0; g < kGaussNodes; ++g) {
            const V4 d0 = c * t.at0.Pd[g] - albedo.diffuse[g];
            const V4 d1 = c * t.per_w.Pd[g];
            const V4 s0 = c * (t.at0.Pd[g] + t.at0.Ps[g]) + t.at0.Q[g] - whole[g];
            const V4 s1 = c * (t.per_w.Pd[g] + t.per_w.Ps[g]) + t.per_w.Q[g];
            num -= W[g] * (d0 * d1 + s0 * s1);
            den += W[g] * (d1 * d1 + s1 * s1);
        }
        const float n = num[0] + num[1] + num[2], d = den[0] + den[1] + den[2];
        return d > 0.0f ? std::clamp(n / d, 0.0f, 1.0f) : previous;
    };
    const Imath::V3f b = start.base_color;
    V4 c = colour(start.coat_weight, V4{b.x, b.y, b.z, 0.0f});
    float w = start.coat_weight;
    for (int round = 0; round < 2; ++round) {
        w = coat(c, w);
        c = colour(w, c);
    }
    TwoLobe out = start;
    out.base_color = Imath::V3f(c[0], c[1], c[2]);
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
