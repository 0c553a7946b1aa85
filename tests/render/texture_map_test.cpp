// Shaders reading baked data maps through the host's texture services.
#include "render_fixture.h"

#include "core/image_io.h"

using namespace render_test;

namespace {

// A plane of R = 0.5 under a uniform white sky, its reflectance scaled by `map`.
std::string plane_with_map(const fs::path& map, float gain)
{
    return R"(
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
map_gain = )" + std::to_string(gain) + R"(
reflectance_scale_map = { file = ")" + map.string() + R"(", colorspace = "raw" }
[[object]]
shape = "plane"
size = 100.0
bsdf = "grey"
)";
}

}  // namespace

// lambert's reflectance_scale_map multiplies R by clamp(gain * map, 0, 1): the plane reflects
// R * s * L (irradiance pi L times R s / pi), so a map of constant 0.25 gives Y = 0.125, a map
// value of 3 is clamped to 1 (Y = 0.5), and a gain of 2 on 0.25 gives Y = 0.25.
TEST(Render, LambertReflectanceScaleMapMultipliesTheAlbedo)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "render_scenes";
    fs::create_directories(dir);
    struct Case {
        float value, gain;
    };
    for (const Case c : {Case{0.25f, 1.0f}, Case{3.0f, 1.0f}, Case{0.25f, 2.0f}}) {
        const std::vector<float> texels(16 * 16, c.value);
        const fs::path map = dir / ("scale_" + std::to_string(c.value) + ".exr");
        patina::make_texture_atomic(map, texels.data(), 16, 16, 1, {"ao"});
        auto l = load(write_scene("plane_scale_map", plane_with_map(map, c.gain)));
        const double expected = 0.5 * std::min(c.value * c.gain, 1.0f);
        EXPECT_NEAR(mean_y(pr::render_xyz(l->scene, 0, true)), expected, 0.02 * expected)
            << "map value " << c.value << ", gain " << c.gain;
    }
}
