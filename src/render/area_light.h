// An emissive mesh as a light: next-event estimation picks a triangle in proportion to its
// area and a uniform point on it, and asks the mesh's emitter plugin for the radiance
// leaving that point towards the shading point.
#pragma once

#include "render/light.h"

#include "core/embree_scene.h"
#include "core/sampling.h"
#include "host/shader_instance.h"

#include <memory>

namespace patina::render {

class AreaLight : public Light {
public:
    /// Mesh `mesh_id` of `scene` (committed, and outliving the light) emitting through
    /// `emitter` (an instance of an emitter shader). `host` is the plugin host; the light
    /// does not need it today (plugins hold their own). Throws std::invalid_argument when
    /// `emitter` is null or not an emitter, std::runtime_error for an unknown mesh id.
    AreaLight(const EmbreeScene& scene, int mesh_id, std::shared_ptr<const ShaderInstance> emitter,
              const PatinaHost* host = nullptr);

    /// A point uniform in area over the mesh; nothing for a zero-area mesh, a point seen
    /// edge-on or from behind a one-sided emitter (zero radiance).
    std::optional<LightSample> sample(const Imath::V3f& p, Imath::V2f u,
                                      const PatinaWavelengths& wl) const override;
    /// The solid-angle density of sample() at `hit` seen from `p`; 0 without a hit.
    float pdf(const Imath::V3f& p, const Imath::V3f& wi,
              const LightHit* hit = nullptr) const override;
    bool is_infinite() const override { return false; }
    SampledSpectrum escaped_radiance(const Imath::V3f&, const PatinaWavelengths& wl) const override
    {
        return SampledSpectrum(wl.count, 0.0f);
    }
    /// π × area × the luminance of the radiance along the normal (both sides for a
    /// two-sided emitter), averaged over a few points of the mesh (computed once).
    float power() const override { return power_; }

    int mesh_id() const { return mesh_id_; }
    double total_area() const { return total_area_; }
    const ShaderInstance& emitter() const { return *emitter_; }

private:
    float estimate_power() const;

    const EmbreeScene* scene_;
    int mesh_id_;
    std::shared_ptr<const ShaderInstance> emitter_;
    Distribution1D triangles_; // over triangle areas
    double total_area_ = 0.0;
    float power_ = 0.0f;
};

} // namespace patina::render
