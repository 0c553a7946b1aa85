// A procedural statue-like mesh with a non-overlapping uv layout, made by the project for
// samples, tests and benchmarks: a fluted column of revolution on a plinth, with a neck and a
// round head. Its ledges, grooves and neck are the crevices that accessibility, polish and
// patina growth need; its uvs are a single island per part, so bakes have real seams.
#pragma once

#include "core/mesh.h"

namespace patina::texgen {

struct StatueOptions {
    float height = 2.0f;     ///< m, from the bottom of the plinth to the top of the head
    int rings = 240;         ///< rows of vertices along the profile
    int segments = 192;      ///< columns around the axis
    int flutes = 16;         ///< vertical grooves on the column
    float flute_depth = 0.12f;  ///< groove depth as a fraction of the column radius
};

/// The statue standing on y = 0, axis along +y through `base_center`. uv layout: the surface
/// of revolution in v in [0.26, 1] (u = angle / 2 pi from +z towards +x, v up the profile
/// by arc length), the bottom disc in the square [0.005, 0.245]^2; the rest is empty.
/// Smooth vertex normals (the seam at u = 0/1 shares them); outward winding.
TriangleMesh make_statue(const Imath::V3f& base_center, const StatueOptions& options = {});

}  // namespace patina::texgen
