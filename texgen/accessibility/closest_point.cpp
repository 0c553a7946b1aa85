#include "texgen/accessibility/closest_point.h"

#include <embree3/rtcore.h>
#include <fmt/format.h>

#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>

namespace patina::texgen {

Imath::V3d closest_point_on_triangle(const Imath::V3d& p, const Imath::V3d& a,
                                     const Imath::V3d& b, const Imath::V3d& c)
{
    // Ericson 2005 §5.1.5, ClosestPtPointTriangle: find the Voronoi region of p.
    const Imath::V3d ab = b - a, ac = c - a, ap = p - a;
    const double d1 = ab.dot(ap), d2 = ac.dot(ap);
    if (d1 <= 0.0 && d2 <= 0.0)
        return a;  // vertex region a
    const Imath::V3d bp = p - b;
    const double d3 = ab.dot(bp), d4 = ac.dot(bp);
    if (d3 >= 0.0 && d4 <= d3)
        return b;  // vertex region b
    const double vc = d1 * d4 - d3 * d2;
    if (vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0)
        return a + (d1 / (d1 - d3)) * ab;  // edge region ab
    const Imath::V3d cp = p - c;
    const double d5 = ab.dot(cp), d6 = ac.dot(cp);
    if (d6 >= 0.0 && d5 <= d6)
        return c;  // vertex region c
    const double vb = d5 * d2 - d1 * d6;
    if (vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0)
        return a + (d2 / (d2 - d6)) * ac;  // edge region ac
    const double va = d3 * d6 - d5 * d4;
    if (va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0)
        return b + ((d4 - d3) / ((d4 - d3) + (d5 - d6))) * (c - b);  // edge region bc
    const double denom = va + vb + vc;
    if (denom == 0.0)
        return a;  // degenerate triangle whose vertices coincide
    const double v = vb / denom, w = vc / denom;
    return a + v * ab + w * ac;  // face region
}

namespace {

    struct QueryState {
        const std::vector<const TriangleMesh*>* meshes;
        const Imath::V3d* p;
        float slack;  // the float query centre's rounding, added to every radius
        ClosestPoint best;
    };

    Imath::V3d to_double(const Imath::V3f& v) { return {v.x, v.y, v.z}; }

    bool closest_triangle_callback(RTCPointQueryFunctionArguments* args)
    {
        auto* state = static_cast<QueryState*>(args->userPtr);
        const TriangleMesh& m = *(*state->meshes)[args->geomID];
        const uint32_t* tri = &m.indices[3 * static_cast<size_t>(args->primID)];
        const Imath::V3d q = closest_point_on_triangle(
            *state->p, to_double(m.positions[tri[0]]), to_double(m.positions[tri[1]]),
            to_double(m.positions[tri[2]]));
        const double d = (q - *state->p).length();
        if (d >= state->best.distance)
            return false;
        state->best = {d, q, true};
        // Shrink the search to the new distance (rounded up, so ties are kept).
        args->query->radius = std::nextafter(static_cast<float>(d), INFINITY) + state->slack;
        return true;
    }

}  // namespace

ClosestPointScene::ClosestPointScene(const EmbreeScene& scene)
{
    device_ = rtcNewDevice(nullptr);
    if (!device_)
        throw std::runtime_error("Embree: cannot create a device for closest-point queries");
    scene_ = rtcNewScene(device_);
    rtcSetSceneFlags(scene_, RTC_SCENE_FLAG_ROBUST);
    for (int id = 0; id < scene.mesh_count(); ++id) {
        const TriangleMesh& mesh = scene.mesh(id);
        RTCGeometry geom = rtcNewGeometry(device_, RTC_GEOMETRY_TYPE_TRIANGLE);
        auto* vertices = static_cast<float*>(
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3,
                                    3 * sizeof(float), mesh.positions.size()));
        auto* indices = static_cast<uint32_t*>(
            rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3,
                                    3 * sizeof(uint32_t), mesh.triangle_count()));
        if (!vertices || !indices) {
            rtcReleaseGeometry(geom);
            throw std::runtime_error(fmt::format(
                "Embree: cannot allocate closest-point buffers for mesh '{}'", mesh.name));
        }
        for (size_t i = 0; i < mesh.positions.size(); ++i)
            std::memcpy(vertices + 3 * i, &mesh.positions[i].x, 3 * sizeof(float));
        std::memcpy(indices, mesh.indices.data(), mesh.indices.size() * sizeof(uint32_t));
        rtcCommitGeometry(geom);
        rtcAttachGeometryByID(scene_, geom, static_cast<unsigned>(id));
        rtcReleaseGeometry(geom);
        meshes_.push_back(&mesh);
    }
    rtcCommitScene(scene_);
    const RTCError error = rtcGetDeviceError(device_);
    if (error != RTC_ERROR_NONE) {
        rtcReleaseScene(scene_);
        rtcReleaseDevice(device_);
        throw std::runtime_error(
            fmt::format("Embree error {} while building the closest-point scene",
                        static_cast<int>(error)));
    }
}

ClosestPointScene::~ClosestPointScene()
{
    rtcReleaseScene(scene_);
    rtcReleaseDevice(device_);
}

ClosestPoint ClosestPointScene::closest(const Imath::V3d& p, double radius) const
{
    QueryState state{&meshes_, &p, 0.0f, {radius, p, false}};
    RTCPointQuery query;
    query.x = static_cast<float>(p.x);
    query.y = static_cast<float>(p.y);
    query.z = static_cast<float>(p.z);
    query.time = 0.0f;
    // Embree's radius is a float: round up so nothing within `radius` is culled. The
    // float query centre is within half an ulp of p; the exact distances use p itself.
    state.slack = 1e-6f * (std::abs(query.x) + std::abs(query.y) + std::abs(query.z));
    query.radius = std::isfinite(radius)
                       ? std::nextafter(static_cast<float>(radius), INFINITY) + state.slack
                       : INFINITY;
    RTCPointQueryContext context;
    rtcInitPointQueryContext(&context);
    rtcPointQuery(scene_, &query, &context, closest_triangle_callback, &state);
    return state.best;
}

}  // namespace patina::texgen
