// Participating media: volumetric furnace, Beer-Lambert, transmittance of shadow rays.
#include "render_fixture.h"

using namespace render_test;
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
