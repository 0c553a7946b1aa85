/*
 * dielectric — Rough or smooth glass-like interface (bsdf)
 * ========================================================
 *
 *  Parameter     Type    Default  Description
 *  ------------  ------  -------  ------------------------------------------------------
 *  eta           float   1.5      Interior index of refraction over exterior, in [1, 4].
 *  roughness     float   0        Perceptual roughness r in [0, 1]; α = r².
 *
 * The boundary between two dielectrics (air and glass, water, a varnish): light is
 * reflected or refracted, in the proportion given by the exact Fresnel equations. The
 * interior is the side below the shading normal (z < 0), the exterior the side above;
 * `eta` is η_interior / η_exterior. Both sides are handled: wo may lie inside (z < 0),
 * where eta is seen inverted and total internal reflection happens.
 *
 * Rough (roughness >= 0.001): the microfacet model of Walter et al. 2007 with the GGX
 * distribution, Smith's height-correlated masking-shadowing, and the generalised half
 * vector wm ∝ η_i wi + η_o wo (η of the side each direction lies on):
 *
 *   reflection    f = D G2 F / (4 |cos θo cos θi|)
 *   transmission  f = D G2 (1 − F) |wi·wm| |wo·wm| / (|cos θo cos θi| (wi·wm + wo·wm/η')²),
 *                 η' = η_wi / η_wo, divided by η'² in PATINA_TRANSPORT_RADIANCE mode
 *
 * (radiance is compressed by η² when it enters a denser medium; importance is not). A
 * visible normal of wo is sampled (Heitz 2018), then reflection with probability F and
 * refraction with probability 1 − F; pdf() returns exactly that density.
 *
 * Smooth (roughness < 0.001), and always when eta = 1: two delta lobes,
 * PATINA_LOBE_SPECULAR, chosen with probabilities F and 1 − F; eval and pdf return 0
 * (abi.h §3). At eta = 1 the boundary is invisible: light passes straight through.
 *
 * A transmitted sample sets PatinaBsdfSample::eta = η' (the index on wi's side over the
 * index on wo's side: 1.5 entering glass from air, 1/1.5 leaving it); a reflected one
 * sets 1. The index does not depend on wavelength (no dispersion).
 *
 * References: Walter, Marschner, Li, Torrance 2007, "Microfacet Models for Refraction
 * through Rough Surfaces", EGSR; Heitz 2018 (JCGT 7(4)); Veach 1997, thesis §5.2
 * (non-symmetric scattering due to refraction); pbrt-v4 §9.5, §9.7 (DielectricBxDF).
 */
#include "basic.h"

#include <patina/shading/fresnel.h>
#include <patina/shading/frame.h>
#include <patina/shading/microfacet.h>
#include <patina/shading/spectral.h>

namespace patina::basic {
namespace {

    using namespace patina::shading;

    constexpr const char* kName = "dielectric";

    // clang-format off
    const PatinaParamDecl kParams[] = {
        {"eta", PATINA_PARAM_FLOAT, {1.5f, 0.0f, 0.0f}, nullptr, nullptr, 1.0f, 4.0f, "",
         "Index of refraction of the interior (below the normal) over the exterior; 1 is an "
         "invisible boundary."},
        {"roughness", PATINA_PARAM_FLOAT, {0.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1.0f, "",
         "Perceptual roughness r; the GGX width is alpha = r^2, and r < 0.001 is a smooth "
         "interface."},
    };
    // clang-format on

    struct Dielectric {
        float eta = 1.5f;
        TrowbridgeReitz distribution;
        bool smooth = false;
    };

    /// f and pdf of the rough lobes at (wo, wi); false, leaving the outputs untouched, where
    /// both are zero.
    bool rough_lobes(const Dielectric& d, Vec3 wo, Vec3 wi, PatinaTransportMode mode, float* f,
                     float* pdf)
    {
        const float cos_o = cos_theta(wo), cos_i = cos_theta(wi);
        if (cos_o == 0.0f || cos_i == 0.0f)
            return false;
        const bool reflect = cos_o * cos_i > 0.0f;
        // Relative index η' = η_wi / η_wo across the boundary (1 for reflection)
        float etap = 1.0f;
        if (!reflect)
            etap = cos_o > 0.0f ? d.eta : 1.0f / d.eta;
        // Generalised half vector wm ∝ η' wi + wo: Walter et al. 2007 Eqs. 13 and 16
        Vec3 wm = wi * etap + wo;
        if (length_squared(wm) == 0.0f)
            return false;
        wm = face_forward(normalize(wm), Vec3(0.0f, 0.0f, 1.0f));
        // Discard back-facing microfacets (both directions must see wm from their own side)
        if (dot(wm, wi) * cos_i <= 0.0f || dot(wm, wo) * cos_o <= 0.0f)
            return false;

        const float F = fresnel_dielectric(dot(wo, wm), d.eta);
        const float D = d.distribution.d(wm);
        const float G = d.distribution.g(wo, wi);
        float value, density;
        if (reflect) {
            // Reflection: Walter et al. 2007 Eq. 20; pdf with the reflection Jacobian, Eq. 14,
            // times the probability F of choosing it
            value = D * G * F / std::abs(4.0f * cos_i * cos_o);
            density = d.distribution.pdf(wo, wm) / (4.0f * abs_dot(wo, wm)) * F;
        } else {
            // Transmission: Walter et al. 2007 Eq. 21 written with η' (pbrt-v4 §9.7); pdf with
            // the refraction Jacobian, Eq. 17, times the probability 1 − F of choosing it
            const float denom = sqr(dot(wi, wm) + dot(wo, wm) / etap);
            const float T = 1.0f - F;
            value = T * D * G * std::abs(dot(wi, wm) * dot(wo, wm) / (cos_i * cos_o * denom));
            // Radiance is scaled by 1/η'² across the boundary; importance is not: Veach 1997 §5.2
            if (mode == PATINA_TRANSPORT_RADIANCE)
                value /= sqr(etap);
            density = d.distribution.pdf(wo, wm) * abs_dot(wi, wm) / denom * T;
        }
        if (!(value > 0.0f) || !is_finite(value) || !(density > 0.0f) || !is_finite(density))
            return false;
        if (f)
            *f = value;
        if (pdf)
            *pdf = density;
        return true;
    }

    void* create(const PatinaHost* host, const PatinaParamValue* values)
    {
        const plugin::Parameters p(host, kName, kParams, values);
        const PatinaParamValue& eta = p.value("eta", PATINA_PARAM_FLOAT);
        const PatinaParamValue& roughness = p.value("roughness", PATINA_PARAM_FLOAT);
        if (!p.ok())
            return nullptr;
        if (eta.type != PATINA_PARAM_FLOAT || !(eta.f >= 1.0f && eta.f <= 4.0f)) {
            report_error(host, kName,
                         "eta %g must lie in [1, 4] (interior index over exterior; "
                         "flip the normal for a less dense interior)",
                         eta.f);
            return nullptr;
        }
        if (roughness.type != PATINA_PARAM_FLOAT || !(roughness.f >= 0.0f && roughness.f <= 1.0f)) {
            report_error(host, kName, "roughness %g must lie in [0, 1]", roughness.f);
            return nullptr;
        }
        auto* d = make_instance<Dielectric>(host, kName);
        if (!d)
            return nullptr;
        d->eta = eta.f;
        // An index-matched boundary has no microfacet geometry to speak of: it is invisible
        d->smooth = roughness.f < kSmoothRoughness || eta.f == 1.0f;
        const float alpha = TrowbridgeReitz::roughness_to_alpha(roughness.f);
        d->distribution = TrowbridgeReitz(alpha, alpha);
        return d;
    }

    void destroy(void* instance)
    {
        delete static_cast<Dielectric*>(instance);
    }

    void eval(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo, PatinaVec3 wi,
              const PatinaWavelengths* wl, float* f)
    {
        const auto& d = *static_cast<const Dielectric*>(instance);
        float value = 0.0f;
        if (!d.smooth)
            rough_lobes(d, wo, wi, transport_mode(ctx), &value, nullptr);
        fill(value, *wl, f);
    }

    float pdf(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo, PatinaVec3 wi,
              const PatinaWavelengths*)
    {
        const auto& d = *static_cast<const Dielectric*>(instance);
        float density = 0.0f;
        if (!d.smooth)
            rough_lobes(d, wo, wi, transport_mode(ctx), nullptr, &density);
        return density;
    }

    int sample_smooth(const Dielectric& d, PatinaTransportMode mode, Vec3 wo, float u_lobe,
                      const PatinaWavelengths& wl, PatinaBsdfSample* out)
    {
        // Fresnel reflectance of the flat interface seen from wo's side
        const float R = fresnel_dielectric(cos_theta(wo), d.eta);
        const float T = 1.0f - R;
        if (u_lobe < R) {
            // Specular reflection, f = R / |cos θi| against probability R: pbrt-v4 §9.5
            const Vec3 wi(-wo.x, -wo.y, wo.z);
            fill(R / abs_cos_theta(wi), wl, out->f);
            out->wi = wi;
            out->pdf = R;
            out->lobe = PATINA_LOBE_REFLECTION | PATINA_LOBE_SPECULAR;
            out->eta = 1.0f;
            return 1;
        }
        // Specular transmission, f = T / |cos θi| (/ η'² for radiance) against probability T
        Vec3 wi;
        float etap = 1.0f;
        if (!(T > 0.0f) || !refract(wo, Vec3(0.0f, 0.0f, 1.0f), d.eta, &etap, &wi))
            return 0;
        if (wi.z == 0.0f)
            return 0;
        float ft = T / abs_cos_theta(wi);
        if (mode == PATINA_TRANSPORT_RADIANCE)
            ft /= sqr(etap);
        fill(ft, wl, out->f);
        out->wi = wi;
        out->pdf = T;
        out->lobe = PATINA_LOBE_TRANSMISSION | PATINA_LOBE_SPECULAR;
        out->eta = etap;
        return 1;
    }

    int sample(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo_, float u_lobe,
               PatinaVec2 u, const PatinaWavelengths* wl, PatinaBsdfSample* out)
    {
        const auto& d = *static_cast<const Dielectric*>(instance);
        const PatinaTransportMode mode = transport_mode(ctx);
        const Vec3 wo = wo_;
        if (wo.z == 0.0f)
            return 0;
        if (d.smooth)
            return sample_smooth(d, mode, wo, u_lobe, *wl, out);

        // Sample a visible microfacet normal, then reflection or refraction by its Fresnel term
        const Vec3 wm = d.distribution.sample_wm(wo, u);
        const float R = fresnel_dielectric(dot(wo, wm), d.eta);
        Vec3 wi;
        int lobe;
        float etap = 1.0f;
        if (u_lobe < R) {
            wi = normalize(reflect(wo, wm));
            if (!same_hemisphere(wo, wi))
                return 0;
            lobe = PATINA_LOBE_REFLECTION | PATINA_LOBE_GLOSSY;
        } else {
            if (!refract(wo, wm, d.eta, &etap, &wi))
                return 0;
            wi = normalize(wi);
            if (wi.z == 0.0f || same_hemisphere(wo, wi))
                return 0;
            lobe = PATINA_LOBE_TRANSMISSION | PATINA_LOBE_GLOSSY;
        }
        // f and pdf exactly as eval and pdf compute them at the sampled direction
        float f = 0.0f, p = 0.0f;
        if (!rough_lobes(d, wo, wi, mode, &f, &p))
            return 0;
        fill(f, *wl, out->f);
        out->wi = wi;
        out->pdf = p;
        out->lobe = lobe;
        out->eta = etap;
        return 1;
    }

    void albedo(const void*, const PatinaShadingContext*, PatinaVec3, const PatinaWavelengths* wl,
                float* a)
    {
        // Reflection plus transmission of the interface: all of the light goes on somewhere
        fill(1.0f, *wl, a);
    }

    const PatinaBsdfFuncs kFuncs = {eval, pdf, sample, albedo};

} // namespace

PatinaShaderDesc dielectric_shader()
{
    return describe(kName,
                 "Rough or smooth boundary between two dielectrics (glass, water, varnish): "
                 "Fresnel-weighted reflection and refraction, from either side.",
                 kParams, create, destroy, kFuncs);
}

} // namespace patina::basic
