#include "render/integrator.h"

#include "core/rgb_spectrum.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace patina::render {

namespace {

    PatinaVec3 to_abi(const Imath::V3f& v) { return {v.x, v.y, v.z}; }
    Imath::V3f from_abi(const PatinaVec3& v) { return {v.x, v.y, v.z}; }

    SampledSpectrum environment_radiance(const Scene& scene, const PatinaWavelengths& wl)
    {
        return SampledSpectrum::from_function(wl, [&](float l) {
            return scene.environment_intensity * RgbToSpectrum::eval(scene.environment, l);
        });
    }

}  // namespace

SampledSpectrum trace_path(const Scene& scene, Ray ray, const PatinaWavelengths& wl,
                           SampledSpectrum& pdf, Pcg32& rng, PathAovs* aovs)
{
    SampledSpectrum L(wl.count, 0.0f), beta(wl.count, 1.0f);
    bool secondaries_terminated = false;
    for (int depth = 0; depth < scene.film.max_depth; ++depth) {
        // Find the next surface; paths that escape see the environment.
        const auto hit = scene.geometry->intersect(ray.origin, ray.dir, 0.0f,
                                                   std::numeric_limits<float>::infinity());
        if (!hit) {
            L += beta * environment_radiance(scene, wl);
            break;
        }
        const SurfacePoint sp = scene.geometry->interpolate(*hit, ray.origin, ray.dir);
        const SceneObject& obj = scene.objects[static_cast<size_t>(scene.mesh_object[static_cast<size_t>(hit->mesh_id)])];
        const ShadingFrame frame = make_shading_frame(sp);
        const Imath::V3f wo_world = -ray.dir;
        const PatinaVec3 wo = to_abi(frame.to_local(wo_world));
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

        // Emission seen by the path.
        if (obj.emitter) {
            float le[PATINA_MAX_WAVELENGTHS] = {};
            obj.emitter->emitter()->emit(obj.emitter->get(), &frame.ctx, wo, &wl, le);
            L += beta * SampledSpectrum::from_array(wl.count, le);
        }
        if (!obj.bsdf)
            break;

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

        // Russian roulette once the path has some length (pbrt-v4 style, on the max
        // throughput so bright paths survive).
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
