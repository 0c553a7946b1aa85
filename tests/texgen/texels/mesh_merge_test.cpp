// merge_meshes: one surface from all meshes of a file.
#include "texgen/texels/mesh_merge.h"

#include "test_util.h"
#include "texgen/texgen_meshes.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace patina::texgen {
namespace {

    using Imath::V3f;

    TEST(MeshMerge, ConcatenatesAndComputesMissingNormals)
    {
        const TriangleMesh quad = make_quad(V3f(0.0f, -3.0f, 0.0f), 2.0f);
        TriangleMesh box = make_box(V3f(0.0f), V3f(1.0f));
        box.normals.clear();
        const TriangleMesh m = merge_meshes({quad, box}, "scene/statue.obj");
        EXPECT_EQ(m.name, "statue");
        ASSERT_EQ(m.positions.size(), quad.positions.size() + box.positions.size());
        ASSERT_EQ(m.triangle_count(), quad.triangle_count() + box.triangle_count());
        ASSERT_EQ(m.normals.size(), m.positions.size());
        ASSERT_EQ(m.uvs.size(), m.positions.size());
        const uint32_t base = static_cast<uint32_t>(quad.positions.size());
        for (size_t i = 0; i < box.indices.size(); ++i)
            EXPECT_EQ(m.indices[quad.indices.size() + i], base + box.indices[i]);
        // The box's computed normals: every vertex belongs to one face, so its normal is
        // that face's (make_box's own normals).
        const TriangleMesh reference = make_box(V3f(0.0f), V3f(1.0f));
        for (size_t v = 0; v < box.positions.size(); ++v) {
            EXPECT_NEAR((m.normals[base + v] - reference.normals[v]).length(), 0.0f, 1e-6f);
            EXPECT_EQ(m.uvs[base + v], box.uvs[v]);
        }
        for (size_t v = 0; v < quad.positions.size(); ++v)
            EXPECT_EQ(m.normals[v], quad.normals[v]);

        EXPECT_EQ(merge_meshes({quad}, "scene/statue.obj").name, "quad");
    }

    TEST(MeshMerge, MixedUvsAndEmptyInputAreErrors)
    {
        const TriangleMesh with = make_quad(V3f(0.0f), 1.0f);
        const TriangleMesh without = test::make_mesh_without_uvs();
        const std::string mixed = test::message_of([&] { merge_meshes({with, without}, "a.glb"); });
        EXPECT_NE(mixed.find("mesh file 'a.glb'"), std::string::npos) << mixed;
        EXPECT_NE(mixed.find("'quad' has uvs but mesh 'no_uvs' has none"), std::string::npos)
            << mixed;
        EXPECT_NE(test::message_of([&] { merge_meshes({}, "b.obj"); }).find("'b.obj'"),
                  std::string::npos);
        // Meshes that all lack uvs merge fine (the per-vertex mode needs none).
        EXPECT_FALSE(merge_meshes({without, without}, "c.obj").has_uvs());
    }

    TEST(MeshMerge, LoadsEveryMeshOfAFile)
    {
        const std::filesystem::path dir =
            std::filesystem::path(PATINA_TEST_BUILD_DIR) / "mesh_merge_test";
        std::filesystem::create_directories(dir);
        const std::filesystem::path file = dir / "two.obj";
        std::ofstream(file) << "o first\nv 0 0 0\nv 1 0 0\nv 1 1 0\nvt 0 0\nvt 1 0\nvt 1 1\n"
                               "f 1/1 2/2 3/3\n"
                               "o second\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n"
                               "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nf 4/4 5/5 6/6 7/7\n";
        const TriangleMesh m = load_merged_mesh(file);
        EXPECT_EQ(m.name, "two");
        EXPECT_EQ(m.triangle_count(), 3u);
        EXPECT_TRUE(m.has_uvs());
        const std::string missing = test::message_of([&] { load_merged_mesh(dir / "nope.obj"); });
        EXPECT_NE(missing.find("nope.obj"), std::string::npos) << missing;
    }

}  // namespace
}  // namespace patina::texgen
