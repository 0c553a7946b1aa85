// The slab_volume medium rendered by patina-render's volumetric path tracer: Beer-Lambert
// through a non-scattering stone slab, and the white furnace (albedo 1, uniform sky) with an
// index-matched boundary and with a refracting, rough stone_surface boundary.
#include "slab_fixture.h"

#include "render/render_fixture.h"

#include <random>

using namespace render_test;

namespace {

/// A scene in the test scratch folder (where the volume files are), rendered as XYZ.
double render_mean_y(const std::string& name, const std::string& text)
{
    const fs::path path = slab_test::scratch_dir() / (name + ".toml");
    std::ofstream(path) << text;
    auto l = load(path);
    return mean_y(pr::render_xyz(l->scene, 0, true));
}

} // namespace

TEST(SlabVolumeRender, NonScatteringSlabFollowsBeerLambert)
{
    // Stone of density 1 and albedo 0 filling a 4 × 4 × 0.5 m box, sigma_t = 1.5 /m, seen
    // through against a white sky: every camera path passes with probability
    // exp(−1.5 · 0.5) = 0.472 (Eq. 2); 16 × 16 × 256 samples give a binomial standard
    // deviation of 0.002.
    slab_test::write_volume("slab", 8, 8, 2, slab_test::Vec3(-2.1f, -2.1f, -0.3f),
                            slab_test::Vec3(2.1f, 2.1f, 0.3f), slab_test::uniform({}));
    const double y = render_mean_y("slab_beer", R"(
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
name = "stone"
type = "slab_volume"
file = "slab.exr"
sigma_t = 1.5
stone_albedo = 0.0
[[object]]
shape = "box"
size = [4.0, 4.0, 0.5]
interior = "stone"
)");
    EXPECT_NEAR(y, std::exp(-1.5 * 0.5), 0.01);
}

namespace {

/// A heterogeneous stone ball: density and composition vary voxel to voxel.
void write_lumpy_volume()
{
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.0f, 1.0f);
    std::vector<slab_test::Voxel> voxels(12 * 12 * 12);
    for (auto& v : voxels) {
        v.density = 0.2f + 0.8f * u(rng);
        v.crust = 0.3f * u(rng);
        v.iron = 0.3f * u(rng);
        v.salt = 0.3f * u(rng);
    }
    slab_test::write_volume("lumpy", 12, 12, 12, slab_test::Vec3(-1, -1, -1),
                            slab_test::Vec3(1, 1, 1),
                            [&](int i, int j, int k) { return voxels[(k * 12 + j) * 12 + i]; });
}

std::string furnace_scene(const std::string& surface)
{
    // Every albedo 1: whatever the composition, nothing is absorbed
    return R"(
[film]
width = 16
height = 16
spp = 96
max_depth = 1000
[camera]
from = [0, 0, 3]
to = [0, 0, 0]
fov_deg = 30
[environment]
color = [1, 1, 1]
[[shader]]
name = "stone"
type = "slab_volume"
file = "lumpy.exr"
sigma_t = 6.0
stone_albedo = 1.0
crust_albedo = 1.0
iron_albedo = 1.0
salt_albedo = 1.0
[[shader]]
name = "surface"
type = "stone_surface"
)" + surface + R"(
[[object]]
shape = "sphere"
radius = 0.8
bsdf = "surface"
interior = "stone"
)";
}

} // namespace

TEST(SlabVolumeRender, WhiteFurnaceWithAnIndexMatchedBoundary)
{
    // A non-absorbing medium under a uniform sky of radiance 1 leaves radiance 1 everywhere
    write_lumpy_volume();
    EXPECT_NEAR(render_mean_y("furnace_matched", furnace_scene("eta = 1.0\nroughness_exponent = 4.0")),
                1.0, 0.015);
}

TEST(SlabVolumeRender, WhiteFurnaceWithARefractingRoughBoundary)
{
    // F_r^k + (1 − F_r^k) = 1 at every crossing, refracted or diffusely transmitted:
    // still radiance 1
    write_lumpy_volume();
    EXPECT_NEAR(render_mean_y("furnace_rough", furnace_scene("eta = 1.5\nroughness_exponent = 3.0")),
                1.0, 0.015);
}

TEST(SlabVolumeRender, WhiteFurnaceWithDiffuseTransmission)
{
    // Light sampled from the boundary (the diffuse lobe is not a delta) must not change it
    write_lumpy_volume();
    EXPECT_NEAR(render_mean_y("furnace_diffuse",
                              furnace_scene("eta = 1.5\nroughness_exponent = 2.0\n"
                                            "transmission = \"diffuse\"")),
                1.0, 0.015);
}
