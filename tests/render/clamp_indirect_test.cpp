// [film] clamp_indirect: the fireflies of a caustic (a diffuse floor seeing the sun in a
// polished sphere, as in the lookdev sample) at the lookdev's 64 samples per pixel, with and
// without the clamp; and the clamp leaves light seen or lit directly alone.
#include "render_fixture.h"

#include <algorithm>
#include <array>

using namespace render_test;

namespace {

/// A polished copper sphere (roughness 0.15, as the lookdev's bare copper) on a grey floor
/// under a sun and a uniform sky, seen as the lookdev camera sees its copper ball.
std::string caustic_scene(double clamp)
{
    return R"(
[film]
width = 160
height = 90
spp = 64
seed = 1
max_depth = 6
clamp_indirect = )" + std::to_string(clamp) + R"(
[camera]
from = [0.0, 0.55, 2.6]
to = [0.0, 0.32, 0.0]
fov_deg = 30
[environment]
color = [0.3, 0.3, 0.3]
[sun]
direction = [0.409576, 0.573576, 0.709406]
irradiance = 4.67
[[shader]]
name = "floor"
type = "lambert"
reflectance = 0.3
[[shader]]
name = "polished"
type = "conductor"
eta = 0.27
k = 3.4
roughness = 0.15
[[object]]
shape = "plane"
size = 20
bsdf = "floor"
[[object]]
shape = "sphere"
center = [0.3, 0.25, 0.4]
radius = 0.25
bsdf = "polished"
)";
}

/// Pixels whose luminance exceeds four times the brightest of their 8 neighbours, and that
/// by more than 0.5: isolated sparks, not edges or highlights (which have neighbours as
/// bright).
int fireflies(const pr::FilmResult& film, int width, int height)
{
    auto y = [&](int x, int yy) { return film.xyz[static_cast<size_t>((yy * width + x) * 3 + 1)]; };
    int count = 0;
    for (int yy = 1; yy + 1 < height; ++yy)
        for (int x = 1; x + 1 < width; ++x) {
            std::array<float, 8> n;
            int k = 0;
            for (int dy = -1; dy <= 1; ++dy)
                for (int dx = -1; dx <= 1; ++dx)
                    if (dx || dy)
                        n[static_cast<size_t>(k++)] = y(x + dx, yy + dy);
            const float brightest = *std::max_element(n.begin(), n.end()), v = y(x, yy);
            count += v > 4.0f * brightest && v > brightest + 0.5f ? 1 : 0;
        }
    return count;
}

}  // namespace

TEST(ClampIndirect, RemovesTheFirefliesOfACausticAndKeepsDirectLight)
{
    auto raw = load(write_scene("caustic_raw", caustic_scene(0.0)));
    auto clamped = load(write_scene("caustic_clamped", caustic_scene(4.0)));
    EXPECT_EQ(clamped->scene.film.clamp_indirect, 4.0f);
    const pr::Region full{0, 0, 160, 90};
    const pr::FilmResult a = pr::render_region(raw->scene, full, {2, true, std::nullopt});
    const pr::FilmResult b = pr::render_region(clamped->scene, full, {2, true, std::nullopt});
    const int before = fireflies(a, 160, 90), after = fireflies(b, 160, 90);
    std::printf("[ fireflies ] 160x90 at 64 spp: %d without the clamp, %d with clamp_indirect 4\n",
                before, after);
    EXPECT_GT(before, 10);  // the defect is there at these settings (the test can fail)
    EXPECT_LE(after, 1);
    // Light seen or lit directly is the same with and without: the sky and the sun on the
    // floor far from the sphere (its bottom-left corner) are the same bits.
    int same = 0;
    for (int yy = 44; yy < 54; ++yy)
        for (int x = 0; x < 10; ++x)
            same += a.xyz[static_cast<size_t>((yy * 96 + x) * 3 + 1)] ==
                            b.xyz[static_cast<size_t>((yy * 96 + x) * 3 + 1)]
                        ? 1
                        : 0;
    EXPECT_GT(same, 50) << "of 100 floor pixels far from the sphere";
}

TEST(ClampIndirect, WavefrontAndPerPathLoopClampAlike)
{
    auto l = load(write_scene("caustic_clamped_loops", caustic_scene(4.0)));
    const pr::Region full{0, 0, 160, 90};
    const pr::FilmResult wave = pr::render_region(l->scene, full, {2, true, std::nullopt});
    setenv("PATINA_RENDER_PER_PATH", "1", 1);
    const pr::FilmResult per_path = pr::render_region(l->scene, full, {2, true, std::nullopt});
    unsetenv("PATINA_RENDER_PER_PATH");
    ASSERT_EQ(wave.xyz.size(), per_path.xyz.size());
    EXPECT_EQ(std::memcmp(wave.xyz.data(), per_path.xyz.data(), wave.xyz.size() * sizeof(float)), 0);
}

TEST(ClampIndirect, IsAFilmSettingWithAFloorOfZero)
{
    const std::string m = error_of("clamp_negative", caustic_scene(-1.0));
    EXPECT_NE(m.find("clamp_indirect"), std::string::npos) << m;
}
