#include "render/integrator.h"

#include "render/area_light.h"
#include "render/light_sampler.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace patina::render {

namespace {

    PatinaVec3 to_abi(const Imath::V3f& v) { return {v.x, v.y, v.z}; }
    Imath::V3f from_abi(const PatinaVec3& v) { return {v.x, v.y, v.z}; }

    // What the previous vertex of the path knows, for MIS weights of emission found by BSDF
    // sampling (pbrt-v4 §13.4, PathIntegrator).
    struct PrevVertex {
        Imath::V3f P{0, 0, 0};
        float bsdf_pdf = 0.0f;
        bool specular = true;  // the camera ray and delta lobes: no light sampling competed
    };

    // Weight of a BSDF-sampled path that found emission whose light-sampling density is
    // light_pdf (already multiplied by the light's selection probability).
    float bsdf_mis_weight(const Scene& scene, const PrevVertex& prev, float light_pdf)
    {
        if (prev.specular || !scene.film.mis)
            return 1.0f;
        return power_heuristic(1, prev.bsdf_pdf, 1, light_pdf);
    }

    // Next-event estimation: one light chosen by power, one direction on it, a shadow ray.
    SampledSpectrum sample_direct(const Scene& scene, const ShadingFrame& frame,
                                  const SurfacePoint& sp, const SceneObject& obj, PatinaVec3 wo,
                                  const PatinaWavelengths& wl, Pcg32& rng)
    {
        SampledSpectrum none(wl.count, 0.0f);
        const float u_light = rng.uniform_float();
        const Imath::V2f u{rng.uniform_float(), rng.uniform_float()};
        const auto chosen = scene.lights.sample(u_light);
        if (!chosen)
            return none;
        const auto ls = chosen->light->sample(sp.P, u, wl);
        if (!ls || !(ls->pdf > 0.0f) || ls->L.is_black())
            return none;
        const PatinaVec3 wi = to_abi(frame.to_local(ls->wi));
        float f[PATINA_MAX_WAVELENGTHS] = {};
        obj.bsdf->bsdf()->eval(obj.bsdf->get(), &frame.ctx, wo, wi, &wl, f);
        const SampledSpectrum fs = SampledSpectrum::from_array(wl.count, f);
        if (fs.is_black())
            return none;
        // Shadow ray to the light, stopping just short of a sampled point on it.
        const Imath::V3f origin = offset_ray_origin(sp, ls->wi);
        const float t_max = std::isinf(ls->distance) ? std::numeric_limits<float>::infinity()
                                                     : ls->distance * (1.0f - 1e-4f);
        if (scene.geometry->occluded(origin, ls->wi, 0.0f, t_max))
            return none;
        const float light_pdf = chosen->pmf * ls->pdf;
        float weight = 1.0f;
        if (!ls->is_delta) {
            const float bsdf_pdf = obj.bsdf->bsdf()->pdf(obj.bsdf->get(), &frame.ctx, wo, wi, &wl);
            weight = power_heuristic(1, light_pdf, 1, bsdf_pdf);
        }
        return fs * ls->L * (std::abs(wi.z) * weight / light_pdf);
    }

}  // namespace

SampledSpectrum trace_path(const Scene& scene, Ray ray, const PatinaWavelengths& wl,
                           SampledSpectrum& pdf, Pcg32& rng, PathAovs* aovs)
{
    SampledSpectrum L(wl.count, 0.0f), beta(wl.count, 1.0f);
    bool secondaries_terminated = false;
    PrevVertex prev;
    for (int depth = 0;; ++depth) {
        // Find the next surface; paths that escape see the infinite lights.
        const auto hit = scene.geometry->intersect(ray.origin, ray.dir, 0.0f,
                                                   std::numeric_limits<float>::infinity());
        if (!hit) {
            for (const Light* light : scene.lights.infinite_lights()) {
                const SampledSpectrum Le = light->escaped_radiance(ray.dir, wl);
                if (Le.is_black())
                    continue;
                const float light_pdf = scene.lights.pmf(light) * light->pdf(prev.P, ray.dir);
                L += beta * Le * bsdf_mis_weight(scene, prev, light_pdf);
            }
            break;
        }
        const SurfacePoint sp = scene.geometry->interpolate(*hit, ray.origin, ray.dir);
        const SceneObject& obj =
            scene.objects[static_cast<size_t>(scene.mesh_object[static_cast<size_t>(hit->mesh_id)])];
        const ShadingFrame frame = make_shading_frame(sp);
        const PatinaVec3 wo = to_abi(frame.to_local(-ray.dir));
        if (depth == 0 && aovs) {
            aovs->hit = true;
            aovs->normal = sp.N;
            aovs->depth = hit->t;
            aovs->albedo = SampledSpectrum(wl.count, 0.0f);
            if (obj.bsdf && obj.bsdf->bsdf()->albedo) {
                float a[PATINA_MAX_WAVELENGTHS] = {};
                obj.bsdf->bsdf()->albedo(obj.bsdf->get(), &frame.ctx, wo, &wl, a);
                aovs->albedo = SampledSpectrum::from_array(wl.count, a);
            }
        }

        // Emission found by the path, weighted against light sampling of the same mesh.
        if (obj.emitter) {
            float le[PATINA_MAX_WAVELENGTHS] = {};
            obj.emitter->emitter()->emit(obj.emitter->get(), &frame.ctx, wo, &wl, le);
            const SampledSpectrum Le = SampledSpectrum::from_array(wl.count, le);
            if (!Le.is_black()) {
                float light_pdf = 0.0f;
                if (const AreaLight* area = scene.lights.area_light_for_mesh(hit->mesh_id)) {
                    const LightHit lh{sp.P, sp.Ng, hit->prim_id};
                    light_pdf = scene.lights.pmf(area) * area->pdf(prev.P, ray.dir, &lh);
                }
                L += beta * Le * bsdf_mis_weight(scene, prev, light_pdf);
            }
        }
        if (!obj.bsdf || depth >= scene.film.max_depth)
            break;

        // Light sampling at this vertex.
        if (scene.film.mis)
            L += beta * sample_direct(scene, frame, sp, obj, wo, wl, rng);

        // Sample the BSDF for the next direction.
        PatinaBsdfSample bs{};
        const PatinaVec2 u{rng.uniform_float(), rng.uniform_float()};
        const float u_lobe = rng.uniform_float();
        if (!obj.bsdf->bsdf()->sample(obj.bsdf->get(), &frame.ctx, wo, u_lobe, u, &wl, &bs) ||
            !(bs.pdf > 0.0f))
            break;
        const float cos_i = std::abs(bs.wi.z);
        for (int i = 0; i < wl.count; ++i)
            beta[i] *= bs.f[i] * cos_i / bs.pdf;
        if ((bs.lobe & PATINA_LOBE_WAVELENGTH_DEPENDENT) && !secondaries_terminated &&
            wl.count > 1) {
            // Only the hero wavelength follows a dispersed direction.
            for (int i = 1; i < wl.count; ++i)
                pdf[i] = 0.0f;
            pdf[0] /= static_cast<float>(wl.count);
            secondaries_terminated = true;
        }
        if (beta.is_black())
            break;
        prev = {sp.P, bs.pdf, (bs.lobe & PATINA_LOBE_SPECULAR) != 0};

        // Russian roulette once the path has some length (pbrt-v4 §13.3: on the largest
        // throughput component, so bright paths survive).
        if (depth >= 3) {
            const float q = std::max(0.05f, 1.0f - beta.max_value());
            if (rng.uniform_float() < q)
                break;
            beta /= 1.0f - q;
        }

        const Imath::V3f wi_world = frame.to_world(from_abi(bs.wi)).normalized();
        ray.origin = offset_ray_origin(sp, wi_world);
        ray.dir = wi_world;
    }
    return L;
}

}  // namespace patina::render
