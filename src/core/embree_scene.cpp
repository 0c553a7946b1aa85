#include "core/embree_scene.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <algorithm>
#include <cassert>
#include <cfloat>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

namespace patina {

namespace {

    /// The uv at barycentrics (b0, b1, b2) of triangle (i0, i1, i2) and the tangents dP/du,
    /// dP/dv from its uvs (pbrt-v4 Triangle::InteractionFromIntersection); false when the
    /// uvs are degenerate (the caller makes a frame about the normal instead).
    inline bool uv_tangents(const TriangleMesh& m, uint32_t i0, uint32_t i1, uint32_t i2,
                            float b0, float b1, float b2, SurfacePoint& sp)
    {
        const Imath::V3f &p0 = m.positions[i0], &p1 = m.positions[i1], &p2 = m.positions[i2];
        const Imath::V2f &uv0 = m.uvs[i0], &uv1 = m.uvs[i1], &uv2 = m.uvs[i2];
        sp.uv = b0 * uv0 + b1 * uv1 + b2 * uv2;
        const Imath::V2f duv02 = uv0 - uv2, duv12 = uv1 - uv2;
        const Imath::V3f dp02 = p0 - p2, dp12 = p1 - p2;
        const float det = duv02.x * duv12.y - duv02.y * duv12.x;
        if (!(std::abs(det) > 1e-12f))
            return false;
        const float inv = 1.0f / det;
        sp.dPdu = (duv12.y * dp02 - duv02.y * dp12) * inv;
        sp.dPdv = (duv02.x * dp12 - duv12.x * dp02) * inv;
        return sp.dPdu.cross(sp.dPdv).length2() > 0.0f;
    }

    // Embree reports errors through a callback on the thread that made the call; keep the
    // text there and throw from check() after the call returns (never through Embree).
    thread_local std::string t_embree_error;

    void on_embree_error(void*, RTCError code, const char* text)
    {
        if (code != RTC_ERROR_NONE)
            t_embree_error = text ? text : "unknown error";
    }

    const char* error_name(RTCError code)
    {
        switch (code) {
        case RTC_ERROR_NONE: return "no error";
        case RTC_ERROR_INVALID_ARGUMENT: return "invalid argument";
        case RTC_ERROR_INVALID_OPERATION: return "invalid operation";
        case RTC_ERROR_OUT_OF_MEMORY: return "out of memory";
        case RTC_ERROR_UNSUPPORTED_CPU: return "unsupported CPU";
        case RTC_ERROR_CANCELLED: return "cancelled";
        default: return "unknown error";
        }
    }

    Imath::V3f abs(const Imath::V3f& v) { return {std::abs(v.x), std::abs(v.y), std::abs(v.z)}; }

    /// Any unit vector perpendicular to unit `n`, and the third axis of a right-handed frame
    /// (Duff et al. 2017, "Building an Orthonormal Basis, Revisited": no square root, no
    /// division but one, no branch but the sign).
    void tangent_frame(const Imath::V3f& n, Imath::V3f& t, Imath::V3f& b)
    {
        const float sign = std::copysign(1.0f, n.z);
        const float a = -1.0f / (sign + n.z);
        const float c = n.x * n.y * a;
        t = Imath::V3f(1.0f + sign * n.x * n.x * a, sign * c, -sign * n.x);
        b = Imath::V3f(c, sign + n.y * n.y * a, -n.y);
    }

    // Bound on the rounding error of P = b0 p0 + b1 p1 + b2 p2 in floats: pbrt-v4's
    // gamma(7) * sum |bi pi| (§6.8.5), times 8 because Embree computes the barycentrics
    // with its own (unpublished) error instead of pbrt's exact edge functions.
    constexpr float kPositionErrorScale = 8.0f * 7.0f * (FLT_EPSILON * 0.5f) /
                                          (1.0f - 7.0f * (FLT_EPSILON * 0.5f));
    // Scaled epsilon of the (P, Ng, dir) overload: 2^-16 relative plus an absolute floor.
    constexpr float kRelativeOffset = 1.0f / 65536.0f;
    constexpr float kAbsoluteOffset = 1e-6f;

}  // namespace

Imath::V3f offset_ray_origin(const Imath::V3f& P, const Imath::V3f& Ng, const Imath::V3f& dir)
{
    const float scale = std::max({std::abs(P.x), std::abs(P.y), std::abs(P.z)});
    const float d = kRelativeOffset * scale + kAbsoluteOffset;
    return P + (Ng.dot(dir) < 0.0f ? -d : d) * Ng;
}

EmbreeScene::EmbreeScene(bool robust)
{
    // Embree (since 3.12.1) keeps to 128-bit SIMD on Skylake-class CPUs so that SSE-only
    // renderers keep their clock; its release notes advise "frequency_level=simd256" for
    // renderers with AVX code, as Patina's shading is (its AVX2 clones). Embree then builds
    // 8-wide BVHs here instead of 4-wide: 5 % faster renders (bench/README.md, 2026-11-27).
    // Elsewhere it changes nothing: CPUs without 256-bit units ignore the level.
    device_ = rtcNewDevice("frequency_level=simd256");
    if (!device_)
        throw std::runtime_error(fmt::format("Embree: cannot create a device: {}",
                                             error_name(rtcGetDeviceError(nullptr))));
    rtcSetDeviceErrorFunction(device_, on_embree_error, nullptr);
    scene_ = rtcNewScene(device_);
    check("creating a scene");
    // Robust mode: no traversal shortcuts that lose hits on edges and vertices.
    rtcSetSceneFlags(scene_, robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
    rtcSetSceneBuildQuality(scene_, RTC_BUILD_QUALITY_HIGH);
    check("configuring the scene");
}

EmbreeScene::~EmbreeScene()
{
    if (scene_)
        rtcReleaseScene(scene_);
    if (device_)
        rtcReleaseDevice(device_);
}

void EmbreeScene::check(const char* what) const
{
    const RTCError code = rtcGetDeviceError(device_);
    if (code == RTC_ERROR_NONE)
        return;
    std::string text = t_embree_error.empty() ? std::string(error_name(code)) : t_embree_error;
    t_embree_error.clear();
    throw std::runtime_error(fmt::format("Embree error while {}: {}", what, text));
}

int EmbreeScene::add_mesh(const TriangleMesh& mesh)
{
    const std::string context = fmt::format("mesh '{}'", mesh.name);
    validate_mesh(mesh, context);
    if (mesh.triangle_count() == 0)
        throw std::runtime_error(context + ": no triangles");

    RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
    check("creating a triangle geometry");
    // Embree-allocated buffers come with the padding its SIMD loads need.
    auto* vertices = static_cast<float*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.positions.size()));
    auto* indices = static_cast<uint32_t*>(rtcSetNewGeometryBuffer(
        geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 3 * sizeof(uint32_t), mesh.triangle_count()));
    if (!vertices || !indices) {
        rtcReleaseGeometry(geom);
        check(("allocating buffers for " + context).c_str());
        throw std::runtime_error("Embree: cannot allocate buffers for " + context);
    }
    for (size_t i = 0; i < mesh.positions.size(); ++i)
        std::memcpy(vertices + 3 * i, &mesh.positions[i].x, 3 * sizeof(float));
    std::memcpy(indices, mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
    rtcCommitGeometry(geom);
    const int id = static_cast<int>(meshes_.size());
    rtcAttachGeometryByID(scene_, geom, static_cast<unsigned>(id));
    rtcReleaseGeometry(geom); // the scene holds its own reference
    check(("adding " + context).c_str());
    meshes_.push_back(mesh);
    std::vector<Imath::V3f>& normals = unit_normals_.emplace_back(mesh.triangle_count());
    for (size_t t = 0; t < normals.size(); ++t) {
        const Imath::V3f& p0 = mesh.positions[mesh.indices[3 * t]];
        const Imath::V3f ng =
            (mesh.positions[mesh.indices[3 * t + 1]] - p0).cross(mesh.positions[mesh.indices[3 * t + 2]] - p0);
        normals[t] = ng.length2() > 0.0f ? ng.normalized() : Imath::V3f(0, 0, 0);
    }
    std::vector<Imath::V4f>& p4 = positions4_.emplace_back(mesh.positions.size());
    for (size_t v = 0; v < p4.size(); ++v)
        p4[v] = Imath::V4f(mesh.positions[v].x, mesh.positions[v].y, mesh.positions[v].z, 0.0f);
    std::vector<Imath::V4f>& n4 = normals4_.emplace_back(mesh.normals.size());
    for (size_t v = 0; v < n4.size(); ++v)
        n4[v] = Imath::V4f(mesh.normals[v].x, mesh.normals[v].y, mesh.normals[v].z, 0.0f);
    committed_ = false;
    return id;
}

void EmbreeScene::commit()
{
    rtcCommitScene(scene_);
    check("building the scene");
    committed_ = true;
}

std::optional<Hit> EmbreeScene::intersect(const Imath::V3f& origin, const Imath::V3f& dir,
                                          float tmin, float tmax) const
{
    if (!committed_)
        throw std::runtime_error("EmbreeScene::intersect called before commit()");
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    // Every field Embree reads is set (no zeroing of the whole 80-byte struct).
    RTCRayHit rh;
    rh.ray.time = 0.0f;
    rh.ray.id = 0;
    rh.ray.flags = 0;
    rh.ray.org_x = origin.x;
    rh.ray.org_y = origin.y;
    rh.ray.org_z = origin.z;
    rh.ray.dir_x = dir.x;
    rh.ray.dir_y = dir.y;
    rh.ray.dir_z = dir.z;
    rh.ray.tnear = tmin;
    rh.ray.tfar = tmax;
    rh.ray.mask = 0xFFFFFFFFu;
    rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
    rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
    rtcIntersect1(scene_, &context, &rh);
    if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
        return std::nullopt;
    return Hit{rh.ray.tfar, static_cast<int>(rh.hit.geomID), static_cast<int>(rh.hit.primID),
               rh.hit.u, rh.hit.v};
}

namespace {

    // Closest hits of a batch through Embree's ray stream API, in chunks of 64 rays.
    void intersect_stream(RTCScene scene, RTCIntersectContextFlags flags,
                          std::span<const RayQuery> rays, std::span<std::optional<Hit>> hits)
    {
        constexpr size_t kChunk = 64;
        RTCRayHit batch[kChunk];
        RTCIntersectContext context;
        rtcInitIntersectContext(&context);
        context.flags = flags;
        for (size_t first = 0; first < rays.size(); first += kChunk) {
            const size_t n = std::min(kChunk, rays.size() - first);
            for (size_t i = 0; i < n; ++i) {
                const RayQuery& r = rays[first + i];
                RTCRayHit& rh = batch[i];
                rh.ray.time = 0.0f;
                rh.ray.id = static_cast<unsigned>(i);
                rh.ray.flags = 0;
                rh.ray.org_x = r.origin.x;
                rh.ray.org_y = r.origin.y;
                rh.ray.org_z = r.origin.z;
                rh.ray.dir_x = r.dir.x;
                rh.ray.dir_y = r.dir.y;
                rh.ray.dir_z = r.dir.z;
                rh.ray.tnear = r.tmin;
                rh.ray.tfar = r.tmax;
                rh.ray.mask = 0xFFFFFFFFu;
                rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
                rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
            }
            rtcIntersect1M(scene, &context, batch, static_cast<unsigned>(n), sizeof(RTCRayHit));
            for (size_t i = 0; i < n; ++i) {
                const RTCRayHit& rh = batch[i];
                if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID)
                    hits[first + i].reset();
                else
                    hits[first + i] = Hit{rh.ray.tfar, static_cast<int>(rh.hit.geomID),
                                          static_cast<int>(rh.hit.primID), rh.hit.u, rh.hit.v};
            }
        }
    }

}  // namespace

void EmbreeScene::intersect_coherent(std::span<const RayQuery> rays,
                                     std::span<std::optional<Hit>> hits) const
{
    if (!committed_)
        throw std::runtime_error("EmbreeScene::intersect_coherent called before commit()");
    if (hits.size() != rays.size())
        throw std::invalid_argument("EmbreeScene::intersect_coherent: one result per ray");
    intersect_stream(scene_, RTC_INTERSECT_CONTEXT_FLAG_COHERENT, rays, hits);
}

void EmbreeScene::intersect_incoherent(std::span<const RayQuery> rays,
                                       std::span<std::optional<Hit>> hits) const
{
    if (!committed_)
        throw std::runtime_error("EmbreeScene::intersect_incoherent called before commit()");
    if (hits.size() != rays.size())
        throw std::invalid_argument("EmbreeScene::intersect_incoherent: one result per ray");
    intersect_stream(scene_, RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT, rays, hits);
}

bool EmbreeScene::occluded(const Imath::V3f& origin, const Imath::V3f& dir, float tmin,
                           float tmax) const
{
    if (!committed_)
        throw std::runtime_error("EmbreeScene::occluded called before commit()");
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray{};
    ray.org_x = origin.x;
    ray.org_y = origin.y;
    ray.org_z = origin.z;
    ray.dir_x = dir.x;
    ray.dir_y = dir.y;
    ray.dir_z = dir.z;
    ray.tnear = tmin;
    ray.tfar = tmax;
    ray.mask = 0xFFFFFFFFu;
    rtcOccluded1(scene_, &context, &ray);
    // Embree marks an occluded ray by setting tfar to -inf.
    return ray.tfar == -INFINITY;
}

void EmbreeScene::trace_shadow_rays(std::span<const ShadowRay> rays,
                                    std::span<uint8_t> visible) const
{
    if (!committed_)
        throw std::runtime_error("EmbreeScene::trace_shadow_rays called before commit()");
    if (visible.size() != rays.size())
        throw std::invalid_argument("EmbreeScene::trace_shadow_rays: one result per ray");
    constexpr size_t kChunk = 64;
    RTCRay batch[kChunk];
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    for (size_t first = 0; first < rays.size(); first += kChunk) {
        const size_t n = std::min(kChunk, rays.size() - first);
        for (size_t i = 0; i < n; ++i) {
            const ShadowRay& r = rays[first + i];
            RTCRay& ray = batch[i];
            ray = RTCRay{};
            ray.org_x = r.origin.x;
            ray.org_y = r.origin.y;
            ray.org_z = r.origin.z;
            ray.dir_x = r.dir.x;
            ray.dir_y = r.dir.y;
            ray.dir_z = r.dir.z;
            ray.tnear = 0.0f;
            ray.tfar = r.tmax;
            ray.mask = 0xFFFFFFFFu;
        }
        rtcOccluded1M(scene_, &context, batch, static_cast<unsigned>(n), sizeof(RTCRay));
        for (size_t i = 0; i < n; ++i)  // Embree marks a blocked ray with tfar = -inf
            visible[first + i] = batch[i].tfar != -INFINITY ? 1 : 0;
    }
}

size_t EmbreeScene::count_unoccluded(std::span<const ShadowRay> rays) const
{
    thread_local std::vector<uint8_t> visible;
    visible.resize(rays.size());
    trace_shadow_rays(rays, visible);
    size_t unoccluded = 0;
    for (const uint8_t v : visible)
        unoccluded += v;
    return unoccluded;
}

SurfacePoint EmbreeScene::interpolate(const Hit& hit, const Imath::V3f& origin,
                                      const Imath::V3f& dir) const
{
    if (hit.mesh_id < 0 || hit.mesh_id >= mesh_count())
        mesh(hit.mesh_id);  // throws, naming the id
    const TriangleMesh& m = meshes_[static_cast<size_t>(hit.mesh_id)];
    if (hit.prim_id < 0 || static_cast<size_t>(hit.prim_id) >= m.triangle_count())
        throw std::runtime_error(fmt::format("EmbreeScene::interpolate: triangle {} out of range for mesh '{}'",
                                             hit.prim_id, m.name));
    const size_t t = static_cast<size_t>(hit.prim_id) * 3;
    const uint32_t i0 = m.indices[t], i1 = m.indices[t + 1], i2 = m.indices[t + 2];
    const Imath::V3f &p0 = m.positions[i0], &p1 = m.positions[i1], &p2 = m.positions[i2];
    const float b1 = hit.u, b2 = hit.v, b0 = 1.0f - b1 - b2;

    SurfacePoint sp;
    sp.mesh_id = hit.mesh_id;
    sp.prim_id = hit.prim_id;
    const Imath::V3f w0 = b0 * p0, w1 = b1 * p1, w2 = b2 * p2;
    sp.P = w0 + w1 + w2;
    sp.p_error = kPositionErrorScale * (abs(w0) + abs(w1) + abs(w2));
    const Imath::V3f back = origin - sp.P;
    const float back_length2 = back.length2();
    sp.wo = back_length2 > 0.0f ? back * (1.0f / std::sqrt(back_length2)) : -dir.normalized();

    // Geometric normal from the winding (unit, from add_mesh); a degenerate triangle (never
    // hit in practice) falls back to facing the ray.
    sp.Ng = unit_normals_[static_cast<size_t>(hit.mesh_id)][static_cast<size_t>(hit.prim_id)];
    if (sp.Ng.x == 0.0f && sp.Ng.y == 0.0f && sp.Ng.z == 0.0f)
        sp.Ng = -dir.normalized();

    // Shading normal: interpolated; the file's normals decide which side is outside.
    sp.N = sp.Ng;
    if (m.has_normals()) {
        const Imath::V3f n = b0 * m.normals[i0] + b1 * m.normals[i1] + b2 * m.normals[i2];
        const float n_length2 = n.length2();
        if (n_length2 > 1e-20f && n_length2 < std::numeric_limits<float>::infinity()) {
            sp.N = n * (1.0f / std::sqrt(n_length2));
            if (sp.N.dot(sp.Ng) < 0.0f)
                sp.Ng = -sp.Ng;
        }
    }

    bool frame_ok = false;
    if (m.has_uvs())
        frame_ok = uv_tangents(m, i0, i1, i2, b0, b1, b2, sp);
    else
        sp.uv = Imath::V2f(hit.u, hit.v);
    if (!frame_ok)
        tangent_frame(sp.N, sp.dPdu, sp.dPdv);
    return sp;
}

namespace {

    // Three coordinates and a zero in one SIMD register (GCC vector extension: SSE on
    // x86-64, no -m flags): the per-component arithmetic of Imath::V3f, in one instruction.
    using Float4 = float __attribute__((vector_size(16)));

    Float4 load4(const Imath::V4f& v)
    {
        Float4 r;
        std::memcpy(&r, &v, sizeof r);
        return r;
    }
    void store3(Imath::V3f& v, Float4 r) { v = Imath::V3f(r[0], r[1], r[2]); }
    Float4 abs4(Float4 v)
    {
        using Int4 = int32_t __attribute__((vector_size(16)));
        Int4 bits;
        std::memcpy(&bits, &v, sizeof bits);
        bits &= 0x7fffffff;
        std::memcpy(&v, &bits, sizeof v);
        return v;
    }

}  // namespace

// AVX2 and baseline clones (as sample_wavelengths_tabulated: no FMA, the same bits).
[[gnu::target_clones("avx2", "default")]]
bool EmbreeScene::interpolate_shading(const Hit& hit, const Imath::V3f& dir,
                                      SurfacePoint& sp) const
{
    assert(hit.mesh_id >= 0 && hit.mesh_id < mesh_count());
    const size_t id = static_cast<size_t>(hit.mesh_id);
    const TriangleMesh& m = meshes_[id];
    const size_t t = static_cast<size_t>(hit.prim_id) * 3;
    const uint32_t i0 = m.indices[t], i1 = m.indices[t + 1], i2 = m.indices[t + 2];
    const float b1 = hit.u, b2 = hit.v, b0 = 1.0f - b1 - b2;

    // As interpolate(), the same operations in the same order (the same bits), three
    // components at a time, without wo.
    sp.mesh_id = hit.mesh_id;
    sp.prim_id = hit.prim_id;
    const std::vector<Imath::V4f>& p4 = positions4_[id];
    const Float4 w0 = b0 * load4(p4[i0]), w1 = b1 * load4(p4[i1]), w2 = b2 * load4(p4[i2]);
    store3(sp.P, w0 + w1 + w2);
    store3(sp.p_error, kPositionErrorScale * (abs4(w0) + abs4(w1) + abs4(w2)));
    sp.Ng = unit_normals_[id][static_cast<size_t>(hit.prim_id)];
    if (sp.Ng.x == 0.0f && sp.Ng.y == 0.0f && sp.Ng.z == 0.0f)
        sp.Ng = -dir.normalized();  // degenerate (never hit in practice)
    sp.N = sp.Ng;
    if (m.has_normals()) {
        const std::vector<Imath::V4f>& n4 = normals4_[id];
        const Float4 n = b0 * load4(n4[i0]) + b1 * load4(n4[i1]) + b2 * load4(n4[i2]);
        const Float4 n2 = n * n;
        const float n_length2 = n2[0] + n2[1] + n2[2];
        if (n_length2 > 1e-20f && n_length2 < std::numeric_limits<float>::infinity()) {
            store3(sp.N, n * (1.0f / std::sqrt(n_length2)));
            if (sp.N.dot(sp.Ng) < 0.0f)
                sp.Ng = -sp.Ng;
        }
    }
    if (!m.has_uvs()) {
        sp.uv = Imath::V2f(hit.u, hit.v);
        tangent_frame(sp.N, sp.dPdu, sp.dPdv);
        return true;
    }
    if (uv_tangents(m, i0, i1, i2, b0, b1, b2, sp))
        return false;
    tangent_frame(sp.N, sp.dPdu, sp.dPdv);
    return true;
}

const TriangleMesh& EmbreeScene::mesh(int mesh_id) const
{
    if (mesh_id < 0 || mesh_id >= mesh_count())
        throw std::runtime_error(fmt::format("EmbreeScene: no mesh with id {} ({} meshes)", mesh_id, mesh_count()));
    return meshes_[static_cast<size_t>(mesh_id)];
}

Imath::Box3f EmbreeScene::bounds() const
{
    if (!committed_ || meshes_.empty())
        return Imath::Box3f();
    RTCBounds b;
    rtcGetSceneBounds(scene_, &b);
    return Imath::Box3f(Imath::V3f(b.lower_x, b.lower_y, b.lower_z),
                        Imath::V3f(b.upper_x, b.upper_y, b.upper_z));
}

}  // namespace patina
