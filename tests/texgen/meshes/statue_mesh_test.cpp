#include "core/mesh_export.h"
#include "texgen/meshes/statue_mesh.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <cmath>
#include <filesystem>

namespace patina::texgen {
namespace {

// Signed volume by the divergence theorem: sum over triangles of p0 . (p1 x p2) / 6.
// Positive for a closed surface wound outward.
double signed_volume(const TriangleMesh& m)
{
    double v = 0.0;
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        const Imath::V3f& a = m.positions[m.indices[3 * t]];
        const Imath::V3f& b = m.positions[m.indices[3 * t + 1]];
        const Imath::V3f& c = m.positions[m.indices[3 * t + 2]];
        v += a.dot(b.cross(c)) / 6.0;
    }
    return v;
}

TEST(StatueMesh, ClosedOutwardAndWithinItsBounds)
{
    StatueOptions o;
    o.rings = 120;
    o.segments = 96;
    const TriangleMesh m = make_statue(Imath::V3f(0.0f), o);
    validate_mesh(m, "statue");
    float y_min = 1e9f, y_max = -1e9f;
    for (const auto& p : m.positions) {
        y_min = std::min(y_min, p.y);
        y_max = std::max(y_max, p.y);
    }
    EXPECT_FLOAT_EQ(y_min, 0.0f);
    EXPECT_NEAR(y_max, o.height, 1e-5f);
    // The volume lies between the column alone (r = 0.2 h over the full height, minus
    // flutes) and the plinth's cylinder (r = 0.3 h): a wrong winding makes it negative.
    const double h = o.height;
    const double vol = signed_volume(m);
    EXPECT_GT(vol, 0.5 * M_PI * 0.2 * 0.2 * h * h * h);
    EXPECT_LT(vol, M_PI * 0.3 * 0.3 * h * h * h);
    for (const auto& n : m.normals)
        EXPECT_NEAR(n.length(), 1.0f, 1e-4f);
    for (const auto& uv : m.uvs) {
        EXPECT_GE(uv.x, 0.0f);
        EXPECT_LE(uv.x, 1.0f);
        EXPECT_GE(uv.y, 0.0f);
        EXPECT_LE(uv.y, 1.0f);
    }
}

TEST(StatueMesh, RejectsBadOptions)
{
    StatueOptions o;
    o.rings = 2;
    EXPECT_THROW(make_statue(Imath::V3f(0.0f), o), std::runtime_error);
}

TEST(MeshExport, ObjAndPlyRoundTripThroughAssimp)
{
    const auto dir = std::filesystem::path(PATINA_TEST_BUILD_DIR) / "mesh_export_test";
    std::filesystem::create_directories(dir);
    StatueOptions o;
    o.rings = 24;
    o.segments = 16;
    const TriangleMesh m = make_statue(Imath::V3f(0.0f), o);
    for (const char* ext : {".obj", ".ply"}) {
        const auto path = dir / (std::string("statue") + ext);
        save_mesh(path, m);
        const auto loaded = load_meshes(path);
        ASSERT_EQ(loaded.size(), 1u) << ext;
        EXPECT_EQ(loaded[0].triangle_count(), m.triangle_count()) << ext;
        EXPECT_TRUE(loaded[0].has_uvs()) << ext;
        EXPECT_NEAR(surface_area(loaded[0]), surface_area(m), 1e-4 * surface_area(m)) << ext;
    }
    // Nothing but the outputs in the folder: the temporary names were renamed.
    int files = 0;
    for ([[maybe_unused]] const auto& e : std::filesystem::directory_iterator(dir))
        ++files;
    EXPECT_EQ(files, 2);
}

TEST(MeshExport, UnknownExtensionIsNamed)
{
    const TriangleMesh m = make_quad(Imath::V3f(0.0f), 1.0f);
    const std::string msg = test::message_of([&] { save_mesh("/tmp/x.xyz", m); });
    EXPECT_NE(msg.find("x.xyz"), std::string::npos) << msg;
    EXPECT_NE(msg.find(".obj"), std::string::npos) << msg;
}

}  // namespace
}  // namespace patina::texgen
