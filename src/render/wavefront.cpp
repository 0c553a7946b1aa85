#include "render/wavefront.h"

#include "render/area_light.h"
#include "render/environment_light.h"
#include "render/light_sampler.h"

#include <cassert>
#include <cmath>

namespace patina::render {

namespace {

    using namespace path;

    // What became of a vertex's light sample: not taken (MIS off, or the path ended
    // before it), a zero value (still added, as trace_path adds beta * 0), or a value that
    // waits for its shadow ray.
    enum class LightSampleState { none, zero, shadow_ray };

    // The hit's part of a bounce (trace_path's loop body from the hit test to the new ray,
    // no media): emission, the light sample (its shadow ray left in `shadow` when one is
    // needed, its value in p.nee_*), the BSDF sample and roulette. True if the path goes
    // on with p.ray; false when it ended (a light sample may still wait for its shadow ray).
    [[gnu::target_clones("avx2", "default")]]  // as trace_path: same bits on either
    bool shade(const Scene& scene, WavefrontPath& p, const std::optional<Hit>& found,
               bool want_aovs, ShadowRay& shadow, LightSampleState& nee)
    {
        nee = LightSampleState::none;
        const PatinaWavelengths& wl = p.wl;
        if (!found) {
            p.L += clamp_indirect(p.beta * escaped(scene, p.ray, p.prev, wl, p.sky), p.depth,
                                  scene.film.clamp_indirect);
            return false;
        }
        const Hit& hit = *found;
        SurfacePoint sp;
        const bool orthonormal = scene.geometry->interpolate_shading(hit, p.ray.dir, sp);
        const SceneObject& obj =
            scene.objects[static_cast<size_t>(scene.mesh_object[static_cast<size_t>(hit.mesh_id)])];
        assert(!obj.interior);  // wavefront_supported: no media

        const ShadingFrame frame = make_shading_frame(sp, orthonormal);
        const PatinaVec3 wo = to_abi(frame.to_local(-p.ray.dir));
        if (p.depth == 0 && want_aovs) {
            p.aov.hit = true;
            p.aov.normal = sp.N;
            p.aov.depth = hit.t;
            p.aov.albedo = SampledSpectrum(wl.count, 0.0f);
            if (obj.bsdf && obj.bsdf->bsdf()->albedo) {
                float a[PATINA_MAX_WAVELENGTHS] = {};
                obj.bsdf->bsdf()->albedo(obj.bsdf->get(), &frame.ctx, wo, &wl, a);
                p.aov.albedo = SampledSpectrum::from_lanes(wl.count, a);
            }
        }

        // Emission found by the path, weighted against light sampling of the same mesh.
        if (obj.emitter) {
            float le[PATINA_MAX_WAVELENGTHS] = {};
            obj.emitter->emitter()->emit(obj.emitter->get(), &frame.ctx, wo, &wl, le);
            const SampledSpectrum Le = SampledSpectrum::from_lanes(wl.count, le);
            if (!Le.is_black()) {
                float light_pdf = 0.0f;
                if (const AreaLight* area = scene.lights.area_light_for_mesh(hit.mesh_id)) {
                    const LightHit lh{sp.P, sp.Ng, hit.prim_id};
                    light_pdf = scene.lights.pmf(area) * area->pdf(p.prev.P, p.ray.dir, &lh);
                }
                p.L += clamp_indirect(p.beta * Le * emission_mis_weight(scene, p.prev, light_pdf),
                                      p.depth, scene.film.clamp_indirect);
            }
        }
        if (!obj.bsdf || p.depth >= scene.film.max_depth)
            return false;

        // Light sampling (sample_direct without media): the value is worked out now, the
        // shadow ray traced with the batch's others; L gets beta * (value or 0) then.
        if (scene.film.mis && scene.lights.has_sampled_lights()) {
            nee = LightSampleState::zero;
            p.nee_beta = p.beta;
            p.nee_value = SampledSpectrum(wl.count, 0.0f);
            p.nee_bounces = p.depth + 1;
            const Scatterer at{obj.bsdf.get(), &frame.ctx, &frame, wo};
            const float u_light = p.rng.uniform_float();
            const Imath::V2f u{p.rng.uniform_float(), p.rng.uniform_float()};
            const auto chosen = scene.lights.sample(u_light);
            std::optional<LightSample> other;
            Imath::V3f wi;
            float distance = kInf, pdf = EnvironmentLight::kUniformSpherePdf;
            const SampledSpectrum* Le = &p.sky.L;
            bool is_delta = false, usable = chosen.has_value();
            if (usable && chosen->light == p.sky.light) {
                usable = !p.sky.black;
                if (usable)
                    wi = EnvironmentLight::sample_uniform_sphere(u);
            } else if (usable) {
                other = chosen->light->sample(sp.P, u, wl);
                usable = other && other->pdf > 0.0f && !other->L.is_black();
                if (usable) {
                    wi = other->wi;
                    distance = other->distance;
                    pdf = other->pdf;
                    Le = &other->L;
                    is_delta = other->is_delta;
                }
            }
            if (usable) {
                SampledSpectrum f;
                const float scatter_pdf = at.eval(wi, wl, f);
                if (!f.is_black()) {
                    if (!std::isinf(distance))
                        distance *= 1.0f - 1e-4f;
                    const float light_pdf = chosen->pmf * pdf;
                    const float weight =
                        is_delta ? 1.0f : power_heuristic(1, light_pdf, 1, scatter_pdf);
                    p.nee_value = f * *Le * (weight / light_pdf);
                    shadow = {offset_ray_origin(sp, wi), wi, distance};
                    nee = LightSampleState::shadow_ray;
                }
            }
        }

        // Sample the BSDF for the next direction.
        PatinaBsdfSample bs{};
        const PatinaVec2 u{p.rng.uniform_float(), p.rng.uniform_float()};
        const float u_lobe = p.rng.uniform_float();
        if (!obj.bsdf->bsdf()->sample(obj.bsdf->get(), &frame.ctx, wo, u_lobe, u, &wl, &bs) ||
            !(bs.pdf > 0.0f))
            return false;
        p.beta *= SampledSpectrum::from_lanes(wl.count, bs.f) * (std::abs(bs.wi.z) / bs.pdf);
        if ((bs.lobe & PATINA_LOBE_WAVELENGTH_DEPENDENT) && !p.secondaries_terminated &&
            wl.count > 1) {
            // Only the hero wavelength follows a dispersed direction.
            for (int i = 1; i < wl.count; ++i)
                p.pdf[i] = 0.0f;
            p.pdf[0] /= static_cast<float>(wl.count);
            p.secondaries_terminated = true;
        }
        p.prev = {sp.P, bs.pdf, (bs.lobe & PATINA_LOBE_SPECULAR) != 0};
        p.eta_scale *= eta_scale_of(bs);
        ++p.depth;
        if (p.beta.is_black() || !survive_roulette(p.depth, p.beta, p.eta_scale, p.rng))
            return false;
        const Imath::V3f wi_world = unit(frame.to_world(from_abi(bs.wi)));
        p.ray.origin = offset_ray_origin(sp, wi_world);
        p.ray.dir = wi_world;
        return true;
    }

    // The light sample's contribution once its shadow ray is answered: trace_path's
    // L += beta * sample_direct(...), with a zero value when occluded.
    [[gnu::target_clones("avx2", "default")]]
    void add_light_sample(WavefrontPath& p, bool visible, float clamp)
    {
        p.L += clamp_indirect(
            p.nee_beta * (visible ? p.nee_value : SampledSpectrum(p.wl.count, 0.0f)),
            p.nee_bounces, clamp);
    }

}  // namespace

void trace_wavefront(const Scene& scene, std::span<WavefrontPath> paths, bool want_aovs,
                     WavefrontScratch& s)
{
    const size_t n = paths.size();
    s.live.resize(n);
    for (size_t i = 0; i < n; ++i) {
        WavefrontPath& p = paths[i];
        p.L = SampledSpectrum(p.wl.count, 0.0f);
        p.beta = SampledSpectrum(p.wl.count, 1.0f);
        p.secondaries_terminated = false;
        p.prev = PrevVertex{};
        p.sky = UniformSky(scene, p.wl, p.cie.d65);
        p.depth = 0;
        p.eta_scale = 1.0f;
        if (want_aovs)
            p.aov = PathAovs{};
        s.live[i] = static_cast<uint32_t>(i);
    }
    s.shadows.resize(n);
    s.shadow_owner.resize(n);
    s.visible.resize(n);
    s.queries.resize(n);
    s.hits.resize(n);
    s.next.resize(n);
    size_t nlive = n;
    for (bool camera_hits = true; nlive > 0; camera_hits = false) {
        // Shade every live path's hit; collect the shadow rays, and the paths that go on
        // with their next rays (written while the path is at hand, not in a pass of its own).
        // After the camera's hits, the k-th live path's hit is hits[k], where the last
        // stream left it: read there, not copied into the (cold) path state first.
        size_t nshadow = 0, m = 0;
        for (size_t k = 0; k < nlive; ++k) {
            const uint32_t i = s.live[k];
            WavefrontPath& p = paths[i];
            LightSampleState nee;
            const std::optional<Hit>& hit = camera_hits ? p.hit : s.hits[k];
            if (shade(scene, p, hit, want_aovs, s.shadows[nshadow], nee)) {
                s.queries[m] = {p.ray.origin, p.ray.dir, 0.0f, kInf};
                s.next[m++] = i;
            }
            if (nee == LightSampleState::shadow_ray)
                s.shadow_owner[nshadow++] = i;
            else if (nee == LightSampleState::zero)
                add_light_sample(p, false, scene.film.clamp_indirect);
        }
        scene.geometry->trace_shadow_rays(std::span(s.shadows.data(), nshadow),
                                          std::span(s.visible.data(), nshadow));
        for (size_t k = 0; k < nshadow; ++k)
            add_light_sample(paths[s.shadow_owner[k]], s.visible[k] != 0,
                             scene.film.clamp_indirect);
        // Trace the next closest-hit rays of the paths that go on.
        scene.geometry->intersect_incoherent(std::span(s.queries.data(), m),
                                             std::span(s.hits.data(), m));
        std::swap(s.live, s.next);
        nlive = m;
    }
}

}  // namespace patina::render
