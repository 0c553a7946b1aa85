/*
 * stone_surface — The boundary of a stone medium: Fresnel raised to a roughness exponent (bsdf)
 * ===========================================================================================
 *
 *  Parameter            Type   Default  Description
 *  -------------------  -----  -------  ------------------------------------------------
 *  eta                  float  1.5      Index of the stone (below the normal) over the
 *                                       outside, in [1, 4]; 1 is an invisible boundary.
 *  roughness_exponent   float  1        Exponent k of the reflected fraction F_r^k, [1, 64].
 *  transmission         string refract  "refract" (Snell) or "diffuse" (cosine-distributed).
 *
 * Dorsey et al. 1999 §5.1: "We compute the amount of reflected light at a surface as
 * F_r(x, ω)^k, where k serves as a simple approximation of surface roughness. ... the
 * remaining light is transmitted through the surface." F_r is the exact Fresnel reflectance
 * of unpolarised light at a smooth dielectric (patina/shading/fresnel.h). Since F_r <= 1,
 * raising it to k > 1 lowers the reflection, most where F_r is small (near the normal), and
 * sends that light into the stone: a rougher stone looks less glossy and more translucent.
 * k = 1 is the smooth interface.
 *
 * Two delta lobes, chosen with probabilities R = F_r^k and T = 1 − R:
 *
 *   reflection    the mirror direction, f |cos θi| / pdf = 1 (weight R / R)
 *   transmission  the refracted direction (Snell), weight T / T = 1
 *
 * transmission = "diffuse" spreads the transmitted 1 − R over the other hemisphere with a
 * cosine distribution instead, f = (1 − R(wo)) / π (the paper does not say where the
 * transmitted light goes; a rough stone surface scatters it). That lobe is not a delta:
 * the path tracer can then sample lights from the boundary (next-event estimation), which
 * makes stone lit by a sky or area lights far less noisy. Energy is conserved the same way
 * (weight 1), but that lobe is not reciprocal.
 *
 * Radiance scaling: radiance is compressed by 1/η'² entering a denser medium (Veach 1997
 * §5.2; η' = η_wi/η_wo) and expanded by η'² leaving it. Both factors are left out here, in
 * both transport modes. A stone is a closed body with the camera and the lights outside, so
 * every path crosses its boundary in and out in pairs, whose factors cancel exactly; leaving
 * them out keeps the throughput inside the stone at its outside value, so that a path
 * tracer's Russian roulette (on throughput) does not kill η² times more paths in the stone
 * than it should (pbrt-v4 §13.4 compensates with an "etaScale" instead). Radiance *inside*
 * the stone is therefore η² too low, which no measurement from outside can see.
 *
 * Both sides are shaded: from inside the stone (wo.z < 0) F_r uses the inverted index and
 * total internal reflection (F_r = 1) stays total for every k. F_r is the same for a pair of
 * refracted directions seen from either side, so the lobes are reciprocal. eval and pdf are
 * 0 (delta lobes, abi.h §3). With eta = 1, F_r = 0: light passes straight through, which is
 * the index-matched boundary of the white-furnace test.
 *
 * The object's interior (interior = "<slab_volume shader>") is below the shading normal:
 * the mesh's normals must point out of the stone.
 */
#include "slab_volume.h"

#include <patina/shading/frame.h>
#include <patina/shading/fresnel.h>
#include <patina/shading/sampling.h>
#include <patina/shading/spectral.h>

#include <cmath>
#include <string_view>

namespace patina::slab_volume {
namespace {

    using namespace patina::shading;

    constexpr const char* kName = "stone_surface";

    // clang-format off
    const PatinaParamDecl kParams[] = {
        {"eta", PATINA_PARAM_FLOAT, {1.5f, 0.0f, 0.0f}, nullptr, nullptr, 1.0f, 4.0f, "",
         "Index of refraction of the stone (below the normal) over the outside; 1 is an "
         "invisible (index-matched) boundary."},
        {"roughness_exponent", PATINA_PARAM_FLOAT, {1.0f, 0.0f, 0.0f}, nullptr, nullptr, 1.0f,
         64.0f, "",
         "Exponent k of the reflected fraction F_r^k (Dorsey et al. 1999 Sec. 5.1): 1 is smooth, "
         "larger is rougher (less reflection, more light into the stone)."},
        {"transmission", PATINA_PARAM_STRING, {0.0f, 0.0f, 0.0f}, "refract", nullptr, 0.0f, 0.0f,
         "",
         "Where the transmitted light goes: \"refract\" (Snell's law, a delta lobe) or "
         "\"diffuse\" (cosine-distributed on the other side; lets the renderer sample lights)."},
    };
    // clang-format on

    struct StoneSurface {
        float eta = 1.5f;
        float k = 1.0f;
        bool diffuse = false; ///< cosine-distributed transmission instead of Snell's
    };

    /// η' = η_wi / η_wo for a direction crossing from wo's side to the other.
    float crossing_eta(const StoneSurface& s, float cos_theta_o)
    {
        return cos_theta_o > 0.0f ? s.eta : 1.0f / s.eta;
    }

    /// f of the diffuse transmission lobe, (1 − R(wo)) / π (no η'² scaling: see the top).
    float diffuse_transmission(const StoneSurface& s, Vec3 wo);

    /// The reflected fraction F_r(cos θo)^k seen from wo's side (§5.1).
    float reflected_fraction(const StoneSurface& s, float cos_theta_o)
    {
        const float fr = fresnel_dielectric(cos_theta_o, s.eta);
        if (fr >= 1.0f)
            return 1.0f; // total internal reflection, whatever k
        return fr > 0.0f ? std::pow(fr, s.k) : 0.0f;
    }

    void* create(const PatinaHost* host, const PatinaParamValue* values)
    {
        const plugin::Parameters p(host, kName, kParams, values);
        const PatinaParamValue& eta = p.value("eta", PATINA_PARAM_FLOAT);
        const PatinaParamValue& k = p.value("roughness_exponent", PATINA_PARAM_FLOAT);
        if (!p.ok())
            return nullptr;
        if (eta.type != PATINA_PARAM_FLOAT || !(eta.f >= 1.0f && eta.f <= 4.0f)) {
            report_error(host, kName,
                         "eta %g must lie in [1, 4] (stone index over the outside's)", eta.f);
            return nullptr;
        }
        if (k.type != PATINA_PARAM_FLOAT || !(k.f >= 1.0f && k.f <= 64.0f)) {
            report_error(host, kName, "roughness_exponent %g must lie in [1, 64]", k.f);
            return nullptr;
        }
        const PatinaParamValue& transmission = p.value("transmission", PATINA_PARAM_STRING);
        const std::string_view mode = transmission.s ? transmission.s : "";
        if (transmission.type != PATINA_PARAM_STRING || (mode != "refract" && mode != "diffuse")) {
            report_error(host, kName, "transmission '%s' must be \"refract\" or \"diffuse\"",
                         transmission.s ? transmission.s : "");
            return nullptr;
        }
        auto* s = make_instance<StoneSurface>(host, kName);
        if (!s)
            return nullptr;
        s->eta = eta.f;
        s->k = k.f;
        s->diffuse = mode == "diffuse";
        return s;
    }

    void destroy(void* instance)
    {
        delete static_cast<StoneSurface*>(instance);
    }

    float diffuse_transmission(const StoneSurface& s, Vec3 wo)
    {
        return (1.0f - reflected_fraction(s, cos_theta(wo))) * kInvPi;
    }

    /// True when wo and wi lie on opposite sides: the diffuse transmission lobe's domain.
    bool crosses(Vec3 wo, Vec3 wi)
    {
        return wo.z * wi.z < 0.0f && is_finite(wo) && is_finite(wi);
    }

    void eval(const void* instance, const PatinaShadingContext*, PatinaVec3 wo_,
              PatinaVec3 wi_, const PatinaWavelengths* wl, float* f)
    {
        const auto& s = *static_cast<const StoneSurface*>(instance);
        const Vec3 wo = wo_, wi = wi_;
        // Reflection and refraction are delta lobes (0 here); diffuse transmission is not
        fill(s.diffuse && crosses(wo, wi) ? diffuse_transmission(s, wo) : 0.0f, *wl, f);
    }

    float pdf(const void* instance, const PatinaShadingContext*, PatinaVec3 wo_, PatinaVec3 wi_,
              const PatinaWavelengths*)
    {
        const auto& s = *static_cast<const StoneSurface*>(instance);
        const Vec3 wo = wo_, wi = wi_;
        if (!s.diffuse || !crosses(wo, wi))
            return 0.0f;
        // Chosen with probability 1 − R, then cosine-distributed
        return (1.0f - reflected_fraction(s, cos_theta(wo))) * abs_cos_theta(wi) * kInvPi;
    }

    int sample(const void* instance, const PatinaShadingContext*, PatinaVec3 wo_, float u_lobe,
               PatinaVec2 u, const PatinaWavelengths* wl, PatinaBsdfSample* out)
    {
        const auto& s = *static_cast<const StoneSurface*>(instance);
        const Vec3 wo = wo_;
        if (wo.z == 0.0f || !is_finite(wo))
            return 0;
        const float R = reflected_fraction(s, cos_theta(wo));
        if (u_lobe < R) {
            // Reflected part F_r^k, mirror direction: f = R/|cos θi| against probability R
            const Vec3 wi(-wo.x, -wo.y, wo.z);
            fill(R / abs_cos_theta(wi), *wl, out->f);
            out->wi = wi;
            out->pdf = R;
            out->lobe = PATINA_LOBE_REFLECTION | PATINA_LOBE_SPECULAR;
            out->eta = 1.0f;
            return 1;
        }
        const float T = 1.0f - R;
        if (s.diffuse) {
            // The remaining 1 − F_r^k crosses cosine-distributed on the other side
            Vec3 wi = sample_cosine_hemisphere(Vec2(u));
            if (wo.z > 0.0f)
                wi.z = -wi.z;
            if (!(T > 0.0f) || wi.z == 0.0f)
                return 0;
            fill(diffuse_transmission(s, wo), *wl, out->f);
            out->wi = wi;
            out->pdf = T * abs_cos_theta(wi) * kInvPi;
            out->lobe = PATINA_LOBE_TRANSMISSION | PATINA_LOBE_DIFFUSE;
            out->eta = crossing_eta(s, cos_theta(wo));
            return 1;
        }
        // The remaining 1 − F_r^k refracts into (or out of) the stone by Snell's law
        Vec3 wi;
        float etap = 1.0f;
        if (!(T > 0.0f) || !refract(wo, Vec3(0.0f, 0.0f, 1.0f), s.eta, &etap, &wi) || wi.z == 0.0f)
            return 0;
        fill(T / abs_cos_theta(wi), *wl, out->f);
        out->wi = wi;
        out->pdf = T;
        out->lobe = PATINA_LOBE_TRANSMISSION | PATINA_LOBE_SPECULAR;
        out->eta = etap;
        return 1;
    }

    void albedo(const void*, const PatinaShadingContext*, PatinaVec3, const PatinaWavelengths* wl,
                float* a)
    {
        // Reflection plus transmission: all of the light goes on somewhere
        fill(1.0f, *wl, a);
    }

    const PatinaBsdfFuncs kFuncs = {eval, pdf, sample, albedo};

} // namespace

PatinaShaderDesc stone_surface_shader()
{
    return describe(
        kName,
        "Boundary of a stone medium (Dorsey et al. 1999 Sec. 5.1): reflects F_r^k of the light, "
        "F_r the Fresnel reflectance and k a roughness exponent, and refracts the rest.",
        kParams, create, destroy, kFuncs);
}

} // namespace patina::slab_volume
