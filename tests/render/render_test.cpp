// The renderer end to end: scene files, plugin shading, spectral film, determinism.
#include "render/renderer.h"
#include "render/scene.h"

#include "core/color_management.h"
#include "core/host.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <cstring>
#include <fstream>
#include <set>

namespace fs = std::filesystem;
namespace pr = patina::render;

namespace {

fs::path write_scene(const std::string& name, const std::string& text)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "render_scenes";
    fs::create_directories(dir);
    const fs::path p = dir / (name + ".toml");
    std::ofstream(p) << text;
    return p;
}

struct Loaded {
    patina::PluginRegistry registry{patina::default_host().c_host()};
    pr::Scene scene;
};

std::unique_ptr<Loaded> load(const fs::path& path)
{
    auto l = std::make_unique<Loaded>();
    const pr::SceneFile file = pr::parse_scene_file(path);
    pr::PluginSearch search;
    search.bundled = false;
    search.environment = false;
    search.command_line = {PATINA_TEST_PLUGIN_DIR};
    search.scene = file.plugin_dirs;
    pr::load_plugins(l->registry, search);
    l->scene = pr::build_scene(file, l->registry, patina::default_host());
    return l;
}

std::string error_of(const std::string& name, const std::string& text)
{
    try {
        load(write_scene(name, text));
    } catch (const std::exception& e) {
        return e.what();
    }
    ADD_FAILURE() << "no error for scene " << name;
    return {};
}

const char* kWhiteFurnace = R"(
[film]
width = 24
height = 16
spp = 32
seed = 7
[camera]
from = [0, 0, 4]
to = [0, 0, 0]
fov_deg = 40
[environment]
color = [1, 1, 1]
[[shader]]
name = "white"
type = "lambert"
reflectance = 1.0
[[object]]
shape = "sphere"
radius = 1.0
bsdf = "white"
)";

}  // namespace

// A white Lambertian sphere in a uniform white environment is invisible: every path that
// hits it leaves with weight exactly 1 (a convex surface sees only the sky), so sphere and
// sky pixels have the sky's radiance. A unit white emission colour is D65 with luminance 1.
TEST(Render, WhiteFurnaceSphereMatchesTheSky)
{
    auto l = load(write_scene("furnace", kWhiteFurnace));
    const std::vector<float> xyz = pr::render_xyz(l->scene, 0, true);
    double sum_y = 0.0;
    for (size_t i = 0; i < xyz.size(); i += 3)
        sum_y += xyz[i + 1];
    const double mean_y = sum_y / static_cast<double>(xyz.size() / 3);
    EXPECT_NEAR(mean_y, 1.0, 0.01);  // unit white light has Y = 1 (abi.h PatinaRgbSpectrum)
    // The centre pixel (sphere) against a corner pixel (sky), each averaged over a 4x4 block.
    auto block = [&](int x0, int y0) {
        double s = 0;
        for (int y = y0; y < y0 + 4; ++y)
            for (int x = x0; x < x0 + 4; ++x)
                s += xyz[(static_cast<size_t>(y) * 24 + x) * 3 + 1];
        return s / 16.0;
    };
    EXPECT_NEAR(block(10, 6), block(0, 0), 0.03);
}

TEST(Render, SameSeedSameBitsForAnyThreadCount)
{
    auto l = load(write_scene("threads", kWhiteFurnace));
    l->scene.film.spp = 4;
    const std::vector<float> one = pr::render_xyz(l->scene, 1, true);
    const std::vector<float> two = pr::render_xyz(l->scene, 2, true);
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(0, std::memcmp(one.data(), two.data(), one.size() * sizeof(float)));
    l->scene.film.seed += 1;
    const std::vector<float> other = pr::render_xyz(l->scene, 2, true);
    EXPECT_NE(0, std::memcmp(one.data(), other.data(), one.size() * sizeof(float)));
}

// A Lambertian plane lit only by a uniform sky of radiance L reflects R * L (the
// irradiance of a uniform hemisphere is pi L, times R / pi): the reflected Y is R.
TEST(Render, LambertPlaneUnderUniformSky)
{
    auto l = load(write_scene("plane", R"(
[film]
width = 16
height = 16
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
reflectance = 0.5
[[object]]
shape = "plane"
size = 100.0
bsdf = "grey"
)"));
    const std::vector<float> xyz = pr::render_xyz(l->scene, 0, true);
    double sum_y = 0.0;
    for (size_t i = 0; i < xyz.size(); i += 3)
        sum_y += xyz[i + 1];
    EXPECT_NEAR(sum_y / static_cast<double>(xyz.size() / 3), 0.5, 0.01);
}

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

TEST(Render, WritesExrAndPngAndNoTemporaryFiles)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "render_out";
    fs::remove_all(dir);
    fs::create_directories(dir);
    const fs::path scene = write_scene("write", kWhiteFurnace);
    pr::PluginSearch search;
    search.bundled = false;
    search.environment = false;
    search.command_line = {PATINA_TEST_PLUGIN_DIR};
    pr::RenderOptions opt;
    opt.output = dir / "image.exr";
    opt.spp = 2;
    opt.quiet = true;
    pr::render_scene_file(scene, search, opt);
    EXPECT_TRUE(fs::exists(dir / "image.exr"));
    EXPECT_TRUE(fs::exists(dir / "image.png"));
    size_t files = 0;
    for ([[maybe_unused]] const auto& e : fs::directory_iterator(dir))
        ++files;
    EXPECT_EQ(files, 2u);
}

// The scene's [plugins] path is resolved against the scene file's folder.
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

// A mesh file goes through Assimp into Embree: a grey OBJ quad filling the view under a
// uniform white sky reflects its albedo (as the built-in plane above).
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

namespace {

double mean_y(const std::vector<float>& xyz)
{
    double sum = 0.0;
    for (size_t i = 0; i < xyz.size(); i += 3)
        sum += xyz[i + 1];
    return sum / static_cast<double>(xyz.size() / 3);
}

}  // namespace

// A Lambertian plane under the sun alone: L = R/π · E · sin(elevation) (the irradiance of a
// distant source of irradiance E at elevation e on a horizontal plane is E sin e).
TEST(Render, LambertPlaneUnderDistantLightMatchesTheClosedForm)
{
    for (const char* diameter : {"0.0", "0.53", "5.0"}) {
        auto l = load(write_scene("sun", std::string(R"(
[film]
width = 8
height = 8
spp = 16
max_depth = 1
[camera]
from = [0, 3, 0.001]
to = [0, 0, 0]
fov_deg = 10
[sun]
elevation_deg = 60
azimuth_deg = 30
irradiance = 2.0
angular_diameter_deg = )") + diameter + R"(
[[shader]]
name = "grey"
type = "lambert"
reflectance = 0.5
[[object]]
shape = "plane"
size = 100.0
bsdf = "grey"
)"));
        const double expected = 0.5 / M_PI * 2.0 * std::sin(60.0 * M_PI / 180.0);
        EXPECT_NEAR(mean_y(pr::render_xyz(l->scene, 0, true)), expected, 0.01 * expected)
            << "angular diameter " << diameter;
    }
}

// Light sampling with MIS and pure BSDF sampling are both unbiased: the same scene (a
// plane, a diffuse and a glossy sphere, an emissive sphere, a dim sky) converges to the
// same mean either way.
TEST(Render, MisAndBsdfSamplingConvergeToTheSameMean)
{
    const std::string scene = R"(
[film]
width = 24
height = 16
spp = 256
max_depth = 4
integrator = "INTEGRATOR"
[camera]
from = [0, 2, 5]
to = [0, 0.5, 0]
fov_deg = 50
[environment]
color = [0.2, 0.2, 0.25]
[[shader]]
name = "grey"
type = "lambert"
reflectance = 0.6
[[shader]]
name = "metal"
type = "conductor"
roughness = 0.4
[[shader]]
name = "lamp"
type = "emitter"
intensity = 8.0
[[object]]
shape = "plane"
size = 20.0
bsdf = "grey"
[[object]]
shape = "sphere"
center = [-0.8, 0.5, 0]
radius = 0.5
bsdf = "grey"
[[object]]
shape = "sphere"
center = [0.8, 0.5, 0]
radius = 0.5
bsdf = "metal"
[[object]]
shape = "sphere"
center = [0, 2.0, 0.5]
radius = 0.3
emitter = "lamp"
)";
    auto with = [&](const std::string& integrator) {
        std::string text = scene;
        text.replace(text.find("INTEGRATOR"), 10, integrator);
        auto l = load(write_scene("mis_" + integrator, text));
        return mean_y(pr::render_xyz(l->scene, 0, true));
    };
    const double mis = with("mis"), bsdf = with("bsdf");
    EXPECT_GT(mis, 0.05);
    EXPECT_NEAR(mis, bsdf, 0.02 * mis);
}

// Meshes bind to shaders by their material names; a transform moves, turns and scales them.
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

// A closed sphere of a scattering, non-absorbing medium behind an index-matched boundary
// inside a uniform white environment is invisible: every path leaves with weight 1 in
// expectation (the volumetric white furnace). The scattering coefficient varies six-fold
// over the spectrum, so paths of many medium events must stay unbiased at every wavelength.
TEST(Render, ScatteringMediumFurnace)
{
    auto l = load(write_scene("medium_furnace", R"(
[film]
width = 16
height = 16
spp = 128
max_depth = 256
[camera]
from = [0, 0, 3]
to = [0, 0, 0]
fov_deg = 30
[environment]
color = [1, 1, 1]
[[shader]]
name = "cloud"
type = "homogeneous"
sigma_a = 0.0
sigma_s = [[400.0, 1.0], [700.0, 6.0]]
g = 0.5
[[object]]
shape = "sphere"
radius = 0.8
interior = "cloud"
)"));
    EXPECT_NEAR(mean_y(pr::render_xyz(l->scene, 0, true)), 1.0, 0.01);
}

// Looking through a box of pure absorber of thickness d at a uniform sky of luminance 1:
// Beer-Lambert, Y = exp(-sigma_a d), for light and BSDF sampling alike.
TEST(Render, AbsorbingSlabFollowsBeerLambert)
{
    // The camera path decides pass or absorb at random: 65536 samples give a binomial
    // standard deviation of 0.002 around exp(-0.75) = 0.472.
    auto l = load(write_scene("medium_slab", R"(
[film]
width = 16
height = 16
spp = 256
[camera]
from = [0, 0, 5]
to = [0, 0, 0]
fov_deg = 2
[environment]
color = [1, 1, 1]
[[shader]]
name = "ink"
type = "homogeneous"
sigma_a = 1.5
sigma_s = 0.0
[[object]]
shape = "box"
size = [4.0, 4.0, 0.5]
interior = "ink"
)"));
    EXPECT_NEAR(mean_y(pr::render_xyz(l->scene, 0, true)), std::exp(-1.5 * 0.5), 0.01);
}

// The same absorber seen by a lit plane behind it: shadow rays through the index-matched
// boundary carry the transmittance (the sun alone, straight down through a 0.4 thick
// slab of sigma_a = 2 onto a white Lambertian plane: R/π · E · exp(-0.8)).
TEST(Render, ShadowRaysCarryTransmittance)
{
    auto l = load(write_scene("medium_shadow", R"(
[film]
width = 8
height = 8
spp = 16
max_depth = 1
[camera]
from = [0, 0.5, 0.001]
to = [0, 0, 0]
fov_deg = 5
[sun]
direction = [0, 1, 0]
angular_diameter_deg = 0.0
irradiance = 3.0
[[shader]]
name = "ink"
type = "homogeneous"
sigma_a = 2.0
sigma_s = 0.0
[[shader]]
name = "white"
type = "lambert"
reflectance = 1.0
[[object]]
shape = "plane"
size = 10.0
bsdf = "white"
[[object]]
shape = "box"
center = [0, 2, 0]
size = [10.0, 0.4, 10.0]
interior = "ink"
)"));
    EXPECT_NEAR(mean_y(pr::render_xyz(l->scene, 0, true)), 3.0 / M_PI * std::exp(-0.8), 2e-3);
}
