// Every ray query goes through Embree 3: an RAII device + scene of triangle meshes, closest
// hit and occlusion queries, and the surface point (position, normals, uv, tangents) at a
// hit interpolated from the mesh data.
#pragma once

#include "core/mesh.h"

#include <Imath/ImathBox.h>
#include <Imath/ImathVec.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <span>
#include <vector>

// Embree's opaque handles, declared here so users need not include <embree3/rtcore.h>.
typedef struct RTCDeviceTy* RTCDevice;
typedef struct RTCSceneTy* RTCScene;

namespace patina {

/// A ray's closest hit: distance t along the ray (in units of |dir|), which mesh (the id
/// add_mesh returned) and triangle, and Embree's barycentrics: the hit point is
/// (1 - u - v) * p0 + u * p1 + v * p2 of the triangle's vertices.
struct Hit {
    float t = 0.0f;
    int mesh_id = -1;
    int prim_id = -1;
    float u = 0.0f, v = 0.0f;
};

/// The geometry at a hit, world space.
struct SurfacePoint {
    Imath::V3f P;        ///< position, from the barycentrics (more accurate than o + t d)
    Imath::V3f p_error;  ///< conservative bound on |P - exact| per component (pbrt-v4 §6.8)
    Imath::V3f Ng;       ///< unit geometric normal of the triangle (see below)
    Imath::V3f N;        ///< unit shading normal, on Ng's side
    Imath::V2f uv;       ///< interpolated uv, or the barycentrics (u, v) if the mesh has none
    Imath::V3f dPdu, dPdv; ///< from the uv parametrisation, else an arbitrary tangent frame
    Imath::V3f wo;       ///< unit direction back towards the ray origin
    int mesh_id = -1;
    int prim_id = -1;
};

/// A shadow ray for EmbreeScene::count_unoccluded: open segment t in [0, tmax] along dir.
struct ShadowRay {
    Imath::V3f origin;
    Imath::V3f dir;
    float tmax = std::numeric_limits<float>::infinity();
};

/// A closest-hit query of a batch (EmbreeScene::intersect_coherent): t in [tmin, tmax].
struct RayQuery {
    Imath::V3f origin;
    Imath::V3f dir;
    float tmin = 0.0f;
    float tmax = std::numeric_limits<float>::infinity();
};

/// Move a ray origin off a surface so the new ray cannot hit it again: offset P along Ng,
/// onto the side `dir` leaves by, by a scaled epsilon (2^-16 of P's largest coordinate
/// plus 1e-6 scene units). Meant for meshes whose triangles are small next to their
/// distance from the origin; the SurfacePoint overload uses the hit's error bound instead.
Imath::V3f offset_ray_origin(const Imath::V3f& P, const Imath::V3f& Ng, const Imath::V3f& dir);
/// pbrt-v4 style: offset by the error bound of the interpolated position, rounded away.
/// Inline: the renderer calls it twice per bounce.
inline Imath::V3f offset_ray_origin(const SurfacePoint& sp, const Imath::V3f& dir)
{
    // Offset along Ng by the error box's extent in that direction (pbrt-v4 OffsetRayOrigin).
    // pbrt's own triangle test also rejects hits closer than its t error bound; Embree
    // accepts t = 0, so a point computed exactly (error 0, e.g. on the plane y = 0) would
    // hit its own triangle again: never offset by less than the scaled epsilon (that of the
    // (P, Ng, dir) overload). That floor, 2^-16 of the largest coordinate, is 2^8 ulps of
    // it, so the rounding of the sum below cannot undo the offset (pbrt's extra next-float
    // step is not needed).
    constexpr float kRelativeOffset = 1.0f / 65536.0f, kAbsoluteOffset = 1e-6f;
    const float ax = std::abs(sp.P.x), ay = std::abs(sp.P.y), az = std::abs(sp.P.z);
    const float scale = std::max(ax, std::max(ay, az));
    const float error = std::abs(sp.Ng.x) * sp.p_error.x + std::abs(sp.Ng.y) * sp.p_error.y +
                        std::abs(sp.Ng.z) * sp.p_error.z;
    float d = std::max(error, kRelativeOffset * scale + kAbsoluteOffset);
    if (sp.Ng.dot(dir) < 0.0f)
        d = -d;
    return sp.P + d * sp.Ng;
}

/// Triangle meshes in one Embree scene. Build (add_mesh, commit) from one thread; after
/// commit, intersect/occluded/interpolate are thread-safe. Embree errors become
/// std::runtime_error with Embree's text.
class EmbreeScene {
public:
    /// `robust` sets RTC_SCENE_FLAG_ROBUST: per Embree's manual, traversal avoids the
    /// optimisations that lose hits on the edges and vertices shared by neighbouring
    /// triangles (closed media boundaries rely on it). Off, traversal is faster (about 20 %
    /// fewer instructions in rtcIntersect1 on the renderer's benchmark scene) and a ray
    /// may, rarely, slip through a shared edge.
    explicit EmbreeScene(bool robust = true);
    ~EmbreeScene();
    EmbreeScene(const EmbreeScene&) = delete;
    EmbreeScene& operator=(const EmbreeScene&) = delete;

    /// Add a copy of `mesh` (kept for interpolation); returns its id, 0, 1, 2, ... in order.
    /// Throws std::runtime_error naming the mesh if it is invalid or has no triangles.
    int add_mesh(const TriangleMesh& mesh);
    /// Build the acceleration structure; needed after the last add_mesh, before queries.
    void commit();

    /// Closest hit with t in [tmin, tmax], or nothing. `dir` need not be unit length.
    std::optional<Hit> intersect(const Imath::V3f& origin, const Imath::V3f& dir, float tmin = 0.0f,
                                 float tmax = std::numeric_limits<float>::infinity()) const;
    /// Closest hits of a batch of coherent rays (camera rays of neighbouring pixels) in one
    /// call: Embree's ray stream API with RTC_INTERSECT_CONTEXT_FLAG_COHERENT, which traces
    /// them as packets. hits[i] answers rays[i] (`hits` as long as `rays`).
    void intersect_coherent(std::span<const RayQuery> rays, std::span<std::optional<Hit>> hits) const;
    /// Closest hits of a batch of unrelated rays (a wavefront's bounce rays): the stream API
    /// without the coherent flag, which Embree traces one ray at a time, so hits[i] is
    /// bitwise what intersect(rays[i]...) gives; one call for the batch.
    void intersect_incoherent(std::span<const RayQuery> rays,
                              std::span<std::optional<Hit>> hits) const;
    /// True if anything lies along the ray with t in [tmin, tmax] (shadow rays).
    bool occluded(const Imath::V3f& origin, const Imath::V3f& dir, float tmin = 0.0f,
                  float tmax = std::numeric_limits<float>::infinity()) const;

    /// How many of `rays` are unoccluded. One call traces the batch through Embree's ray
    /// stream API (rtcOccluded1M), which amortises the per-ray call overhead and lets Embree
    /// reorder incoherent rays (the AO and exposure bakers' many rays per texel).
    size_t count_unoccluded(std::span<const ShadowRay> rays) const;
    /// The same stream query, per ray: visible[i] = 1 if rays[i] is unoccluded, else 0
    /// (`visible` as long as `rays`).
    void trace_shadow_rays(std::span<const ShadowRay> rays, std::span<uint8_t> visible) const;

    /// The surface point of a hit of the ray (origin, dir). Ng follows the winding
    /// (cross(p1 - p0, p2 - p0)) unless the mesh has normals, in which case Ng is flipped to
    /// the side of the interpolated normal (pbrt's rule: the file's normals say which side
    /// is outside); N is the interpolated normal, or Ng without normals.
    SurfacePoint interpolate(const Hit& hit, const Imath::V3f& origin, const Imath::V3f& dir) const;

    /// interpolate() for a renderer's shading point, leaner: the same P, p_error, Ng, N, uv,
    /// dPdu and dPdv, but wo is not computed (the renderer has the ray) and the hit is not
    /// range-checked (it must come from this scene's intersect); `dir`, the ray's direction,
    /// only turns a degenerate triangle's normal towards the ray. Returns true when
    /// (dPdu, dPdv, N) is already an orthonormal right-handed frame, as for a mesh without
    /// uvs (Duff et al.'s frame about N), so that a shading frame can be taken as it is.
    bool interpolate_shading(const Hit& hit, const Imath::V3f& dir, SurfacePoint& sp) const;

    const TriangleMesh& mesh(int mesh_id) const;
    int mesh_count() const { return static_cast<int>(meshes_.size()); }
    /// World bounds of everything added (valid after commit).
    Imath::Box3f bounds() const;

private:
    void check(const char* what) const;

    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    bool committed_ = false;
    std::vector<TriangleMesh> meshes_;
    /// Per mesh, per triangle: the unit winding normal cross(p1 - p0, p2 - p0), or 0 for a
    /// degenerate triangle; computed once in add_mesh instead of at every hit.
    std::vector<std::vector<Imath::V3f>> unit_normals_;
    /// Per mesh: positions and normals (empty without normals) padded to four floats, so
    /// that interpolate_shading loads each with one SIMD load.
    std::vector<std::vector<Imath::V4f>> positions4_, normals4_;
};

}  // namespace patina
