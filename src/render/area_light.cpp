#include "render/area_light.h"

#include "render/light_sampler.h"
#include "render/shading_frame.h"

#include <cmath>
#include <numbers>
#include <stdexcept>
#include <vector>

namespace patina::render {

namespace {

    // Points of the mesh at which power() asks the emitter for its radiance.
    constexpr int kPowerPoints = 16;

    PatinaVec3 to_abi(const Imath::V3f& v)
    {
        return {v.x, v.y, v.z};
    }

    struct Barycentrics {
        float b0, b1, b2;
    };

    // A point uniform in area on a triangle: pbrt-v4 SampleUniformTriangle (Heitz 2019,
    // "A Low-Distortion Map Between Triangle and Square"), weights of p0, p1, p2.
    Barycentrics sample_uniform_triangle(float u0, float u1)
    {
        float b0, b1;
        if (u0 < u1) {
            b0 = u0 / 2;
            b1 = u1 - b0;
        } else {
            b1 = u1 / 2;
            b0 = u0 - b1;
        }
        return {b0, b1, 1.0f - b0 - b1};
    }

    void triangle_vertices(const TriangleMesh& m, int tri, Imath::V3f& p0, Imath::V3f& p1,
                           Imath::V3f& p2)
    {
        const size_t t = static_cast<size_t>(tri) * 3;
        p0 = m.positions[m.indices[t]];
        p1 = m.positions[m.indices[t + 1]];
        p2 = m.positions[m.indices[t + 2]];
    }

} // namespace

AreaLight::AreaLight(const EmbreeScene& scene, int mesh_id,
                     std::shared_ptr<const ShaderInstance> emitter, const PatinaHost*)
    : scene_(&scene), mesh_id_(mesh_id), emitter_(std::move(emitter))
{
    if (!emitter_ || emitter_->kind() != PATINA_SHADER_EMITTER || !emitter_->emitter() ||
        !emitter_->emitter()->emit)
        throw std::invalid_argument("area light for mesh " + std::to_string(mesh_id) +
                                    ": the shader is not an emitter");
    const TriangleMesh& m = scene.mesh(mesh_id);
    std::vector<float> areas(m.triangle_count());
    for (size_t i = 0; i < areas.size(); ++i) {
        Imath::V3f p0, p1, p2;
        triangle_vertices(m, static_cast<int>(i), p0, p1, p2);
        const double a = 0.5 * static_cast<double>((p1 - p0).cross(p2 - p0).length());
        areas[i] = std::isfinite(a) ? static_cast<float>(a) : 0.0f;
        total_area_ += areas[i];
    }
    if (!(total_area_ > 0.0))
        return; // nothing to sample; power 0
    triangles_ = Distribution1D(areas);
    power_ = estimate_power();
}

std::optional<LightSample> AreaLight::sample(const Imath::V3f& p, Imath::V2f u,
                                             const PatinaWavelengths& wl) const
{
    if (!(total_area_ > 0.0))
        return std::nullopt;
    // Choose a triangle by area, reusing the rest of u.x for the point on it
    float u_tri = 0.0f, pmf = 0.0f;
    const int tri = triangles_.sample_discrete(u.x, &pmf, &u_tri);
    if (!(pmf > 0.0f))
        return std::nullopt; // only a zero-area triangle at the rim of its cdf piece
    const Barycentrics b = sample_uniform_triangle(u_tri, u.y);
    Imath::V3f p0, p1, p2;
    triangle_vertices(scene_->mesh(mesh_id_), tri, p0, p1, p2);
    const Imath::V3f to_light = b.b0 * p0 + b.b1 * p1 + b.b2 * p2 - p;
    const float dist = to_light.length();
    if (!(dist > 0.0f) || !std::isfinite(dist))
        return std::nullopt;

    // The surface point as a ray from p would find it (Embree's barycentrics: u = b1, v = b2)
    const Hit hit{dist, mesh_id_, tri, b.b1, b.b2};
    const SurfacePoint sp = scene_->interpolate(hit, p, to_light / dist);
    const Imath::V3f d = sp.P - p;
    const float dist2 = d.length2();
    if (!(dist2 > 0.0f))
        return std::nullopt;
    LightSample ls;
    ls.distance = std::sqrt(dist2);
    ls.wi = d / ls.distance;
    const float cos_light = std::abs(sp.Ng.dot(ls.wi));
    if (!(cos_light > 0.0f))
        return std::nullopt; // seen edge-on
    // Area density 1/A turned into solid angle: p_ω = p_A r² / |cos θ_light|
    // (pbrt-v4 §4.2.3, dω = cos θ dA / r²)
    ls.pdf = static_cast<float>(dist2 / (cos_light * total_area_));
    if (!std::isfinite(ls.pdf))
        return std::nullopt;

    // Radiance the emitter sends from the light point back towards p
    const ShadingFrame frame = make_shading_frame(sp);
    float radiance[PATINA_MAX_WAVELENGTHS] = {};
    emitter_->emitter()->emit(emitter_->get(), &frame.ctx, to_abi(frame.to_local(-ls.wi)), &wl,
                              radiance);
    ls.L = SampledSpectrum::from_array(wl.count, radiance);
    if (ls.L.is_black())
        return std::nullopt; // e.g. behind a one-sided emitter
    return ls;
}

float AreaLight::pdf(const Imath::V3f& p, const Imath::V3f& wi, const LightHit* hit) const
{
    if (!hit || !(total_area_ > 0.0))
        return 0.0f;
    const float dist2 = (hit->P - p).length2();
    const float norms = std::sqrt(hit->Ng.length2() * wi.length2());
    const float cos_light = norms > 0.0f ? std::abs(hit->Ng.dot(wi)) / norms : 0.0f;
    if (!(cos_light > 0.0f))
        return 0.0f;
    // The same change of measure as sample(): p_ω = r² / (A |cos θ_light|)
    const float pdf = static_cast<float>(dist2 / (cos_light * total_area_));
    return std::isfinite(pdf) ? pdf : 0.0f;
}

float AreaLight::estimate_power() const
{
    // Radiance along the normal (front and back) at a few points spread over the mesh by
    // area; a Lambertian emitter of radiance L sends π L per unit area from each side.
    const PatinaWavelengths wl = power_wavelengths();
    const TriangleMesh& m = scene_->mesh(mesh_id_);
    double sum = 0.0;
    for (int i = 0; i < kPowerPoints; ++i) {
        float u_tri = 0.0f;
        const float ux = (static_cast<float>(i) + 0.5f) / kPowerPoints;
        const int tri = triangles_.sample_discrete(ux, nullptr, &u_tri);
        // Second coordinate from the golden-ratio sequence so points do not line up
        const float uy = std::fmod(0.5f + static_cast<float>(i) * 0.618034f, 1.0f);
        const Barycentrics b = sample_uniform_triangle(u_tri, uy);
        Imath::V3f p0, p1, p2;
        triangle_vertices(m, tri, p0, p1, p2);
        const Imath::V3f ng = (p1 - p0).cross(p2 - p0).normalized();
        const Imath::V3f P = b.b0 * p0 + b.b1 * p1 + b.b2 * p2;
        const SurfacePoint sp =
            scene_->interpolate(Hit{1.0f, mesh_id_, tri, b.b1, b.b2}, P + ng, -ng);
        const ShadingFrame frame = make_shading_frame(sp);
        for (const float side : {1.0f, -1.0f}) {
            float radiance[PATINA_MAX_WAVELENGTHS] = {};
            emitter_->emitter()->emit(emitter_->get(), &frame.ctx, PatinaVec3{0.0f, 0.0f, side},
                                      &wl, radiance);
            sum += power_luminance(SampledSpectrum::from_array(wl.count, radiance));
        }
    }
    const double power = std::numbers::pi * total_area_ * sum / kPowerPoints;
    return std::isfinite(power) ? static_cast<float>(power) : 0.0f;
}

} // namespace patina::render
