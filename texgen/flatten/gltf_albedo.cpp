#include "texgen/flatten/gltf_albedo.h"

#include <patina/shading/fresnel.h>
#include <patina/shading/frame.h>
#include <patina/shading/microfacet.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen {

using shading::kGaussMu;
using shading::kGaussNodes;
using shading::Vec2;
using shading::Vec3;

namespace {

    constexpr double kPi = 3.14159265358979323846;

    /// Blender's Fresnel shape for an index-1.5 dielectric (Cycles' interpolate_fresnel_color):
    /// (F(v·h) − F0) / (1 − F0), F the exact dielectric Fresnel of η 1.5, F0 = 0.04.
    double blender_fresnel_shape(double c)
    {
        const double f0 = 0.04;
        return (shading::fresnel_dielectric(static_cast<float>(c), 1.5f) - f0) / (1.0 - f0);
    }

    double pow5(double x) { return x * x * x * x * x; }

    Vec3 outgoing(int g)
    {
        const float mu = kGaussMu[g];
        return {std::sqrt(std::max(0.0f, 1.0f - mu * mu)), 0.0f, mu};
    }

}  // namespace

GltfTarget gltf_target(const std::string& name)
{
    if (name == "khronos")
        return GltfTarget::khronos;
    if (name == "blender")
        return GltfTarget::blender;
    throw std::runtime_error(
        fmt::format("--target '{}': expected khronos (three.js, Babylon.js, the Khronos "
                    "sample viewer) or blender (Blender 3.4's Principled BSDF)", name));
}

const char* gltf_target_name(GltfTarget target)
{
    return target == GltfTarget::khronos ? "khronos" : "blender";
}

GltfAlbedo::GltfAlbedo()
{
    constexpr int kStrata = 64;
    std::array<std::array<float, kGaussNodes>, kRoughnessNodes> eb{};
    for (int k = 0; k < kRoughnessNodes; ++k) {
        const float r = kMinRoughness + (1.0f - kMinRoughness) * k / (kRoughnessNodes - 1);
        const shading::TrowbridgeReitz ggx(r * r, r * r);
        for (int g = 0; g < kGaussNodes; ++g) {
            const Vec3 wo = outgoing(g);
            // The specular terms: the mean of G2 / G1 (times a Fresnel shape) over the
            // visible normals of wo (Heitz 2018), stratified.
            double e1 = 0.0, e5 = 0.0, e_blender = 0.0;
            for (int i = 0; i < kStrata; ++i)
                for (int j = 0; j < kStrata; ++j) {
                    const Vec3 wm = ggx.sample_wm(wo, Vec2((i + 0.5f) / kStrata, (j + 0.5f) / kStrata));
                    const Vec3 wi = shading::reflect(wo, wm);
                    if (wi.z <= 0.0f)
                        continue;
                    const double w = ggx.g(wo, wi) / ggx.g1(wo);
                    const double c = std::clamp(static_cast<double>(shading::dot(wo, wm)), 0.0, 1.0);
                    e1 += w;
                    e5 += w * pow5(1.0 - c);
                    e_blender += w * blender_fresnel_shape(c);
                }
            const double n = static_cast<double>(kStrata) * kStrata;
            e1_[k][g] = static_cast<float>(e1 / n);
            e5_[k][g] = static_cast<float>(e5 / n);
            eb[k][g] = static_cast<float>(e_blender / n);
        }
    }
    // The diffuse terms by the midpoint rule over the hemisphere of wi.
    constexpr int kTheta = 64, kPhi = 128;
    for (int g = 0; g < kGaussNodes; ++g) {
        const Vec3 wo = outgoing(g);
        const double fv = pow5(1.0 - wo.z);
        std::array<double, kRoughnessNodes> kb{};
        double kd = 0.0;
        for (int i = 0; i < kTheta; ++i) {
            const double theta = (i + 0.5) / kTheta * kPi / 2.0;
            const double mu = std::cos(theta), sin_theta = std::sin(theta);
            const double dw = (kPi / 2.0 / kTheta) * (2.0 * kPi / kPhi) * sin_theta;
            const double fl = pow5(1.0 - mu);
            for (int j = 0; j < kPhi; ++j) {
                const double phi = (j + 0.5) / kPhi * 2.0 * kPi;
                const Vec3 wi(static_cast<float>(sin_theta * std::cos(phi)),
                              static_cast<float>(sin_theta * std::sin(phi)), static_cast<float>(mu));
                const Vec3 h = shading::normalize(wo + wi);
                const double vh = std::clamp(static_cast<double>(shading::dot(wo, h)), 0.0, 1.0);
                // Khronos: (1 − Fs(0.04, v·h)) / π.
                kd += (1.0 - (0.04 + 0.96 * pow5(1.0 - vh))) / kPi * mu * dw;
                // Cycles' principled diffuse (Burley 2015): Lambert's (1 − FL/2)(1 − FV/2)
                // and the retro-reflection Rr (FL + FV + FL FV (Rr − 1)), Rr = 2 r cos²θd.
                for (int k = 0; k < kRoughnessNodes; ++k) {
                    const double r = kMinRoughness + (1.0 - kMinRoughness) * k / (kRoughnessNodes - 1);
                    const double rr = 2.0 * r * vh * vh;
                    const double f = ((1.0 - 0.5 * fl) * (1.0 - 0.5 * fv) +
                                      rr * (fl + fv + fl * fv * (rr - 1.0))) / kPi;
                    kb[static_cast<size_t>(k)] += f * mu * dw;
                }
            }
        }
        kd_[g] = static_cast<float>(kd);
        for (int k = 0; k < kRoughnessNodes; ++k)
            kb_[k][g] = static_cast<float>(kb[static_cast<size_t>(k)]);
    }
    eb_ = eb;
}

const GltfAlbedo& gltf_albedo_model()
{
    static const GltfAlbedo model;
    return model;
}

void GltfAlbedo::locate(float r, int* k, float* s)
{
    const float x = std::clamp((r - kMinRoughness) / (1.0f - kMinRoughness), 0.0f, 1.0f) *
                    (kRoughnessNodes - 1);
    *k = std::min(static_cast<int>(x), kRoughnessNodes - 2);
    *s = x - static_cast<float>(*k);
}

float GltfAlbedo::at(const Table& t, float r, int g)
{
    int k;
    float s;
    locate(r, &k, &s);
    return t[k][g] + s * (t[k + 1][g] - t[k][g]);
}

GltfAlbedo::Terms GltfAlbedo::terms(GltfTarget target, float r, float m, float w, float rc) const
{
    Terms t;
    for (int g = 0; g < kGaussNodes; ++g) {
        const float e1 = at(e1_, r, g), e1c = at(e1_, rc, g);
        if (target == GltfTarget::khronos) {
            const float e5 = at(e5_, r, g);
            const float x = 1.0f - kGaussMu[g];
            const float fc = 0.04f + 0.96f * x * x * x * x * x;
            const float keep = 1.0f - w * fc;
            t.Pd[g] = keep * (1.0f - m) * kd_[g];
            t.Ps[g] = keep * m * (e1 - e5);
            t.Q[g] = keep * ((1.0f - m) * (0.04f * e1 + 0.96f * e5) + m * e5) + w * fc * e1c;
        } else {
            const float eb = at(eb_, r, g), ebc = at(eb_, rc, g);
            t.Pd[g] = (1.0f - m) * at(kb_, r, g);
            t.Ps[g] = m * (e1 - eb);
            t.Q[g] = (1.0f - m) * (0.04f * e1 + 0.96f * eb) + m * eb +
                     0.25f * w * (0.04f * e1c + 0.96f * ebc);
        }
    }
    return t;
}

GltfAlbedo::AffineTerms GltfAlbedo::affine_terms(GltfTarget target, float r, float m,
                                                 float rc) const
{
    // terms() at w = 0 and the change per unit of w, each table row found once.
    int k, kc;
    float s, sc;
    locate(r, &k, &s);
    locate(rc, &kc, &sc);
    auto row = [](const Table& t, int k, float s, int g) {
        return t[k][g] + s * (t[k + 1][g] - t[k][g]);
    };
    AffineTerms a;
    for (int g = 0; g < kGaussNodes; ++g) {
        const float e1 = row(e1_, k, s, g), e1c = row(e1_, kc, sc, g);
        if (target == GltfTarget::khronos) {
            const float e5 = row(e5_, k, s, g);
            const float x = 1.0f - kGaussMu[g];
            const float fc = 0.04f + 0.96f * x * x * x * x * x;
            const float pd = (1.0f - m) * kd_[g], ps = m * (e1 - e5);
            const float q = (1.0f - m) * (0.04f * e1 + 0.96f * e5) + m * e5;
            a.at0.Pd[g] = pd;
            a.at0.Ps[g] = ps;
            a.at0.Q[g] = q;
            a.per_w.Pd[g] = -fc * pd;
            a.per_w.Ps[g] = -fc * ps;
            a.per_w.Q[g] = fc * (e1c - q);
        } else {
            const float eb = row(eb_, k, s, g), ebc = row(eb_, kc, sc, g);
            a.at0.Pd[g] = (1.0f - m) * row(kb_, k, s, g);
            a.at0.Ps[g] = m * (e1 - eb);
            a.at0.Q[g] = (1.0f - m) * (0.04f * e1 + 0.96f * eb) + m * eb;
            a.per_w.Pd[g] = 0.0f;
            a.per_w.Ps[g] = 0.0f;
            a.per_w.Q[g] = 0.25f * (0.04f * e1c + 0.96f * ebc);
        }
    }
    return a;
}

}  // namespace patina::texgen
