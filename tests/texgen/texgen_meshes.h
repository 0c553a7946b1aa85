// Test meshes for the texgen suites, made in code: a cube with a split uv layout (an atlas
// of six separate islands, as artists lay out a cube), a plane over two UDIM tiles, and a
// mesh without uvs.
#pragma once

#include "core/mesh.h"

#include <Imath/ImathVec.h>

namespace patina::test {

/// Origins (lower-left uv corner) of the six islands of atlas_cube, and their side. Columns
/// at u = 1/64, 22/64, 43/64 and rows at v = 1/16, 9/16, each island 5/16 wide: gaps of 1/64
/// in u and 3/16 in v between islands, all values exact in binary.
inline constexpr float kAtlasIsland = 5.0f / 16.0f;
inline Imath::V2f atlas_island_origin(int face)
{
    return Imath::V2f(static_cast<float>(1 + 21 * (face % 3)) / 64.0f,
                      face < 3 ? 1.0f / 16.0f : 9.0f / 16.0f);
}

/// make_box's cube (6 faces of 4 vertices, outward normals) with each face's [0,1]^2 uvs
/// scaled into its own island of a 3 x 2 atlas of the unit square: no overlaps, gaps
/// between islands, seams along every cube edge.
inline TriangleMesh make_atlas_cube(const Imath::V3f& center = Imath::V3f(0.0f),
                                    float size = 1.0f)
{
    TriangleMesh m = make_box(center, Imath::V3f(size));
    m.name = "atlas_cube";
    for (size_t v = 0; v < m.uvs.size(); ++v)
        m.uvs[v] = atlas_island_origin(static_cast<int>(v / 4)) + kAtlasIsland * m.uvs[v];
    return m;
}

/// An up-facing (+y) rectangle 2 * size along x and size along z, centred at `center`, of
/// 2 x 2 cells (8 triangles) whose uvs span [0, 2] x [0, 1]: the left half (x < center.x)
/// in UDIM 1001, the right half in 1002, each at the same texel density.
inline TriangleMesh make_udim_plane(const Imath::V3f& center = Imath::V3f(0.0f),
                                    float size = 1.0f)
{
    TriangleMesh m = make_plane(Imath::V3f(0.0f), size, 2);
    m.name = "udim_plane";
    for (size_t v = 0; v < m.positions.size(); ++v) {
        m.positions[v].x *= 2.0f;
        m.positions[v] += center;
        m.uvs[v].x *= 2.0f;
    }
    return m;
}

/// A closed uv sphere whose uvs have been dropped (normals kept).
inline TriangleMesh make_mesh_without_uvs()
{
    TriangleMesh m = make_uv_sphere(Imath::V3f(0.0f), 1.0f, 8, 16);
    m.name = "no_uvs";
    m.uvs.clear();
    return m;
}

}  // namespace patina::test
