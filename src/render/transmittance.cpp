#include "render/transmittance.h"

#include <cmath>
#include <limits>

namespace patina::render {

namespace {
    // Enough for any sane nesting of medium boundaries; a ray that crosses more is treated
    // as blocked rather than looping forever on a degenerate mesh.
    constexpr int kMaxCrossings = 64;
}  // namespace

SampledSpectrum transmittance_along(const Scene& scene, Imath::V3f origin, const Imath::V3f& dir,
                                    float distance, const ShaderInstance* medium,
                                    const PatinaWavelengths& wl, Pcg32& rng)
{
    SampledSpectrum tr(wl.count, 1.0f);
    if (!scene.has_media) {
        if (scene.geometry->occluded(origin, dir, 0.0f, distance))
            tr = SampledSpectrum(wl.count, 0.0f);
        return tr;
    }
    for (int crossing = 0; crossing < kMaxCrossings; ++crossing) {
        const auto hit = scene.geometry->intersect(origin, dir, 0.0f, distance);
        const float segment = hit ? hit->t : distance;
        if (medium && segment > 0.0f) {
            float t[PATINA_MAX_WAVELENGTHS] = {};
            PatinaShadingContext ctx{};
            ctx.P = {origin.x, origin.y, origin.z};
            const float seg = std::isinf(segment) ? std::numeric_limits<float>::max() : segment;
            medium->medium()->transmittance(medium->get(), &ctx, ctx.P, {dir.x, dir.y, dir.z}, seg,
                                            rng.uniform_float(), &wl, t);
            tr *= SampledSpectrum::from_lanes(wl.count, t);
            if (tr.is_black())
                return tr;
        }
        if (!hit)
            return tr;
        const SceneObject& obj =
            scene.objects[static_cast<size_t>(scene.mesh_object[static_cast<size_t>(hit->mesh_id)])];
        if (obj.bsdf || !obj.interior)
            return SampledSpectrum(wl.count, 0.0f);
        const SurfacePoint sp = scene.geometry->interpolate(*hit, origin, dir);
        medium = medium_after_crossing(obj, sp.Ng, dir, medium);
        origin = offset_ray_origin(sp, dir);
        distance -= hit->t;
    }
    return SampledSpectrum(wl.count, 0.0f);
}

}  // namespace patina::render
