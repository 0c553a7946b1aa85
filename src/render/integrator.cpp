#include "render/integrator.h"

#include "render/area_light.h"
#include "render/environment_light.h"
#include "render/light_sampler.h"
#include "render/path_common.h"
#include "render/transmittance.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace patina::render {

namespace {

    using namespace path;
    // Index-matched boundaries crossed without scattering do not count as bounces; this
    // bounds them so a degenerate mesh cannot loop forever.
    constexpr int kMaxPassThrough = 256;

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
    float eta_scale = 1.0f;  // η'² over the boundaries crossed: survive_roulette
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
                if (scene.film.mis && scene.lights.has_sampled_lights())
                    L += clamp_indirect(beta * sample_direct(scene, phase, P, nullptr, nullptr,
                                                             ray.dir, medium, wl, sky, rng),
                                        depth + 1, scene.film.clamp_indirect);
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
                if (beta.is_black() || !survive_roulette(depth, beta, eta_scale, rng))
                    break;
                ray = {P, from_abi(wi).normalized()};
                continue;
            }
        }

        // Paths that escape see the infinite lights.
        if (!hit) {
            L += clamp_indirect(beta * escaped(scene, ray, prev, wl, sky), depth,
                                scene.film.clamp_indirect);
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
                L += clamp_indirect(beta * Le * emission_mis_weight(scene, prev, light_pdf),
                                    depth, scene.film.clamp_indirect);
            }
        }
        if (!obj.bsdf || depth >= scene.film.max_depth)
            break;

        // Light sampling at this vertex. The shadow ray leaves on the light's side: the
        // medium there is this one unless it crosses into the object's interior.
        if (scene.film.mis && scene.lights.has_sampled_lights()) {
            const Scatterer surface{obj.bsdf.get(), &frame.ctx, &frame, wo};
            L += clamp_indirect(beta * sample_direct(scene, surface, sp.P, &sp, &obj, ray.dir,
                                                     medium, wl, sky, rng),
                                depth + 1, scene.film.clamp_indirect);
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
        eta_scale *= eta_scale_of(bs);
        ++depth;
        if (beta.is_black() || !survive_roulette(depth, beta, eta_scale, rng))
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
