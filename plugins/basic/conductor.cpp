/*
 * conductor — Rough or smooth metal (bsdf)
 * =========================================
 *
 *  Parameter     Type      Default             Description
 *  ------------  --------  ------------------  ---------------------------------------------
 *  eta           spectrum  copper (J&C 1972)   Real part n of the complex index n + ik.
 *  k             spectrum  copper (J&C 1972)   Extinction coefficient k (imaginary part).
 *  roughness     float     0.2                 Perceptual roughness r in [0, 1]; α = r².
 *  anisotropy    float     0                   Stretch of the lobe along dPdu, in [0, 1].
 *
 * A metal interface in air (exterior index 1) described by microfacet theory: the
 * Trowbridge-Reitz (GGX) distribution of normals, Smith's height-correlated
 * masking-shadowing, and the exact Fresnel reflectance of the complex index n + ik at
 * every wavelength of the path (no Schlick approximation):
 *
 *     f(wo, wi) = D(wm) G2(wo, wi) F(|wo·wm|, n(λ), k(λ)) / (4 |cos θo| |cos θi|),
 *     wm = normalize(wo + wi).
 *
 * Roughness: the GGX width is α = roughness² (Burley 2012), so that equal steps of
 * roughness look like equal steps of blur. Below roughness 0.001 the surface is a perfect
 * mirror: a delta lobe (PATINA_LOBE_SPECULAR) sampled with probability 1, for which eval
 * and pdf return 0 (abi.h §3).
 *
 * Anisotropy a stretches the distribution along the shading frame's x axis (dPdu):
 * αx = α / sqrt(1 − 0.9 a), αy = α · sqrt(1 − 0.9 a) (Burley 2012, addendum on anisotropy);
 * a = 0 is isotropic.
 *
 * Sampling draws the visible normals of wo (Heitz 2018), so the weight f cos θi / pdf is
 * F G2 / G1(wo) <= 1. The surface reflects alike on both sides; nothing is transmitted.
 * The default spectra are copper at room temperature, Johnson & Christy 1972 (see below);
 * any tabulated n, k (nm) or constant numbers may be given.
 *
 * References: Walter et al. 2007 (EGSR), Heitz 2014 (JCGT 3(2)), Heitz 2018 (JCGT 7(4)),
 * Born & Wolf, Principles of Optics, §14.2; pbrt-v4 §9.4, §9.6 (ConductorBxDF).
 */
#include "basic.h"

#include <patina/shading/fresnel.h>
#include <patina/shading/frame.h>
#include <patina/shading/microfacet.h>
#include <patina/shading/spectral.h>

#include <algorithm>
#include <new>

namespace patina::basic {
namespace {

    using namespace patina::shading;

    constexpr const char* kName = "conductor";

    // Copper at room temperature, 354-892 nm (the entries that span 360-830 nm): P. B. Johnson
    // and R. W. Christy, "Optical constants of the noble metals", Phys. Rev. B 6, 4370-4379
    // (1972), as tabulated by refractiveindex.info (CC0); wavelengths converted from µm to nm.
    // clang-format off
    constexpr int kCopperCount = 18;
    constexpr float kCopperLambdaNm[kCopperCount] = {
        354.2f, 367.9f, 381.5f, 397.4f, 413.3f, 430.5f, 450.9f, 471.4f, 495.9f,
        520.9f, 548.6f, 582.1f, 616.8f, 659.5f, 704.5f, 756.0f, 821.1f, 892.0f};
    constexpr float kCopperN[kCopperCount] = {
        1.37f, 1.36f, 1.33f, 1.32f, 1.28f, 1.25f, 1.24f, 1.25f, 1.22f,
        1.18f, 1.02f, 0.70f, 0.30f, 0.22f, 0.21f, 0.24f, 0.26f, 0.30f};
    constexpr float kCopperK[kCopperCount] = {
        1.916f, 1.975f, 2.045f, 2.116f, 2.207f, 2.305f, 2.397f, 2.483f, 2.564f,
        2.608f, 2.577f, 2.704f, 3.205f, 3.747f, 4.205f, 4.665f, 5.180f, 5.768f};
    const PatinaTabulatedSpectrum kCopperEta = {kCopperCount, kCopperLambdaNm, kCopperN};
    const PatinaTabulatedSpectrum kCopperKappa = {kCopperCount, kCopperLambdaNm, kCopperK};
    // clang-format on

    // clang-format off
    const PatinaParamDecl kParams[] = {
        {"eta", PATINA_PARAM_SPECTRUM, {1.0f, 0.0f, 0.0f}, nullptr, &kCopperEta, 0.0f, 1000.0f, "",
         "Real part n of the metal's complex index of refraction n + ik relative to the outside, "
         "per wavelength in nm (default: copper, Johnson & Christy 1972)."},
        {"k", PATINA_PARAM_SPECTRUM, {0.0f, 0.0f, 0.0f}, nullptr, &kCopperKappa, 0.0f, 1000.0f, "",
         "Extinction coefficient k, the imaginary part of the complex index n + ik, per "
         "wavelength in nm (default: copper, Johnson & Christy 1972)."},
        {"roughness", PATINA_PARAM_FLOAT, {0.2f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1.0f, "",
         "Perceptual roughness r; the GGX width is alpha = r^2, and r < 0.001 is a perfect "
         "mirror."},
        {"anisotropy", PATINA_PARAM_FLOAT, {0.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1.0f, "",
         "Stretch of the highlight along dPdu: alpha_x = alpha / sqrt(1 - 0.9 a), alpha_y = "
         "alpha * sqrt(1 - 0.9 a); 0 is isotropic."},
    };
    // clang-format on

    struct Conductor {
        TabulatedSpectrum eta;
        TabulatedSpectrum k;
        TrowbridgeReitz distribution;
        bool smooth = false;
    };

    /// Exact conductor Fresnel reflectance at |cos_theta_i| for each wavelength of the path.
    SpectralArray fresnel(const Conductor& c, float cos_theta_i, const PatinaWavelengths& wl)
    {
        SpectralArray F;
        for_each_wavelength(wl, [&](int i, float lambda) {
            F[i] = fresnel_conductor(cos_theta_i, c.eta.eval(lambda), c.k.eval(lambda));
        });
        return F;
    }

    /// Microfacet normal of the reflection pair (wo, wi), above the surface; false when there
    /// is none (different hemispheres, a direction in the tangent plane, wi = −wo).
    bool reflection_half_vector(Vec3 wo, Vec3 wi, Vec3* wm)
    {
        if (!same_hemisphere(wo, wi))
            return false;
        const Vec3 h = wo + wi;
        if (length_squared(h) == 0.0f)
            return false;
        *wm = face_forward(normalize(h), Vec3(0.0f, 0.0f, 1.0f));
        return wm->z > 0.0f;
    }

    /// The rough lobe's f (per wavelength) and pdf at (wo, wi); false, with f and pdf
    /// untouched, where the lobe is zero.
    bool rough_lobe(const Conductor& c, Vec3 wo, Vec3 wi, const PatinaWavelengths& wl,
                    SpectralArray* f, float* pdf)
    {
        Vec3 wm;
        if (!reflection_half_vector(wo, wi, &wm))
            return false;
        const float cos_o = abs_cos_theta(wo), cos_i = abs_cos_theta(wi);
        const float wo_dot_wm = abs_dot(wo, wm);
        // Torrance-Sparrow reflection with Smith G2: Walter et al. 2007 Eq. 20, pbrt-v4 §9.6.5
        const float dg = c.distribution.d(wm) * c.distribution.g(wo, wi) / (4.0f * cos_o * cos_i);
        // Visible-normal density times the reflection Jacobian 1/(4 |wo·wm|): Walter et al. 2007
        // Eq. 14, Heitz 2018
        const float p = c.distribution.pdf(wo, wm) / (4.0f * wo_dot_wm);
        if (!(dg > 0.0f) || !is_finite(dg) || !(p > 0.0f) || !is_finite(p))
            return false;
        if (f)
            *f = fresnel(c, wo_dot_wm, wl) * dg;
        if (pdf)
            *pdf = p;
        return true;
    }

    bool is_finite_nonneg(float x)
    {
        return is_finite(x) && x >= 0.0f;
    }

    /// Checks a SPECTRUM parameter: usable table, values in [0, max]; nullptr when fine.
    const char* check_spectrum(const PatinaParamValue& v)
    {
        if (v.type != PATINA_PARAM_SPECTRUM)
            return "expected a spectrum value";
        if (const char* why = check_tabulated(v.spectrum))
            return why;
        for (int i = 0; i < v.spectrum.count; ++i)
            if (!is_finite_nonneg(v.spectrum.value[i]))
                return "values must be finite and >= 0";
        return nullptr;
    }

    void* create(const PatinaHost* host, const PatinaParamValue* values)
    {
        const plugin::Parameters p(host, kName, kParams, values);
        const PatinaParamValue& eta = p.value("eta", PATINA_PARAM_SPECTRUM);
        const PatinaParamValue& k = p.value("k", PATINA_PARAM_SPECTRUM);
        const PatinaParamValue& roughness = p.value("roughness", PATINA_PARAM_FLOAT);
        const PatinaParamValue& anisotropy = p.value("anisotropy", PATINA_PARAM_FLOAT);
        if (!p.ok())
            return nullptr;
        if (const char* why = check_spectrum(eta)) {
            report_error(host, kName, "eta: %s", why);
            return nullptr;
        }
        if (const char* why = check_spectrum(k)) {
            report_error(host, kName, "k: %s", why);
            return nullptr;
        }
        if (roughness.type != PATINA_PARAM_FLOAT || !(roughness.f >= 0.0f && roughness.f <= 1.0f)) {
            report_error(host, kName, "roughness %g must lie in [0, 1]", roughness.f);
            return nullptr;
        }
        if (anisotropy.type != PATINA_PARAM_FLOAT ||
            !(anisotropy.f >= 0.0f && anisotropy.f <= 1.0f)) {
            report_error(host, kName, "anisotropy %g must lie in [0, 1]", anisotropy.f);
            return nullptr;
        }

        auto* c = make_instance<Conductor>(host, kName);
        if (!c)
            return nullptr;
        try {
            c->eta = TabulatedSpectrum(eta.spectrum);
            c->k = TabulatedSpectrum(k.spectrum);
        } catch (const std::bad_alloc&) {
            report_error(host, kName, "out of memory");
            delete c;
            return nullptr;
        }
        // n + ik = 0 has no Fresnel reflectance; n and k are piecewise linear over the union
        // of both tables' wavelengths, so checking those wavelengths covers every λ
        auto vanishes_at = [&](float lambda) {
            if (c->eta.eval(lambda) != 0.0f || c->k.eval(lambda) != 0.0f)
                return false;
            report_error(host, kName,
                         "eta and k are both 0 at %g nm; a complex index of "
                         "refraction n + ik must not vanish",
                         lambda);
            return true;
        };
        bool vanishes = false;
        for (int i = 0; i < c->eta.size() && !vanishes; ++i)
            vanishes = vanishes_at(c->eta.lambda_nm(i));
        for (int i = 0; i < c->k.size() && !vanishes; ++i)
            vanishes = vanishes_at(c->k.lambda_nm(i));
        if (vanishes) {
            delete c;
            return nullptr;
        }
        c->smooth = roughness.f < kSmoothRoughness;
        // Anisotropic widths from one roughness: Burley 2012, addendum (aspect = sqrt(1 − 0.9 a))
        const float alpha = TrowbridgeReitz::roughness_to_alpha(roughness.f);
        const float aspect = std::sqrt(1.0f - 0.9f * anisotropy.f);
        c->distribution = TrowbridgeReitz(alpha / aspect, alpha * aspect);
        return c;
    }

    void destroy(void* instance)
    {
        delete static_cast<Conductor*>(instance);
    }

    void eval(const void* instance, const PatinaShadingContext*, PatinaVec3 wo, PatinaVec3 wi,
              const PatinaWavelengths* wl, float* f)
    {
        const auto& c = *static_cast<const Conductor*>(instance);
        SpectralArray value;
        if (!c.smooth)
            rough_lobe(c, wo, wi, *wl, &value, nullptr);
        store(value, *wl, f);
    }

    float pdf(const void* instance, const PatinaShadingContext*, PatinaVec3 wo, PatinaVec3 wi,
              const PatinaWavelengths* wl)
    {
        const auto& c = *static_cast<const Conductor*>(instance);
        float p = 0.0f;
        if (!c.smooth)
            rough_lobe(c, wo, wi, *wl, nullptr, &p);
        return p;
    }

    int sample(const void* instance, const PatinaShadingContext*, PatinaVec3 wo_, float /*u_lobe*/,
               PatinaVec2 u, const PatinaWavelengths* wl, PatinaBsdfSample* out)
    {
        const auto& c = *static_cast<const Conductor*>(instance);
        const Vec3 wo = wo_;
        if (wo.z == 0.0f)
            return 0;
        if (c.smooth) {
            // Perfect specular reflection: f = F / |cos θi| against a discrete probability 1
            const Vec3 wi(-wo.x, -wo.y, wo.z);
            const float cos_i = abs_cos_theta(wi);
            store(fresnel(c, cos_i, *wl) * (1.0f / cos_i), *wl, out->f);
            out->wi = wi;
            out->pdf = 1.0f;
            out->lobe = PATINA_LOBE_REFLECTION | PATINA_LOBE_SPECULAR;
            out->eta = 1.0f;
            return 1;
        }
        // Sample a visible microfacet normal and reflect wo about it
        const Vec3 wm = c.distribution.sample_wm(wo, u);
        const Vec3 wi = normalize(reflect(wo, wm));
        if (!same_hemisphere(wo, wi))
            return 0;
        // f and pdf exactly as eval and pdf compute them at the sampled direction
        SpectralArray f;
        float p = 0.0f;
        if (!rough_lobe(c, wo, wi, *wl, &f, &p))
            return 0;
        store(f, *wl, out->f);
        out->wi = wi;
        out->pdf = p;
        out->lobe = PATINA_LOBE_REFLECTION | PATINA_LOBE_GLOSSY;
        out->eta = 1.0f;
        return 1;
    }

    void albedo(const void* instance, const PatinaShadingContext*, PatinaVec3 wo,
                const PatinaWavelengths* wl, float* a)
    {
        // Estimate: the Fresnel reflectance at the viewing angle (ignores masking losses)
        const auto& c = *static_cast<const Conductor*>(instance);
        store(fresnel(c, abs_cos_theta(wo), *wl), *wl, a);
    }

    const PatinaBsdfFuncs kFuncs = {eval, pdf, sample, albedo};

} // namespace

PatinaShaderDesc conductor_shader()
{
    return describe(kName,
                 "Rough or smooth metal: GGX microfacets with the exact Fresnel reflectance of a "
                 "spectral complex index of refraction n + ik.",
                 kParams, create, destroy, kFuncs);
}

} // namespace patina::basic
