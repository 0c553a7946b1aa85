// Closest-point queries on the scene's triangles (Embree's rtcPointQuery with an exact
// point-triangle distance): the distance from a point to the nearest surface, the test
// behind Miller's tangent spheres and the distance field of the offset surface.
#pragma once

#include "core/embree_scene.h"

#include <Imath/ImathVec.h>

#include <limits>
#include <vector>

namespace patina::texgen {

/// Closest point on triangle (a, b, c) to p: Ericson 2005, "Real-Time Collision Detection",
/// §5.1.5 (Voronoi regions of the vertices, edges and face). Exact up to rounding.
Imath::V3d closest_point_on_triangle(const Imath::V3d& p, const Imath::V3d& a,
                                     const Imath::V3d& b, const Imath::V3d& c);

/// The answer of a bounded closest-point query.
struct ClosestPoint {
    double distance = 0.0;  ///< to the nearest triangle, or the query radius if none is nearer
    Imath::V3d point;       ///< the nearest point (valid when found)
    bool found = false;     ///< a triangle lies nearer than the query radius
};

/// A BVH over every mesh of an EmbreeScene for point queries. EmbreeScene does not expose
/// its Embree scene, so this builds its own over the same triangles (which must outlive it).
/// Thread-safe after construction.
class ClosestPointScene {
public:
    explicit ClosestPointScene(const EmbreeScene& scene);
    ~ClosestPointScene();
    ClosestPointScene(const ClosestPointScene&) = delete;
    ClosestPointScene& operator=(const ClosestPointScene&) = delete;

    /// The nearest point of any triangle to p, if nearer than `radius` (infinity: no
    /// bound); otherwise found = false and distance = radius.
    ClosestPoint closest(const Imath::V3d& p, double radius) const;
    double distance(const Imath::V3d& p, double radius) const { return closest(p, radius).distance; }

private:
    RTCDevice device_ = nullptr;
    RTCScene scene_ = nullptr;
    std::vector<const TriangleMesh*> meshes_;
};

}  // namespace patina::texgen
