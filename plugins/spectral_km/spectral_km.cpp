/*
 * spectral_km — A faded pigment layer over its substrate, from a fade stack (bsdf)
 * ================================================================================
 *
 *  Parameter       Type      Default   Description
 *  --------------  --------  --------  -------------------------------------------------
 *  fade            file      (none)    fade.toml of a fade stack (patina-texgen fade).
 *  coat            float     0         Weight of a clear glossy coat over the layer, [0, 1].
 *  coat_roughness  float     0.1       Perceptual roughness of the coat (GGX alpha = r²).
 *  coat_ior        float     1.5       Index of refraction of the coat.
 *  substrate       spectrum  -1        Reflectance under the layer, replacing the stack's;
 *                                      -1 keeps the stack's.
 *
 * Kimmel et al. 2013 fade a pigment layer over a substrate (§3-§4); `patina-texgen fade`
 * solves the two-flux model once per material over a range of doses and writes, per dose
 * row and wavelength, the layer's reflectance from above (R_top), from below (R_bottom) and
 * its transmittance T, and a dose map that gives each texel its (fractional) row.
 *
 * At a shading point this shader looks the row up in the dose map at uv (filtered, through
 * the host), interpolates R_top, T, R_bottom and the substrate ρ* at each wavelength of the
 * path (bilinear in row and wavelength; clamped to the table's wavelengths, e.g. 330-700 nm,
 * outside it) and composites the layer over its substrate,
 *
 *     R(λ) = R_top + T² ρ* / (1 − R_bottom ρ*)              (Kubelka 1948; Eqs. 25-27)
 *
 * which is the solver's total reflectance. The layer reflects diffusely (the two-flux model
 * has no angular detail): f = R / π. With `coat` > 0 a clear dielectric coat adds a GGX
 * reflection lobe and takes the energy it reflects away from the diffuse light (coat.h):
 * the directional albedo is w E(wo) + R (1 − w E(wo)) <= 1, and f is reciprocal.
 *
 * Both sides of a surface show the same (front) state. `substrate` replaces ρ* without
 * re-solving the fading: the layer faded over the stack's substrate, seen over another one.
 *
 * Sampling picks the coat with probability w E(wo) / (w E(wo) + 0.5 (1 − w E(wo))), then
 * the coat's visible normals (Heitz 2018) or the cosine-weighted hemisphere; pdf is the
 * same mixture.
 *
 * References: Kimmel, Baranoski, Chen, Yim, Miranda 2013, "Spectral Appearance Changes
 * Induced by Light Exposure", ACM TOG 32(1); Kubelka 1948, JOSA 38(5); Walter et al. 2007;
 * Kelemen & Szirmay-Kalos 2001; Kulla & Conty 2017 (energy compensation).
 */
#include "coat.h"
#include "fade_table.h"

#include <patina/plugin_support.h>
#include <patina/shading/sampling.h>
#include <patina/shading/spectral.h>

#include <cstdio>
#include <exception>
#include <new>

namespace patina::spectral_km {
namespace {

    using namespace patina::shading;

    constexpr const char* kName = "spectral_km";
    // The base albedo sampling assumes when it weighs the coat against the diffuse lobe
    constexpr float kTypicalBaseAlbedo = 0.5f;

    struct SpectralKm {
        const PatinaHost* host = nullptr;
        FadeTable table;
        Coat coat;
    };

    // clang-format off
    const PatinaParamDecl kParams[] = {
        {"fade", PATINA_PARAM_FILE, {0.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 0.0f, "",
         "fade.toml of a fade stack written by patina-texgen fade (table, dose map, substrate)."},
        {"coat", PATINA_PARAM_FLOAT, {0.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1.0f, "",
         "Weight of a clear glossy coat (varnish) over the layer; 0 = none."},
        {"coat_roughness", PATINA_PARAM_FLOAT, {0.1f, 0.0f, 0.0f}, nullptr, nullptr, 0.01f, 1.0f,
         "", "Perceptual roughness r of the coat; the GGX width is alpha = r^2."},
        {"coat_ior", PATINA_PARAM_FLOAT, {1.5f, 0.0f, 0.0f}, nullptr, nullptr, 1.01f, 3.0f, "",
         "Index of refraction of the coat (its Fresnel reflectance)."},
        {"substrate", PATINA_PARAM_SPECTRUM, {-1.0f, 0.0f, 0.0f}, nullptr, nullptr, -1.0f, 1.0f,
         "", "Reflectance under the layer over wavelength in nm, replacing the stack's "
         "substrate; -1 keeps the stack's."},
    };
    // clang-format on

    void report(const PatinaHost* host, const std::string& message)
    {
        if (host && host->error)
            host->error(host, kName, message.c_str());
    }

    void* create(const PatinaHost* host, const PatinaParamValue* values)
    {
        const plugin::Parameters p(host, kName, kParams, values);
        const char* path = p.text("fade");
        const PatinaTabulatedSpectrum& s = p.value("substrate", PATINA_PARAM_SPECTRUM).spectrum;
        const float coat = p.number("coat"), coat_roughness = p.number("coat_roughness"),
                    coat_ior = p.number("coat_ior");
        if (!p.ok())
            return nullptr;
        try {
            auto* instance = new SpectralKm{};
            instance->host = host;
            if (!*path) {
                delete instance;
                report(host, "fade: no fade.toml given (a fade stack from patina-texgen fade)");
                return nullptr;
            }
            if (std::string e = instance->table.load(host, path); !e.empty()) {
                delete instance;
                report(host, "fade: " + e);
                return nullptr;
            }
            // Substrate override: the spectrum at the table's wavelengths
            const bool keep = s.count == 1 && s.value[0] < 0.0f;
            if (!keep) {
                std::vector<float> rho;
                for (float lambda : instance->table.wavelengths_nm()) {
                    const float v = patina_tabulated_eval(&s, lambda);
                    if (!(v >= 0.0f && v <= 1.0f)) {
                        delete instance;
                        report(host, "substrate: a reflectance must lie in [0, 1] (or be the "
                                     "single value -1 to keep the stack's)");
                        return nullptr;
                    }
                    rho.push_back(v);
                }
                instance->table.set_substrate(std::move(rho));
            }
            instance->coat = Coat(coat, coat_roughness, coat_ior);
            return instance;
        } catch (const std::exception& e) {
            report(host, std::string("create failed: ") + e.what());
        } catch (...) {
            report(host, "create failed");
        }
        return nullptr;
    }

    void destroy(void* instance)
    {
        delete static_cast<SpectralKm*>(instance);
    }

    // The table row at the shading point (the dose map's coordinate channel).
    float dose_row(const SpectralKm& s, const PatinaShadingContext* ctx)
    {
        if (!ctx)
            return 0.0f;
        float row = 0.0f;
        if (!s.host->texture_lookup(s.host, s.table.dose_map(), ctx, ctx->uv.x, ctx->uv.y, 0, 1,
                                    &row))
            return 0.0f;
        return row;
    }

    // R(λ) of the layer over its substrate at the path's wavelengths.
    SpectralArray layer_reflectance(const SpectralKm& s, const PatinaShadingContext* ctx,
                                    const PatinaWavelengths& wl)
    {
        const float row = dose_row(s, ctx);
        SpectralArray r;
        for_each_wavelength(wl, [&](int i, float lambda) { r[i] = s.table.reflectance(row, lambda); });
        return r;
    }

    // Both sides show the front: mirror a configuration below the surface above it.
    bool to_upper(Vec3* wo, Vec3* wi)
    {
        if (!same_hemisphere(*wo, *wi) || wo->z == 0.0f)
            return false;
        if (wo->z < 0.0f) {
            wo->z = -wo->z;
            wi->z = -wi->z;
        }
        return true;
    }

    float coat_probability(const SpectralKm& s, float cos_o)
    {
        const float w = s.coat.weight() * s.coat.albedo(cos_o);
        if (w <= 0.0f)
            return 0.0f;
        return w / (w + kTypicalBaseAlbedo * (1.0f - w));
    }

    void eval(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo_,
              PatinaVec3 wi_, const PatinaWavelengths* wl, float* f)
    {
        const auto& s = *static_cast<const SpectralKm*>(instance);
        Vec3 wo(wo_), wi(wi_);
        if (!to_upper(&wo, &wi)) {
            fill(0.0f, *wl, f);
            return;
        }
        // Diffuse layer R / π, scaled by what the coat lets through; plus the coat's lobe
        const float base = kInvPi * s.coat.base_factor(wo.z, wi.z);
        const float spec = s.coat.weight() > 0.0f ? s.coat.weight() * s.coat.eval(wo, wi) : 0.0f;
        SpectralArray r = layer_reflectance(s, ctx, *wl) * base;
        r += SpectralArray(spec);
        store(r, *wl, f);
    }

    float pdf(const void* instance, const PatinaShadingContext*, PatinaVec3 wo_, PatinaVec3 wi_,
              const PatinaWavelengths*)
    {
        const auto& s = *static_cast<const SpectralKm*>(instance);
        Vec3 wo(wo_), wi(wi_);
        if (!to_upper(&wo, &wi))
            return 0.0f;
        const float p = coat_probability(s, wo.z);
        const float p_coat = p > 0.0f ? p * s.coat.pdf(wo, wi) : 0.0f;
        return p_coat + (1.0f - p) * cosine_hemisphere_pdf(wi.z);
    }

    int sample(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo_,
               float u_lobe, PatinaVec2 u_, const PatinaWavelengths* wl, PatinaBsdfSample* out)
    {
        const auto& s = *static_cast<const SpectralKm*>(instance);
        Vec3 wo(wo_);
        if (wo.z == 0.0f)
            return 0;
        const bool below = wo.z < 0.0f;
        if (below)
            wo.z = -wo.z;
        const Vec2 u(u_.x, u_.y);
        const float p = coat_probability(s, wo.z);
        Vec3 wi;
        bool glossy = false;
        if (u_lobe < p) {
            if (!s.coat.sample(wo, u, &wi))
                return 0;
            glossy = true;
        } else {
            wi = sample_cosine_hemisphere(u);
        }
        if (below) {
            wo.z = -wo.z;
            wi.z = -wi.z;
        }
        // f and pdf exactly as eval and pdf give them at the sampled direction
        const float density = pdf(instance, ctx, wo, wi, wl);
        if (!(density > 0.0f))
            return 0;
        out->wi = wi;
        eval(instance, ctx, wo, wi, wl, out->f);
        out->pdf = density;
        out->lobe = PATINA_LOBE_REFLECTION | (glossy ? PATINA_LOBE_GLOSSY : PATINA_LOBE_DIFFUSE);
        out->eta = 1.0f;
        return 1;
    }

    void albedo(const void* instance, const PatinaShadingContext* ctx, PatinaVec3 wo,
                const PatinaWavelengths* wl, float* a)
    {
        const auto& s = *static_cast<const SpectralKm*>(instance);
        const float e = s.coat.weight() * s.coat.albedo(wo.z);
        SpectralArray r = layer_reflectance(s, ctx, *wl) * (1.0f - e);
        r += SpectralArray(e);
        store(r, *wl, a);
    }

    const PatinaBsdfFuncs kFuncs = {eval, pdf, sample, albedo};

}  // namespace
}  // namespace patina::spectral_km

PATINA_PLUGIN("spectral_km", "0.1.0",
              patina::plugin::describe(
                  patina::spectral_km::kName,
                  "A pigment layer faded by light (Kimmel et al. 2013) over its substrate: "
                  "Kubelka-Munk reflectance per wavelength from a fade stack, with an optional "
                  "clear glossy coat.",
                  patina::spectral_km::kParams, patina::spectral_km::create,
                  patina::spectral_km::destroy, patina::spectral_km::kFuncs))
