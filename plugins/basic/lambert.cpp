/*
 * lambert — Smooth diffuse material (bsdf)
 * =========================================
 *
 *  Parameter     Type    Default          Description
 *  ------------  ------  ---------------  -----------------------------------------------
 *  reflectance   color   (0.5, 0.5, 0.5)  Diffuse reflectance R in [0, 1], scene-linear.
 *  reflectance_scale_map
 *                texture none             A data map (raw) whose first channel, clamped to
 *                                         [0, 1], scales R: baked ambient occlusion,
 *                                         accessibility or wetness shown on a surface.
 *  map_gain      float   1                Multiplies the map value before the clamp (e.g.
 *                                         1 / max for an exposure map in J/m^2).
 *  reflectance_spectrum
 *                spectrum -1              A measured reflectance over wavelength in nm, in
 *                                         [0, 1], used instead of `reflectance` (e.g. a
 *                                         ColorChecker patch: { file = "chart.csv", column =
 *                                         "dark skin" }); -1: use `reflectance`.
 *
 * An ideal diffuse (Lambertian) reflector: light is scattered equally into every direction
 * of the hemisphere it arrived from, f(wo, wi) = R(λ) / π, so the directional albedo is
 * R(λ) for every viewing direction. R is the host's smooth uplift of the RGB reflectance
 * (abi.h, PatinaRgbSpectrum); a grey stays exactly constant over wavelength. A
 * `reflectance_spectrum` is used as it is, linear between its samples and held at its end
 * values outside them.
 *
 * Both sides of the surface reflect alike (wo and wi in the same hemisphere); nothing is
 * transmitted. Directions are sampled with the cosine-weighted density cos θi / π, which
 * makes every sample's weight f cos θi / pdf equal R(λ).
 *
 * Reference: Lambert 1760, "Photometria"; pbrt-v4 §9.2 (DiffuseBxDF).
 */
#include "basic.h"

#include <patina/shading/fast_trig.h>
#include <patina/shading/frame.h>
#include <patina/shading/sampling.h>
#include <patina/shading/spectral.h>

#include <new>
#include <vector>

namespace patina::basic {
namespace {

    using namespace patina::shading;

    constexpr const char* kName = "lambert";

    struct Lambert {
        PatinaRgbSpectrum reflectance;
        // A measured reflectance (its own copy of the samples), used instead when not empty.
        std::vector<float> measured_nm{}, measured{};
        PatinaTabulatedSpectrum measured_spectrum{0, nullptr, nullptr};
        const PatinaHost* host = nullptr;
        const PatinaTexture* scale_map = nullptr;  // may be null
        float map_gain = 1.0f;
        // A grey reflectance without a map is one number for every wavelength and point:
        // R / π, computed once here (the same bits as evaluating it per call).
        bool constant = false;
        float constant_f = 0.0f;
    };

    // clang-format off
    const PatinaParamDecl kParams[] = {
        {"reflectance", PATINA_PARAM_COLOR, {0.5f, 0.5f, 0.5f}, nullptr, nullptr, 0.0f, 1.0f,
         "scene_linear", "Diffuse reflectance (albedo) R in [0, 1]; f = R / pi."},
        {"reflectance_scale_map", PATINA_PARAM_TEXTURE, {0.0f, 0.0f, 0.0f}, nullptr, nullptr,
         0.0f, 0.0f, "raw",
         "Data texture whose first channel, clamped to [0, 1], scales the reflectance (e.g. a "
         "baked AO, accessibility or wetness map)."},
        {"map_gain", PATINA_PARAM_FLOAT, {1.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1e30f,
         "", "Multiplies the reflectance_scale_map value before the clamp to [0, 1] (e.g. "
         "1 / max for an exposure map in J/m^2)."},
        {"reflectance_spectrum", PATINA_PARAM_SPECTRUM, {-1.0f, 0.0f, 0.0f}, nullptr, nullptr,
         -1.0f, 1.0f, "",
         "Measured reflectance R(lambda) in [0, 1] over wavelength in nm, used instead of "
         "reflectance (e.g. { file = \"chart.csv\", column = \"dark skin\" }); -1: use "
         "reflectance."},
    };
    // clang-format on

    void* create(const PatinaHost* host, const PatinaParamValue* values)
    {
        const plugin::Parameters p(host, kName, kParams, values);
        const PatinaParamValue& r = p.value("reflectance", PATINA_PARAM_COLOR);
        const PatinaTexture* scale_map = p.texture("reflectance_scale_map");
        const float map_gain = p.number("map_gain");
        const PatinaParamValue& measured = p.value("reflectance_spectrum", PATINA_PARAM_SPECTRUM);
        if (!p.ok())
            return nullptr;
        const PatinaTabulatedSpectrum& m = measured.spectrum;
        const bool use_measured = !(m.count == 1 && m.value[0] == -1.0f);
        for (int i = 0; use_measured && i < m.count; ++i)
            if (!(m.value[i] >= 0.0f && m.value[i] <= 1.0f)) {
                report_error(host, kName, "reflectance_spectrum: %g at %g nm must lie in [0, 1]",
                             m.value[i], m.lambda_nm[i]);
                return nullptr;
            }
        if (r.type != PATINA_PARAM_COLOR) {
            report_error(host, kName, "reflectance: expected a colour value");
            return nullptr;
        }
        for (int c = 0; c < 3; ++c) {
            if (!(r.rgb[c] >= 0.0f && r.rgb[c] <= 1.0f)) {
                report_error(host, kName, "reflectance (%g, %g, %g) must lie in [0, 1]", r.rgb[0],
                             r.rgb[1], r.rgb[2]);
                return nullptr;
            }
        }
        const PatinaRgbSpectrum& s = r.color;
        if (s.illuminant != 0) {
            report_error(host, kName,
                         "reflectance was uplifted as an emission colour; a "
                         "reflectance spectrum is needed");
            return nullptr;
        }
        if (!is_finite(s.c0) || !is_finite(s.c1) || !is_finite(s.c2) || !is_finite(s.scale)) {
            report_error(host, kName, "reflectance spectrum has non-finite coefficients");
            return nullptr;
        }
        // An albedo above 1 would create energy; allow only float rounding
        float lo = 0.0f, hi = 0.0f;
        rgb_spectrum_range(s, &lo, &hi);
        if (lo < 0.0f || hi > 1.0f + 1e-5f) {
            report_error(host, kName,
                         "reflectance spectrum ranges over [%g, %g] in 360-830 nm; it must stay "
                         "within [0, 1]",
                         lo, hi);
            return nullptr;
        }
        Lambert* lambert = make_instance<Lambert>(host, kName, s);
        if (!lambert)
            return nullptr;
        lambert->host = host;
        lambert->scale_map = scale_map;
        lambert->map_gain = map_gain;
        if (use_measured) {
            try {  // no exception may cross the C ABI
                lambert->measured_nm.assign(m.lambda_nm, m.lambda_nm + m.count);
                lambert->measured.assign(m.value, m.value + m.count);
            } catch (const std::bad_alloc&) {
                report_error(host, kName, "out of memory");
                delete lambert;
                return nullptr;
            }
            lambert->measured_spectrum = {m.count, lambert->measured_nm.data(),
                                          lambert->measured.data()};
            return lambert;
        }
        if (!lambert->scale_map && s.c0 == 0.0f && s.c1 == 0.0f) {
            lambert->constant = true;
            // eval's value for a grey: eval_rgb (the constant c2 path) times (1 * 1/π).
            lambert->constant_f = patina_rgb_spectrum_eval(&s, 0.0f) * (1.0f * kInvPi);
        }
        return lambert;
    }

    void destroy(void* instance)
    {
        delete static_cast<Lambert*>(instance);
    }

    // The reflectance scale at the shading point: the map's first channel in [0, 1], or 1.
    float reflectance_scale(const Lambert& lambert, const PatinaShadingContext* ctx)
    {
        if (!lambert.scale_map || !ctx)
            return 1.0f;
        float value = 1.0f;
        if (!lambert.host->texture_lookup(lambert.host, lambert.scale_map, ctx, ctx->uv.x,
                                          ctx->uv.y, 0, 1, &value))
            return 1.0f;
        value *= lambert.map_gain;
        return value >= 0.0f ? (value <= 1.0f ? value : 1.0f) : 0.0f;  // NaN -> 0
    }

    // R at the path's wavelengths: the measured spectrum, else the uplifted colour.
    SpectralArray reflectance(const Lambert& lambert, const PatinaWavelengths& wl)
    {
        return lambert.measured.empty() ? eval_rgb(lambert.reflectance, wl)
                                        : eval_tabulated(lambert.measured_spectrum, wl);
    }

    void eval(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo, PatinaVec3 wi,
              const PatinaWavelengths* wl, float* f)
    {
        const auto* lambert = static_cast<const Lambert*>(instance);
        if (!same_hemisphere(wo, wi)) {
            fill(0.0f, *wl, f);
            return;
        }
        if (lambert->constant) {
            // Every lane of the output array (abi.h: it holds PATINA_MAX_WAVELENGTHS
            // floats): two vector stores instead of a loop over the count.
            for (int i = 0; i < PATINA_MAX_WAVELENGTHS; ++i)
                f[i] = lambert->constant_f;
            return;
        }
        // Lambertian BRDF f = R / π: pbrt-v4 §9.2
        store(reflectance(*lambert, *wl) * (reflectance_scale(*lambert, ctx) * kInvPi), *wl, f);
    }

    float pdf(const void*, const PatinaShadingContext*, PatinaVec3 wo, PatinaVec3 wi,
              const PatinaWavelengths*)
    {
        if (!same_hemisphere(wo, wi))
            return 0.0f;
        return cosine_hemisphere_pdf(abs_cos_theta(wi));
    }

    int sample(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo,
               float /*u_lobe*/, PatinaVec2 u, const PatinaWavelengths* wl, PatinaBsdfSample* out)
    {
        if (wo.z == 0.0f)
            return 0;
        // Cosine-weighted hemisphere on the side of wo (the concentric disc's cos and sin by
        // polynomial: fast_trig.h)
        Vec3 wi = sample_cosine_hemisphere_poly(u);
        if (wo.z < 0.0f)
            wi.z = -wi.z;
        const float p = cosine_hemisphere_pdf(abs_cos_theta(wi));
        if (p == 0.0f)
            return 0;
        out->wi = wi;
        eval(instance, ctx, wo, wi, wl, out->f);
        out->pdf = p;
        out->lobe = PATINA_LOBE_REFLECTION | PATINA_LOBE_DIFFUSE;
        out->eta = 1.0f;
        return 1;
    }

    void albedo(const void* instance, const PatinaShadingContext* ctx, PatinaVec3,
                const PatinaWavelengths* wl, float* a)
    {
        const auto* lambert = static_cast<const Lambert*>(instance);
        store(reflectance(*lambert, *wl) * reflectance_scale(*lambert, ctx), *wl, a);
    }

    const PatinaBsdfFuncs kFuncs = {eval, pdf, sample, albedo};

} // namespace

PatinaShaderDesc lambert_shader()
{
    return describe(kName,
                 "Ideal diffuse (Lambertian) reflection, f = R / pi, on both sides of the surface.",
                 kParams, create, destroy, kFuncs);
}

} // namespace patina::basic
