#include "render/integrator.h"

#include "render/area_light.h"
#include "render/environment_light.h"
#include "render/light_sampler.h"
#include "render/transmittance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace patina::render {

namespace {

    constexpr float kInf = std::numeric_limits<float>::infinity();
    // Index-matched boundaries crossed without scattering do not count as bounces; this
    // bounds them so a degenerate mesh cannot loop forever.
    constexpr int kMaxPassThrough = 256;

    PatinaVec3 to_abi(const Imath::V3f& v) { return {v.x, v.y, v.z}; }
    Imath::V3f from_abi(const PatinaVec3& v) { return {v.x, v.y, v.z}; }
    // v / |v| with one square root and one division (Imath's normalized() divides thrice and
    // checks for tiny vectors); v must not be 0.
    Imath::V3f unit(const Imath::V3f& v) { return v * (1.0f / std::sqrt(v.dot(v))); }

    // What the previous scattering vertex knows, for MIS weights of emission found by BSDF
    // or phase sampling (pbrt-v4 §13.4 and §14.2, VolPathIntegrator).
    struct PrevVertex {
        Imath::V3f P{0, 0, 0};
        float pdf = 0.0f;      // solid-angle pdf of the direction it sampled
        bool specular = true;  // camera ray or delta lobe: no light sampling competed
    };

    float emission_mis_weight(const Scene& scene, const PrevVertex& prev, float light_pdf)
    {
        if (prev.specular || !scene.film.mis)
            return 1.0f;
        return power_heuristic(1, prev.pdf, 1, light_pdf);
    }

    // How a scattering vertex (a surface BSDF or a medium's phase function) answers NEE.
    struct Scatterer {
        const ShaderInstance* shader;
        const PatinaShadingContext* ctx;
        const ShadingFrame* frame;  // null for a medium point (world-space directions)
        PatinaVec3 wo;

        // Value (times |cos| on surfaces) and pdf of scattering towards world direction wi;
        // the pdf is left at 0 when the value is 0 (the sample is dropped).
        float eval(const Imath::V3f& wi, const PatinaWavelengths& wl, SampledSpectrum& f) const
        {
            float v[PATINA_MAX_WAVELENGTHS] = {};
            if (frame) {
                const PatinaVec3 wl_i = to_abi(frame->to_local(wi));
                shader->bsdf()->eval(shader->get(), ctx, wo, wl_i, &wl, v);
                f = SampledSpectrum::from_lanes(wl.count, v) * std::abs(wl_i.z);
                if (f.is_black())
                    return 0.0f;
                return shader->bsdf()->pdf(shader->get(), ctx, wo, wl_i, &wl);
            }
            const float pdf = shader->medium()->phase_eval(shader->get(), ctx, wo, to_abi(wi), &wl, v);
            f = SampledSpectrum::from_lanes(wl.count, v);
            return pdf;
        }
    };

    // A constant environment's radiance at the path's wavelengths, evaluated once per path
    // (it is the same for every direction and every vertex), with its selection probability.
    struct UniformSky {
        const EnvironmentLight* light = nullptr;
        SampledSpectrum L;
        float pmf = 0.0f;
        bool black = true;  // L is 0 at every wavelength (or there is no uniform sky)

        UniformSky(const Scene& scene, const PatinaWavelengths& wl, const SampledSpectrum& d65)
            : light(scene.lights.uniform_sky())
        {
            if (light) {
                L = light->constant_radiance(wl, d65);
                pmf = scene.lights.uniform_sky_pmf();
                black = L.is_black();
            }
        }
    };

    // Next-event estimation: one light chosen by power, one direction on it, transmittance
    // to it through the media on the way.
    // `sp` is the surface point (null at a medium point) and `obj` its object; `medium` is
    // the one the path arrived in, along `incoming`.
    [[gnu::target_clones("avx2", "default")]]  // as trace_path below
    SampledSpectrum sample_direct(const Scene& scene, const Scatterer& at, const Imath::V3f& P,
                                  const SurfacePoint* sp, const SceneObject* obj,
                                  const Imath::V3f& incoming, const ShaderInstance* medium,
                                  const PatinaWavelengths& wl, const UniformSky& sky, Pcg32& rng)
    {
        const float u_light = rng.uniform_float();
        const Imath::V2f u{rng.uniform_float(), rng.uniform_float()};
        const auto chosen = scene.lights.sample(u_light);
        if (!chosen)
            return SampledSpectrum(wl.count, 0.0f);
        // The uniform sky's sample refers to its radiance, taken once per path; other lights
        // sample into `other`.
        std::optional<LightSample> other;
        Imath::V3f wi;
        float distance = kInf, pdf = EnvironmentLight::kUniformSpherePdf;
        const SampledSpectrum* Le = &sky.L;
        bool is_delta = false;
        if (chosen->light == sky.light) {
            if (sky.black)
                return SampledSpectrum(wl.count, 0.0f);
            wi = EnvironmentLight::sample_uniform_sphere(u);
        } else {
            other = chosen->light->sample(P, u, wl);
            if (!other || !(other->pdf > 0.0f) || other->L.is_black())
                return SampledSpectrum(wl.count, 0.0f);
            wi = other->wi;
            distance = other->distance;
            pdf = other->pdf;
            Le = &other->L;
            is_delta = other->is_delta;
        }
        SampledSpectrum f;
        const float scatter_pdf = at.eval(wi, wl, f);
        if (f.is_black())
            return SampledSpectrum(wl.count, 0.0f);
        // Leaving a surface, the shadow ray starts on the side it goes to, in the medium of
        // that side (the interior when it passes through); from a medium point it starts
        // where it is.
        Imath::V3f origin = P;
        const ShaderInstance* start_medium = medium;
        if (sp) {
            origin = offset_ray_origin(*sp, wi);
            if (wi.dot(sp->Ng) * incoming.dot(sp->Ng) > 0.0f)
                start_medium = medium_after_crossing(*obj, sp->Ng, wi, medium);
        }
        if (!std::isinf(distance))
            distance *= 1.0f - 1e-4f;
        const float light_pdf = chosen->pmf * pdf;
        const float weight = is_delta ? 1.0f : power_heuristic(1, light_pdf, 1, scatter_pdf);
        if (!scene.has_media) {
            // Without media the transmittance is 1 or 0: one occlusion query (what
            // transmittance_along does then), and no multiplication by ones.
            if (scene.geometry->occluded(origin, wi, 0.0f, distance))
                return SampledSpectrum(wl.count, 0.0f);
            return f * *Le * (weight / light_pdf);
        }
        const SampledSpectrum tr =
            transmittance_along(scene, origin, wi, distance, start_medium, wl, rng);
        if (tr.is_black())
            return SampledSpectrum(wl.count, 0.0f);
        return f * tr * *Le * (weight / light_pdf);
    }

    SampledSpectrum escaped(const Scene& scene, const Ray& ray, const PrevVertex& prev,
                            const PatinaWavelengths& wl, const UniformSky& sky)
    {
        SampledSpectrum L(wl.count, 0.0f);
        for (const Light* light : scene.lights.infinite_lights()) {
            if (light == sky.light) {
                if (!sky.black)
                    L += sky.L * emission_mis_weight(scene, prev,
                                                     sky.pmf * EnvironmentLight::kUniformSpherePdf);
                continue;
            }
            const SampledSpectrum Le = light->escaped_radiance(ray.dir, wl);
            if (Le.is_black())
                continue;
            const float light_pdf = scene.lights.pmf(light) * light->pdf(prev.P, ray.dir);
            L += Le * emission_mis_weight(scene, prev, light_pdf);
        }
        return L;
    }

    // Russian roulette once the path has some length (pbrt-v4 §13.3: on the largest
    // throughput component, so bright paths survive). False ends the path.
    bool survive_roulette(int depth, SampledSpectrum& beta, Pcg32& rng)
    {
        if (depth < 3)
            return true;
        const float q = std::max(0.05f, 1.0f - beta.max_value());
        if (rng.uniform_float() < q)
            return false;
        beta /= 1.0f - q;
        return true;
    }

}  // namespace

SampledSpectrum trace_path(const Scene& scene, Ray ray, const PatinaWavelengths& wl,
                           const CieAtWavelengths& cie, SampledSpectrum& pdf, Pcg32& rng,
                           PathAovs* aovs)
{
    const std::optional<Hit> first_hit = scene.geometry->intersect(ray.origin, ray.dir, 0.0f, kInf);
    return trace_path(scene, ray, first_hit, wl, cie, pdf, rng, aovs);
}

// AVX2 and baseline clones, chosen at load time: an 8-lane SampledSpectrum operation is one
// AVX instruction instead of two SSE ones. No FMA (the "avx2" target does not enable it), so
// every operation rounds as in the baseline clone: the same bits on either (checked on the
// bench scene against a baseline-only build: identical pixels; callgrind -49 per sample).
[[gnu::target_clones("avx2", "default")]]
SampledSpectrum trace_path(const Scene& scene, Ray ray, const std::optional<Hit>& first_hit,
                           const PatinaWavelengths& wl, const CieAtWavelengths& cie,
                           SampledSpectrum& pdf, Pcg32& rng, PathAovs* aovs)
{
    SampledSpectrum L(wl.count, 0.0f), beta(wl.count, 1.0f);
    bool secondaries_terminated = false;
    PrevVertex prev;
    const UniformSky sky(scene, wl, cie.d65);
    const ShaderInstance* medium = nullptr;  // the camera is in vacuum
    int pass_through = 0;
    bool first_segment = true;
    for (int depth = 0;;) {
        const std::optional<Hit> hit = first_segment
                                           ? first_hit
                                           : scene.geometry->intersect(ray.origin, ray.dir, 0.0f, kInf);
        first_segment = false;

        // In a medium: a free flight up to the next surface, maybe ending in a scattering.
        if (medium) {
            PatinaShadingContext mctx{};
            mctx.P = to_abi(ray.origin);
            float t = 0.0f, weight[PATINA_MAX_WAVELENGTHS] = {};
            const int scattered = medium->medium()->sample_distance(
                medium->get(), &mctx, mctx.P, to_abi(ray.dir), hit ? hit->t : kInf,
                rng.uniform_float(), &wl, &t, weight);
            beta *= SampledSpectrum::from_lanes(wl.count, weight);
            if (beta.is_black())
                break;
            if (scattered) {
                const Imath::V3f P = ray.origin + t * ray.dir;
                if (depth >= scene.film.max_depth)
                    break;
                mctx.P = to_abi(P);
                const PatinaVec3 wo = to_abi(-ray.dir);
                const Scatterer phase{medium, &mctx, nullptr, wo};
                if (scene.film.mis)
                    L += beta * sample_direct(scene, phase, P, nullptr, nullptr, ray.dir, medium,
                                              wl, sky, rng);
                PatinaVec3 wi{};
                float p[PATINA_MAX_WAVELENGTHS] = {};
                const Imath::V2f u{rng.uniform_float(), rng.uniform_float()};
                const float phase_pdf = medium->medium()->phase_sample(
                    medium->get(), &mctx, wo, {u.x, u.y}, &wl, &wi, p);
                if (!(phase_pdf > 0.0f))
                    break;
                beta *= SampledSpectrum::from_lanes(wl.count, p) / phase_pdf;
                prev = {P, phase_pdf, false};
                ++depth;
                if (beta.is_black() || !survive_roulette(depth, beta, rng))
                    break;
                ray = {P, from_abi(wi).normalized()};
                continue;
            }
        }

        // Paths that escape see the infinite lights.
        if (!hit) {
            L += beta * escaped(scene, ray, prev, wl, sky);
            break;
        }
        SurfacePoint sp;
        const bool orthonormal = scene.geometry->interpolate_shading(*hit, ray.dir, sp);
        const SceneObject& obj =
            scene.objects[static_cast<size_t>(scene.mesh_object[static_cast<size_t>(hit->mesh_id)])];

        // An index-matched medium boundary: cross it without scattering.
        if (!obj.bsdf && obj.interior && !obj.emitter) {
            if (++pass_through > kMaxPassThrough)
                break;
            medium = medium_after_crossing(obj, sp.Ng, ray.dir, medium);
            ray.origin = offset_ray_origin(sp, ray.dir);
            continue;
        }

        const ShadingFrame frame = make_shading_frame(sp, orthonormal);
        const PatinaVec3 wo = to_abi(frame.to_local(-ray.dir));
        if (depth == 0 && aovs) {
            aovs->hit = true;
            aovs->normal = sp.N;
            aovs->depth = hit->t;
            aovs->albedo = SampledSpectrum(wl.count, 0.0f);
            if (obj.bsdf && obj.bsdf->bsdf()->albedo) {
                float a[PATINA_MAX_WAVELENGTHS] = {};
                obj.bsdf->bsdf()->albedo(obj.bsdf->get(), &frame.ctx, wo, &wl, a);
                aovs->albedo = SampledSpectrum::from_lanes(wl.count, a);
            }
        }

        // Emission found by the path, weighted against light sampling of the same mesh.
        if (obj.emitter) {
            float le[PATINA_MAX_WAVELENGTHS] = {};
            obj.emitter->emitter()->emit(obj.emitter->get(), &frame.ctx, wo, &wl, le);
            const SampledSpectrum Le = SampledSpectrum::from_lanes(wl.count, le);
            if (!Le.is_black()) {
                float light_pdf = 0.0f;
                if (const AreaLight* area = scene.lights.area_light_for_mesh(hit->mesh_id)) {
                    const LightHit lh{sp.P, sp.Ng, hit->prim_id};
                    light_pdf = scene.lights.pmf(area) * area->pdf(prev.P, ray.dir, &lh);
                }
                L += beta * Le * emission_mis_weight(scene, prev, light_pdf);
            }
        }
        if (!obj.bsdf || depth >= scene.film.max_depth)
            break;

        // Light sampling at this vertex. The shadow ray leaves on the light's side: the
        // medium there is this one unless it crosses into the object's interior.
        if (scene.film.mis) {
            const Scatterer surface{obj.bsdf.get(), &frame.ctx, &frame, wo};
            L += beta * sample_direct(scene, surface, sp.P, &sp, &obj, ray.dir, medium, wl, sky,
                                      rng);
        }

        // Sample the BSDF for the next direction.
        PatinaBsdfSample bs{};
        const PatinaVec2 u{rng.uniform_float(), rng.uniform_float()};
        const float u_lobe = rng.uniform_float();
        if (!obj.bsdf->bsdf()->sample(obj.bsdf->get(), &frame.ctx, wo, u_lobe, u, &wl, &bs) ||
            !(bs.pdf > 0.0f))
            break;
        beta *= SampledSpectrum::from_lanes(wl.count, bs.f) * (std::abs(bs.wi.z) / bs.pdf);
        if ((bs.lobe & PATINA_LOBE_WAVELENGTH_DEPENDENT) && !secondaries_terminated &&
            wl.count > 1) {
            // Only the hero wavelength follows a dispersed direction.
            for (int i = 1; i < wl.count; ++i)
                pdf[i] = 0.0f;
            pdf[0] /= static_cast<float>(wl.count);
            secondaries_terminated = true;
        }
        prev = {sp.P, bs.pdf, (bs.lobe & PATINA_LOBE_SPECULAR) != 0};
        ++depth;
        if (beta.is_black() || !survive_roulette(depth, beta, rng))
            break;

        const Imath::V3f wi_world = unit(frame.to_world(from_abi(bs.wi)));
        // Transmission through the surface moves the path into or out of the interior.
        if (wi_world.dot(sp.Ng) * ray.dir.dot(sp.Ng) > 0.0f)
            medium = medium_after_crossing(obj, sp.Ng, wi_world, medium);
        ray.origin = offset_ray_origin(sp, wi_world);
        ray.dir = wi_world;
    }
    return L;
}

}  // namespace patina::render
