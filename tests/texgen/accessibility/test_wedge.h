// Test geometry shared by the ao and accessibility tests: a V-groove (two long planes
// meeting at a crease) and the surface sample on it.
#pragma once

#include "core/mesh.h"
#include "texgen/texels/surface_samples.h"

#include <cmath>

namespace patina::test {

/// Two rectangles meeting at the crease x = y = 0 (along z, |z| <= width / 2): face 1 is
/// y = 0, 0 <= x <= length, normal +y; face 2 leaves the crease in the direction
/// (cos alpha, sin alpha, 0), so the groove's opening angle is alpha. The inside of the
/// groove is the region between the faces.
inline TriangleMesh make_wedge(double alpha, float length, float width)
{
    TriangleMesh m;
    m.name = "wedge";
    const float hw = 0.5f * width;
    const float cx = static_cast<float>(std::cos(alpha)) * length;
    const float cy = static_cast<float>(std::sin(alpha)) * length;
    m.positions = {{0, 0, -hw}, {length, 0, -hw}, {length, 0, hw}, {0, 0, hw},
                   {0, 0, -hw}, {cx, cy, -hw},    {cx, cy, hw},    {0, 0, hw}};
    // Face 1 wound for +y, face 2 for its inward normal (sin alpha, -cos alpha, 0).
    m.indices = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7};
    return m;
}

/// A surface sample with every field set (Imath vectors are not zeroed by default).
inline texgen::SurfaceSample make_sample(const Imath::V3f& P, const Imath::V3f& N,
                                         const Imath::V3f& Ng)
{
    texgen::SurfaceSample s;
    s.P = P;
    s.N = N;
    s.Ng = Ng;
    s.uv = Imath::V2f(0.0f, 0.0f);
    return s;
}

/// A sample on face 1 at distance d from the crease (z = 0), normal +y.
inline texgen::SurfaceSample wedge_face_sample(float d)
{
    return make_sample(Imath::V3f(d, 0, 0), Imath::V3f(0, 1, 0), Imath::V3f(0, 1, 0));
}

}  // namespace patina::test
