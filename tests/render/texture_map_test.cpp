// Shaders reading baked data maps through the host's texture services.
#include "render_fixture.h"

#include "core/image_io.h"

using namespace render_test;

// lambert's reflectance_scale_map multiplies R by the map's first channel: a plane of
// R = 0.5 under a uniform white sky reflects R * s * L (irradiance pi L times R s / pi), so a
// map of constant s = 0.25 gives Y = 0.125; a map value above 1 is clamped to 1 (Y = 0.5).
TEST(Render, LambertReflectanceScaleMapMultipliesTheAlbedo)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "render_scenes";
    fs::create_directories(dir);
    for (const float s : {0.25f, 3.0f}) {
        const std::vector<float> texels(16 * 16, s);
        const fs::path map = dir / (s < 1.0f ? "scale_quarter.exr" : "scale_three.exr");
        patina::make_texture_atomic(map, texels.data(), 16, 16, 1, {"ao"});
        auto l = load(write_scene("plane_scale_map", R"(
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
reflectance_scale_map = { file = ")" + map.string() + R"(", colorspace = "raw" }
[[object]]
shape = "plane"
size = 100.0
bsdf = "grey"
)"));
        const double expected = 0.5 * std::min(s, 1.0f);
        EXPECT_NEAR(mean_y(pr::render_xyz(l->scene, 0, true)), expected, 0.02 * expected)
            << "map value " << s;
    }
}
