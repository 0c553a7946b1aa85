// Scene files: errors that name the file and key, plugin paths, meshes, materials, transforms.
#include "render_fixture.h"

using namespace render_test;
TEST(Render, BadKeyNamesFileLineAndKey)
{
    const std::string msg = error_of("badkey", "[film]\nwidth = 10\nspp_count = 4\n");
    EXPECT_NE(msg.find("badkey.toml:3:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("unknown key 'spp_count' in [film]"), std::string::npos) << msg;
}

TEST(Render, MissingMeshNamesTheFile)
{
    const std::string msg = error_of("nomesh", R"(
[[shader]]
name = "a"
type = "lambert"
[[object]]
mesh = "no_such_statue.obj"
bsdf = "a"
)");
    EXPECT_NE(msg.find("no_such_statue.obj"), std::string::npos) << msg;
    EXPECT_NE(msg.find("nomesh.toml:6:"), std::string::npos) << msg;
}

TEST(Render, UnknownColourSpaceIsNamed)
{
    const std::string msg = error_of("badspace", "[environment]\ncolor = [1, 1, 1]\ncolorspace = 'adobe_rgb_1998'\n");
    EXPECT_NE(msg.find("unknown colour space 'adobe_rgb_1998'"), std::string::npos) << msg;
}

TEST(Render, UnknownShaderParameterIsAnError)
{
    const std::string msg = error_of("badparam", R"(
[[shader]]
name = "metal"
type = "conductor"
roughnes = 0.2
)");
    EXPECT_NE(msg.find("parameter 'roughnes'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("did you mean 'roughness'"), std::string::npos) << msg;
}

TEST(Render, ShaderOfTheWrongKindIsRefused)
{
    const std::string msg = error_of("wrongkind", R"(
[[shader]]
name = "lamp"
type = "emitter"
[[object]]
shape = "sphere"
bsdf = "lamp"
)");
    EXPECT_NE(msg.find("cannot be used as 'bsdf'"), std::string::npos) << msg;
}

TEST(Render, ScenePluginPathIsRelativeToTheScene)
{
    const fs::path fixtures = fs::path(PATINA_FIXTURE_PLUGIN_DIR) / "good";
    const fs::path scene_dir = fs::path(PATINA_TEST_BUILD_DIR) / "render_scenes";
    fs::create_directories(scene_dir);
    const std::string rel = fs::relative(fixtures, scene_dir).string();
    auto l = load(write_scene("plugin_path", "[plugins]\npath = ['" + rel + "']\n"
                                             "[[shader]]\nname = 'probe'\ntype = 'fixture_diffuse'\n"));
    ASSERT_EQ(l->scene.shaders.count("probe"), 1u);
    EXPECT_EQ(std::string(l->scene.shaders.at("probe")->desc().name), "fixture_diffuse");
}

TEST(Render, ObjMeshUnderUniformSky)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "render_scenes";
    fs::create_directories(dir);
    std::ofstream(dir / "quad.obj") << "v -50 0 -50\nv 50 0 -50\nv 50 0 50\nv -50 0 50\n"
                                       "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\n"
                                       "f 1/1 4/4 3/3\nf 1/1 3/3 2/2\n";
    auto l = load(write_scene("objmesh", R"(
[film]
width = 8
height = 8
spp = 64
[camera]
from = [0, 3, 0.001]
to = [0, 0, 0]
fov_deg = 20
[environment]
color = [1, 1, 1]
[[shader]]
name = "grey"
type = "lambert"
reflectance = 0.25
[[object]]
mesh = "quad.obj"
bsdf = "grey"
)"));
    const std::vector<float> xyz = pr::render_xyz(l->scene, 0, true);
    double sum_y = 0.0;
    for (size_t i = 0; i < xyz.size(); i += 3)
        sum_y += xyz[i + 1];
    EXPECT_NEAR(sum_y / static_cast<double>(xyz.size() / 3), 0.25, 0.01);
}


TEST(Render, MaterialNamesBindShadersAndTransformsPlaceMeshes)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "render_scenes";
    fs::create_directories(dir);
    std::ofstream(dir / "two.mtl") << "newmtl bronze\nKd 0.5 0.3 0.1\nnewmtl stone\nKd 0.5 0.5 0.5\n";
    std::ofstream(dir / "two.obj") << "mtllib two.mtl\n"
                                      "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 2 0 0\nv 3 0 0\nv 3 1 0\n"
                                      "usemtl bronze\nf 1 2 3\nusemtl stone\nf 4 5 6\n";
    const std::string head = R"(
[[shader]]
name = "metal"
type = "conductor"
[[shader]]
name = "rock"
type = "lambert"
[[object]]
mesh = "two.obj"
)";
    auto l = load(write_scene("materials", head + R"(
materials = { bronze = "metal", stone = "rock" }
transform = { scale = 2.0, rotate_deg = [0, 90, 0], translate = [0, 0, 5] }
)"));
    ASSERT_EQ(l->scene.objects.size(), 2u);
    std::set<std::string> bound;
    for (const auto& o : l->scene.objects)
        bound.insert(o.bsdf->desc().name);
    EXPECT_EQ(bound, (std::set<std::string>{"conductor", "lambert"}));
    // The first triangle's vertex (1, 0, 0): scaled to (2, 0, 0), turned 90° about +y to
    // (0, 0, -2) (right-handed: +x goes to -z), moved to (0, 0, 3). The triangle now spans
    // z in [3, 5] in the plane x = 0: a ray down the -x axis from (5, 0.1, 3.2) finds it at
    // distance 5, one from (5, 0.1, 6) misses.
    const auto hit = l->scene.geometry->intersect({5.0f, 0.1f, 3.2f}, {-1.0f, 0.0f, 0.0f});
    EXPECT_FALSE(l->scene.geometry->intersect({5.0f, 0.1f, 6.0f}, {-1.0f, 0.0f, 0.0f}).has_value());
    ASSERT_TRUE(hit.has_value());
    EXPECT_NEAR(hit->t, 5.0f, 1e-4f);

    EXPECT_NE(error_of("nomat", head).find("has material"), std::string::npos);
    EXPECT_NE(error_of("typomat", head + "materials = { bronse = \"metal\", stone = \"rock\" }\n")
                  .find("no material named 'bronse'"),
              std::string::npos);
}
