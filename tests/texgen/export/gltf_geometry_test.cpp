// The geometry of exported assets (texgen/export/gltf_geometry.h): a mesh split by UDIM
// tile with glTF's uvs, and tangents whose bitangent points up the image, the direction
// flatten's normal map calls +Y (OpenGL, green up).
#include "texgen/export/gltf_geometry.h"

#include "test_util.h"

#include <gtest/gtest.h>

namespace patina::texgen {
namespace {

/// A unit quad in the y = 0 plane facing +y, its uvs the unit square shifted by (du, dv):
/// u along +x, v (up the image) along -z.
TriangleMesh quad(float du, float dv)
{
    TriangleMesh m;
    m.positions = {{0, 0, 0}, {1, 0, 0}, {1, 0, -1}, {0, 0, -1}};
    m.normals.assign(4, Imath::V3f(0, 1, 0));
    m.uvs = {{du, dv}, {du + 1, dv}, {du + 1, dv + 1}, {du, dv + 1}};
    m.indices = {0, 1, 2, 0, 2, 3};
    return m;
}

TEST(GltfGeometry, TilesGetTheirTrianglesWithGltfUvs)
{
    TriangleMesh mesh = quad(0, 0);
    const TriangleMesh second = quad(1, 0);  // tile 1002
    for (const Imath::V3f& p : second.positions)
        mesh.positions.push_back(p + Imath::V3f(2, 0, 0));
    mesh.normals.insert(mesh.normals.end(), second.normals.begin(), second.normals.end());
    mesh.uvs.insert(mesh.uvs.end(), second.uvs.begin(), second.uvs.end());
    for (uint32_t i : second.indices)
        mesh.indices.push_back(i + 4);

    const std::vector<TileGeometry> tiles = split_by_tile(mesh, {1001, 1002}, "test");
    ASSERT_EQ(tiles.size(), 2u);
    for (size_t k = 0; k < 2; ++k) {
        const TileGeometry& t = tiles[k];
        EXPECT_EQ(t.tile, k);
        ASSERT_EQ(t.positions.size(), 4u);  // only the tile's vertices
        EXPECT_EQ(t.indices.size(), 6u);
        // Patina's (u, v) with v up becomes glTF's (u - u0, v0 + 1 - v): the vertex at the
        // image's bottom-left, Patina (u0, 0), is glTF (0, 1).
        EXPECT_EQ(t.positions[0], mesh.positions[4 * k]);
        EXPECT_EQ(t.uvs[0], Imath::V2f(0, 1));
        EXPECT_EQ(t.uvs[2], Imath::V2f(1, 0));
        for (const Imath::V4f& tangent : t.tangents) {
            // +u is +x; glTF's bitangent cross(N, T) w is the image's up, Patina's +v: -z.
            EXPECT_NEAR(tangent.x, 1.0f, 1e-6f);
            const Imath::V3f n(0, 1, 0), dir(tangent.x, tangent.y, tangent.z);
            const Imath::V3f bitangent = n.cross(dir) * tangent.w;
            EXPECT_NEAR(bitangent.z, -1.0f, 1e-6f);
        }
    }
}

TEST(GltfGeometry, MirroredUvsFlipTheBitangent)
{
    TriangleMesh mesh = quad(0, 0);
    for (Imath::V2f& uv : mesh.uvs)
        uv.x = 1.0f - uv.x;  // u now runs along -x: the island is mirrored
    const std::vector<TileGeometry> tiles = split_by_tile(mesh, {1001}, "test");
    ASSERT_EQ(tiles.size(), 1u);
    for (const Imath::V4f& t : tiles[0].tangents) {
        EXPECT_NEAR(t.x, -1.0f, 1e-6f);
        const Imath::V3f bitangent = Imath::V3f(0, 1, 0).cross(Imath::V3f(t.x, t.y, t.z)) * t.w;
        EXPECT_NEAR(bitangent.z, -1.0f, 1e-6f);  // still up the image
        EXPECT_EQ(t.w, -1.0f);
    }
}

TEST(GltfGeometry, TrianglesOffTheStacksTilesAreRefused)
{
    const std::string m =
        test::message_of([&] { split_by_tile(quad(0, 10), {1001}, "export of 'x'"); });
    EXPECT_NE(m.find("export of 'x': triangle 0 has its uv centroid"), std::string::npos) << m;
    EXPECT_NE(m.find("on tile 1101, not one of the stack's UDIM tiles (1001)"), std::string::npos)
        << m;
    TriangleMesh bare = quad(0, 0);
    bare.uvs.clear();
    EXPECT_NE(test::message_of([&] { split_by_tile(bare, {1001}, "m"); }).find("no uvs"),
              std::string::npos);
}

TEST(GltfGeometry, MeanTexelSizeIsSurfaceOverUvArea)
{
    // A 1 m quad on the whole tile at 100 texels: 1 cm texels; at half the uv area, the
    // same surface spreads over fewer texels (sqrt 2 larger).
    TriangleMesh mesh = quad(0, 0);
    EXPECT_NEAR(mean_texel_size_m(mesh, 100, "m"), 0.01, 1e-12);
    for (Imath::V2f& uv : mesh.uvs)
        uv.x *= 0.5f;
    EXPECT_NEAR(mean_texel_size_m(mesh, 100, "m"), 0.01 * std::sqrt(2.0), 1e-12);
}

}  // namespace
}  // namespace patina::texgen
