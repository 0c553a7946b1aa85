#include "core/mesh.h"
#include "core/mesh_convention.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

namespace patina {
namespace {

    using patina::test::message_of;

    std::filesystem::path write_file(const std::string& name, const std::string& text)
    {
        const auto dir = std::filesystem::path(PATINA_TEST_BUILD_DIR) / "mesh_convention_test";
        std::filesystem::create_directories(dir);
        const auto path = dir / name;
        std::ofstream(path, std::ios::binary) << text;
        return path;
    }

    Imath::V3f apply(const Imath::M44f& m, const Imath::V3f& p)
    {
        Imath::V3f out;
        m.multVecMatrix(p, out);
        return out;
    }

    float det3(const Imath::M44f& m)
    {
        return m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
               m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
               m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    }

    // A COLLADA 1.4.1 document holding one triangle, 1.5 units along its up axis, with the
    // <asset> given: what Blender, 3ds Max and SketchUp write, reduced to the elements
    // Assimp needs.
    std::string collada(const std::string& asset)
    {
        return R"(<?xml version="1.0" encoding="utf-8"?>
<COLLADA xmlns="http://www.collada.org/2005/11/COLLADASchema" version="1.4.1">
  <asset>)" + asset + R"(</asset>
  <library_geometries>
    <geometry id="tri" name="tri">
      <mesh>
        <source id="tri-pos">
          <float_array id="tri-pos-array" count="9">0 0 0 1 0 0 0 0 150</float_array>
          <technique_common>
            <accessor source="#tri-pos-array" count="3" stride="3">
              <param name="X" type="float"/><param name="Y" type="float"/><param name="Z" type="float"/>
            </accessor>
          </technique_common>
        </source>
        <vertices id="tri-vtx"><input semantic="POSITION" source="#tri-pos"/></vertices>
        <triangles count="1"><input semantic="VERTEX" source="#tri-vtx" offset="0"/><p>0 1 2</p></triangles>
      </mesh>
    </geometry>
  </library_geometries>
  <library_visual_scenes>
    <visual_scene id="scene" name="scene">
      <node id="n" name="n"><instance_geometry url="#tri"/></node>
    </visual_scene>
  </library_visual_scenes>
  <scene><instance_visual_scene url="#scene"/></scene>
</COLLADA>
)";
    }

    float height_of(const std::vector<TriangleMesh>& meshes) { return bounds_of(meshes).max.y; }

}  // namespace

TEST(MeshConvention, EveryUpAxisTurnsToPlusYByAProperRotation)
{
    for (int index = 0; index < 3; ++index)
        for (int sign : {1, -1}) {
            const Axis up{index, sign};
            const Imath::M44f m = convention_matrix(up, 1.0);
            Imath::V3f axis(0.0f);
            axis[index] = static_cast<float>(sign);
            EXPECT_EQ(apply(m, axis), Imath::V3f(0, 1, 0)) << up.name();
            EXPECT_FLOAT_EQ(det3(m), 1.0f) << up.name() << ": a rotation, not a mirror";
        }
    // Z up as Blender's glTF exporter and Assimp's COLLADA reader turn it: (x, y, z) ->
    // (x, z, -y), so a file's +y (forward) becomes -z.
    EXPECT_EQ(apply(convention_matrix({2, 1}, 1.0), Imath::V3f(1, 2, 3)), Imath::V3f(1, 3, -2));
    EXPECT_EQ(apply(convention_matrix({1, 1}, 0.01), Imath::V3f(100, 200, 300)),
              Imath::V3f(1, 2, 3));
}

TEST(MeshConvention, AxesAndUnitsParseAndBadOnesAreNamed)
{
    EXPECT_EQ(parse_axis("z", "--up"), (Axis{2, 1}));
    EXPECT_EQ(parse_axis("-Y", "--up"), (Axis{1, -1}));
    EXPECT_EQ(parse_axis("+x", "--up").name(), "+x");
    EXPECT_NE(message_of([] { parse_axis("w", "--up"); }).find("--up: 'w' is not an axis"),
              std::string::npos);
    EXPECT_DOUBLE_EQ(parse_unit("cm", "--unit"), 0.01);
    EXPECT_DOUBLE_EQ(parse_unit("Millimetres", "--unit"), 0.001);
    EXPECT_DOUBLE_EQ(parse_unit("inch", "--unit"), 0.0254);  // exact since 1959
    EXPECT_DOUBLE_EQ(parse_unit("ft", "--unit"), 0.3048);
    EXPECT_NE(message_of([] { parse_unit("furlong", "--unit"); }).find("m, cm, mm"),
              std::string::npos);
    EXPECT_EQ(unit_name(0.01), "cm");
    EXPECT_EQ(unit_name(0.5), "0.5 m");
}

TEST(MeshConvention, OptionsOverrideTheFileWithAWarning)
{
    DeclaredConvention fbx{Axis{2, 1}, 0.01, "FBX GlobalSettings", false};
    const MeshConvention as_declared = resolve_convention(fbx, {});
    EXPECT_EQ(as_declared.up, (Axis{2, 1}));
    EXPECT_DOUBLE_EQ(as_declared.metres_per_unit, 0.01);
    EXPECT_EQ(as_declared.up_from, "FBX GlobalSettings");
    EXPECT_TRUE(as_declared.warnings.empty());

    const MeshConvention overridden = resolve_convention(fbx, {Axis{1, 1}, 0.001});
    EXPECT_EQ(overridden.up, (Axis{1, 1}));
    EXPECT_EQ(overridden.up_from, "--up");
    ASSERT_EQ(overridden.warnings.size(), 2u);
    EXPECT_NE(overridden.warnings[0].find("the file declares +z up (FBX GlobalSettings)"),
              std::string::npos);
    EXPECT_NE(overridden.warnings[1].find("its unit as cm"), std::string::npos);

    // An option that agrees with the file says nothing; a file that declares nothing takes
    // the option silently, else Patina's default.
    EXPECT_TRUE(resolve_convention(fbx, {Axis{2, 1}, 0.01}).warnings.empty());
    const MeshConvention obj = resolve_convention({}, {});
    EXPECT_TRUE(obj.is_identity());
    EXPECT_EQ(obj.describe(), "up +y (Patina's default), unit m (Patina's default)");
}

TEST(MeshConvention, ASizeThatSuggestsAnotherUnitIsNamed)
{
    MeshConvention metres;
    // A 1.5 m figure modelled in centimetres and read as metres: 150 m.
    const std::string large =
        implausible_size_warning(Imath::Box3f({0, 0, 0}, {40, 150, 30}), metres);
    EXPECT_NE(large.find("150 m along its longest side"), std::string::npos) << large;
    EXPECT_NE(large.find("--unit cm"), std::string::npos) << large;
    // The same in millimetres: 1500 m, and millimetres bring it to 1.5 m.
    EXPECT_NE(implausible_size_warning(Imath::Box3f({0, 0, 0}, {400, 1500, 300}), metres)
                  .find("--unit mm"),
              std::string::npos);
    // A statue read as millimetres though modelled in metres: 2 mm tall.
    MeshConvention millimetres;
    millimetres.metres_per_unit = 0.001;
    const std::string small =
        implausible_size_warning(Imath::Box3f({0, 0, 0}, {0.0004f, 0.002f, 0.0003f}), millimetres);
    EXPECT_NE(small.find("small"), std::string::npos) << small;
    EXPECT_NE(small.find("--unit m "), std::string::npos) << small;
    // Plausible sizes, a room to a tower, pass without a word.
    EXPECT_EQ(implausible_size_warning(Imath::Box3f({0, 0, 0}, {0.3f, 1.5f, 0.4f}), metres), "");
    EXPECT_EQ(implausible_size_warning(Imath::Box3f({0, 0, 0}, {20, 80, 20}), metres), "");
}

TEST(MeshConvention, ColladaUnitAndUpAxisAreHonouredAndCanBeOverridden)
{
    const auto zup_cm = write_file(
        "zup_cm.dae", collada(R"(<unit name="centimeter" meter="0.01"/><up_axis>Z_UP</up_axis>)"));
    MeshConvention applied;
    const auto meshes = load_meshes(zup_cm, {}, &applied);
    EXPECT_EQ(applied.up, (Axis{2, 1}));
    EXPECT_DOUBLE_EQ(applied.metres_per_unit, 0.01);
    EXPECT_EQ(applied.up_from, "COLLADA <asset>");
    EXPECT_NEAR(height_of(meshes), 1.5f, 1e-5f);  // 150 cm along the file's z

    // Overridden: the file's numbers taken as metres along y (Assimp's conversion undone).
    MeshConvention raw;
    const auto as_yup_m = load_meshes(zup_cm, {Axis{1, 1}, 1.0}, &raw);
    EXPECT_EQ(raw.warnings.size(), 2u);
    const Imath::Box3f box = bounds_of(as_yup_m);
    EXPECT_NEAR(box.max.z, 150.0f, 1e-3f);
    EXPECT_NEAR(box.max.y - box.min.y, 0.0f, 1e-4f);

    // No <unit> and no <up_axis>: COLLADA's defaults, metres and Y up.
    const auto plain = write_file("plain.dae", collada(""));
    MeshConvention defaults;
    load_meshes(plain, {}, &defaults);
    EXPECT_TRUE(defaults.is_identity());
}

TEST(MeshConvention, ObjIsTakenAsYUpMetresUnlessTheOptionsSay)
{
    const auto obj = write_file("tall.obj", "v 0 0 0\nv 1 0 0\nv 0 0 150\nf 1 2 3\n");
    MeshConvention applied;
    const auto as_is = load_meshes(obj, {}, &applied);
    EXPECT_TRUE(applied.is_identity());
    EXPECT_NEAR(bounds_of(as_is).max.z, 150.0f, 1e-5f);
    const auto upright = load_meshes(obj, {Axis{2, 1}, 0.01}, &applied);
    EXPECT_TRUE(applied.warnings.empty());  // OBJ declares nothing to contradict
    EXPECT_NEAR(bounds_of(upright).max.y, 1.5f, 1e-5f);
    EXPECT_NEAR(bounds_of(upright).min.z, 0.0f, 1e-6f);
}

}  // namespace patina
