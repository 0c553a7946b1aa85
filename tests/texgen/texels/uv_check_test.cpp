// uv-check numbers on layouts whose answers are known: the atlas cube (six islands, no
// overlap), make_box (six faces on the same square), a partial overlap, texel density of a
// plane, uvs outside the UDIM tiles, a mesh without uvs.
#include "texgen/texels/uv_check.h"

#include "texgen/texgen_meshes.h"

#include <gtest/gtest.h>

namespace patina::texgen {
namespace {

    using Imath::V2f;
    using Imath::V3f;

    TEST(UvCheck, AtlasCubeHasSixIslandsAndNoOverlap)
    {
        const UvCheck c = check_uvs(test::make_atlas_cube(), {64, 64, 2});
        EXPECT_TRUE(c.has_uvs);
        EXPECT_EQ(c.triangles, 12u);
        EXPECT_EQ(c.vertices, 24u);
        EXPECT_EQ(c.islands, 6u);
        EXPECT_FALSE(c.overlaps());
        EXPECT_EQ(c.overlapping_triangle_pairs, 0u);
        // Each island is 5/16 of 64 = 20 texels square: 6 * 400 texels of 2 x 2 sub-samples.
        EXPECT_EQ(c.covered_sub_samples, 6u * 400u * 4u);
        EXPECT_EQ(c.udims, std::vector<int>{1001});
        EXPECT_EQ(c.vertices_outside_udims + c.triangles_outside_udims, 0u);
        EXPECT_EQ(c.zero_uv_area + c.zero_surface_area, 0u);
        // Every face is 1 m^2 and gets 400 texels: 400 texels/m^2, 50 mm texels.
        EXPECT_NEAR(c.texel_density_mean, 400.0, 1e-9);
        EXPECT_NEAR(c.texel_density_min, 400.0, 1e-9);
        EXPECT_NEAR(c.texel_density_max, 400.0, 1e-9);
        EXPECT_NEAR(texel_size_mm(c.texel_density_mean), 50.0, 1e-9);
        const std::string report = format_uv_check(c);
        EXPECT_NE(report.find("uv islands       6"), std::string::npos) << report;
        EXPECT_NE(report.find("overlapping uvs  none"), std::string::npos) << report;
        EXPECT_NE(report.find("udim tiles       1001"), std::string::npos) << report;
    }

    TEST(UvCheck, BoxFacesSharingTheSquareOverlap)
    {
        // make_box maps every face onto the whole unit square: every covered sub-sample is
        // claimed by all six faces. Overlapping pairs: each face's two triangles meet their
        // twins on the other five faces, 2 * C(6, 2) = 30 pairs (the two halves of a face
        // share only the diagonal, whose centres the tie rule gives to one of them).
        const UvCheck c = check_uvs(make_box(V3f(0.0f), V3f(1.0f)), {32, 32, 2});
        EXPECT_EQ(c.islands, 6u);
        EXPECT_TRUE(c.overlaps());
        EXPECT_EQ(c.covered_sub_samples, 32u * 32u * 4u);
        EXPECT_EQ(c.overlapping_sub_samples, c.covered_sub_samples);
        EXPECT_DOUBLE_EQ(c.overlap_fraction(), 1.0);
        EXPECT_EQ(c.overlapping_triangle_pairs, 30u);
        EXPECT_EQ(c.overlapping_islands, 6u);
        const std::string report = format_uv_check(c);
        EXPECT_NE(report.find("overlapping uvs  100% of the covered uv area"), std::string::npos)
            << report;
        EXPECT_NE(report.find("30 triangle pairs in 6 islands"), std::string::npos) << report;
    }

    TEST(UvCheck, PartialOverlapFraction)
    {
        // Quad A on u in [0, 1/2], quad B on u in [1/4, 3/4] (both v in [0, 1]): they share
        // 1/4 of the unit square out of 3/4 covered, a third. Triangle pairs: A's lower-right
        // half with both of B's halves, A's upper-left half with B's upper-left: 3.
        TriangleMesh m = make_quad(V3f(0.0f), 1.0f);
        TriangleMesh b = make_quad(V3f(0.0f, 1.0f, 0.0f), 1.0f);
        for (V2f& uv : m.uvs)
            uv.x *= 0.5f;
        for (V2f& uv : b.uvs)
            uv.x = 0.25f + 0.5f * uv.x;
        const uint32_t base = static_cast<uint32_t>(m.positions.size());
        m.positions.insert(m.positions.end(), b.positions.begin(), b.positions.end());
        m.normals.insert(m.normals.end(), b.normals.begin(), b.normals.end());
        m.uvs.insert(m.uvs.end(), b.uvs.begin(), b.uvs.end());
        for (uint32_t i : b.indices)
            m.indices.push_back(base + i);
        const UvCheck c = check_uvs(m, {64, 64, 2});
        EXPECT_EQ(c.islands, 2u);
        EXPECT_EQ(c.covered_sub_samples, 48u * 64u * 4u);
        EXPECT_EQ(c.overlapping_sub_samples, 16u * 64u * 4u);
        EXPECT_NEAR(c.overlap_fraction(), 1.0 / 3.0, 1e-12);
        EXPECT_EQ(c.overlapping_triangle_pairs, 3u);
        EXPECT_EQ(c.overlapping_islands, 2u);
    }

    TEST(UvCheck, TexelDensityOfAPlane)
    {
        // A 2 m square (4 m^2) mapped onto the whole 1024 x 1024 map:
        // 1024^2 / 4 = 262144 texels/m^2, texels of 2 m / 1024 = 1.953125 mm.
        const UvCheck c = check_uvs(make_plane(V3f(0.0f), 2.0f, 4), {1024, 1024, 1});
        EXPECT_NEAR(c.texel_density_mean, 262144.0, 1e-6);
        EXPECT_NEAR(c.texel_density_min, 262144.0, 1e-6);
        EXPECT_NEAR(c.texel_density_max, 262144.0, 1e-6);
        EXPECT_NEAR(texel_size_mm(c.texel_density_mean), 1.953125, 1e-9);
        EXPECT_EQ(c.islands, 1u);
        EXPECT_FALSE(c.overlaps());

        // Stretch half of it: squash the uvs of the left column of cells to half their
        // width, so those triangles get half the texels per square metre.
        TriangleMesh stretched = make_plane(V3f(0.0f), 2.0f, 2);
        for (V2f& uv : stretched.uvs)
            uv.x = uv.x <= 0.5f ? 0.5f * uv.x : uv.x - 0.25f;
        const UvCheck s = check_uvs(stretched, {1024, 1024, 1});
        EXPECT_NEAR(s.texel_density_max, 262144.0, 1e-6);
        EXPECT_NEAR(s.texel_density_min, 131072.0, 1e-6);
        // Mean: 3/4 of the map's texels over 4 m^2.
        EXPECT_NEAR(s.texel_density_mean, 0.75 * 262144.0, 1e-6);
    }

    TEST(UvCheck, UdimTilesAndUvsOutside)
    {
        const UvCheck udim = check_uvs(test::make_udim_plane(), {32, 32, 2});
        EXPECT_EQ(udim.udims, (std::vector<int>{1001, 1002}));
        EXPECT_EQ(udim.triangles_outside_udims, 0u);
        EXPECT_FALSE(udim.overlaps());
        EXPECT_NE(format_uv_check(udim).find("udim tiles       1001 1002"), std::string::npos);

        // Shift the quad to u in [-1, 0]: its 4 vertices and 2 triangles are outside.
        TriangleMesh outside = make_quad(V3f(0.0f), 1.0f);
        for (V2f& uv : outside.uvs)
            uv.x -= 1.0f;
        const UvCheck c = check_uvs(outside, {32, 32, 2});
        EXPECT_EQ(c.vertices_outside_udims, 2u);  // u = -1 (u = 0 is inside)
        EXPECT_EQ(c.triangles_outside_udims, 2u);
        EXPECT_TRUE(c.udims.empty());
        EXPECT_NE(format_uv_check(c).find("2 triangles by their uv centroid"), std::string::npos);
        EXPECT_NE(format_uv_check(c).find("will refuse the mesh: 2 triangles lie outside the "
                                          "UDIM tiles: --uv-wrap folds them"),
                  std::string::npos);
        EXPECT_NE(c.refusal(), "");
    }

    TEST(UvCheck, MissingUvsSuggestThePerVertexMode)
    {
        const UvCheck c = check_uvs(test::make_mesh_without_uvs(), {});
        EXPECT_FALSE(c.has_uvs);
        EXPECT_EQ(c.triangles, test::make_mesh_without_uvs().triangle_count());
        const std::string report = format_uv_check(c);
        EXPECT_NE(report.find("no uvs; bake per vertex with --per-vertex out.ply"),
                  std::string::npos)
            << report;
    }

    TEST(UvCheck, DegenerateTrianglesAreCounted)
    {
        TriangleMesh m = make_quad(V3f(0.0f), 1.0f);
        // make_quad's triangles (0, 1, 3) and (0, 3, 2) both use vertices 0 and 3: one uv
        // for both collapses them in uv space (their surface area stays).
        m.uvs[3] = m.uvs[0];
        const UvCheck c = check_uvs(m, {16, 16, 2});
        EXPECT_EQ(c.zero_uv_area, 2u);
        EXPECT_NE(format_uv_check(c).find("2 triangles with zero uv area"), std::string::npos);
    }

}  // namespace
}  // namespace patina::texgen
