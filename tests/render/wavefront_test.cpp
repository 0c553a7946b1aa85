// The wavefront loop (render/wavefront.*) is a reordering of trace_path's work over many
// paths, not a new estimator: every path's radiance, generator and wavelength pdf must come
// out bitwise as trace_path leaves them, and a render through it bitwise equal to the
// per-path loop's.
#include "render_fixture.h"

#include "render/wavefront.h"

#include <cstdlib>
#include <cstring>

using namespace render_test;

namespace {

// Every kind of surface vertex the wavefront handles: diffuse, glossy and refracting
// (transmission through a surface without a medium) BSDFs, an emissive mesh (area light,
// MIS of hits), a sun (a delta light) and a uniform sky; the light sampler chooses among
// three lights, so no light is taken with probability 1.
const char* kMixedScene = R"(
[film]
width = 20
height = 14
spp = 6
seed = 11
max_depth = 6
aovs = ["albedo", "normal", "depth"]
[camera]
from = [0, 2, 5]
to = [0, 0.5, 0]
fov_deg = 50
[environment]
color = [0.3, 0.35, 0.4]
[sun]
elevation_deg = 50
azimuth_deg = 20
irradiance = 1.5
angular_diameter_deg = 0.53
[[shader]]
name = "grey"
type = "lambert"
reflectance = 0.6
[[shader]]
name = "metal"
type = "conductor"
roughness = 0.3
[[shader]]
name = "glass"
type = "dielectric"
roughness = 0.2
[[shader]]
name = "lamp"
type = "emitter"
intensity = 6.0
[[object]]
shape = "plane"
size = 20.0
bsdf = "grey"
[[object]]
shape = "sphere"
center = [-1.0, 0.5, 0]
radius = 0.5
bsdf = "grey"
[[object]]
shape = "sphere"
center = [0.2, 0.5, 0.3]
radius = 0.45
bsdf = "glass"
[[object]]
shape = "sphere"
center = [1.2, 0.5, 0]
radius = 0.5
bsdf = "metal"
[[object]]
shape = "sphere"
center = [0, 2.0, 0.5]
radius = 0.3
emitter = "lamp"
)";

bool same_bits(const patina::SampledSpectrum& a, const patina::SampledSpectrum& b)
{
    return a.count == b.count && std::memcmp(a.v, b.v, sizeof(a.v)) == 0;
}

bool same_bits(const std::vector<float>& a, const std::vector<float>& b)
{
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

struct PerPathLoop {  // PATINA_RENDER_PER_PATH=1 for the lifetime of the object
    PerPathLoop() { setenv("PATINA_RENDER_PER_PATH", "1", 1); }
    ~PerPathLoop() { unsetenv("PATINA_RENDER_PER_PATH"); }
};

}  // namespace

TEST(Wavefront, EachPathBitwiseAsTracePath)
{
    auto l = load(write_scene("wavefront_mixed", kMixedScene));
    const pr::Scene& scene = l->scene;
    ASSERT_TRUE(pr::wavefront_supported(scene));
    // Camera rays over the frame, found one at a time; 4 hero wavelengths each.
    constexpr int kPaths = 3000;
    std::vector<pr::WavefrontPath> paths(kPaths);
    const pr::Camera::Raster raster = scene.camera.raster(scene.film.width, scene.film.height);
    for (int i = 0; i < kPaths; ++i) {
        pr::WavefrontPath& p = paths[static_cast<size_t>(i)];
        p.rng = patina::Pcg32(static_cast<uint64_t>(i) + 1);
        const float px = p.rng.uniform_float() * static_cast<float>(scene.film.width);
        const float py = p.rng.uniform_float() * static_cast<float>(scene.film.height);
        p.ray = raster.ray(px, py);
        p.hit = scene.geometry->intersect(p.ray.origin, p.ray.dir);
        p.wl = patina::sample_wavelengths_tabulated(p.rng.uniform_float(), 4, p.pdf, p.cie);
    }
    std::vector<pr::WavefrontPath> reference = paths;  // the inputs, for trace_path
    pr::WavefrontScratch scratch;
    pr::trace_wavefront(scene, paths, true, scratch);

    int hits = 0, lit = 0, mismatched = 0;
    for (size_t i = 0; i < paths.size(); ++i) {
        pr::WavefrontPath& r = reference[i];
        pr::PathAovs aov;
        const patina::SampledSpectrum L =
            pr::trace_path(scene, r.ray, r.hit, r.wl, r.cie, r.pdf, r.rng, &aov);
        const pr::WavefrontPath& p = paths[i];
        const bool same = same_bits(L, p.L) && same_bits(r.pdf, p.pdf) &&
                          aov.hit == p.aov.hit && same_bits(aov.albedo, p.aov.albedo) &&
                          aov.normal == p.aov.normal && aov.depth == p.aov.depth;
        // Both generators must stand at the same place.
        const bool same_stream = r.rng == p.rng;
        if (!same || !same_stream)
            ++mismatched;
        hits += p.aov.hit ? 1 : 0;
        lit += L.max_value() > 0.0f ? 1 : 0;
    }
    EXPECT_EQ(mismatched, 0);
    // The comparison means something: most camera rays hit and carry light.
    EXPECT_GT(hits, kPaths / 2);
    EXPECT_GT(lit, kPaths / 2);
}

TEST(Wavefront, RenderBitwiseAsThePerPathLoop)
{
    auto l = load(write_scene("wavefront_mixed", kMixedScene));
    const pr::Region full{0, 0, l->scene.film.width, l->scene.film.height};
    const pr::FilmResult wave = pr::render_region(l->scene, full, {2, true, std::nullopt});
    pr::FilmResult per_path;
    {
        PerPathLoop force;
        per_path = pr::render_region(l->scene, full, {2, true, std::nullopt});
    }
    EXPECT_TRUE(same_bits(wave.xyz, per_path.xyz));
    EXPECT_TRUE(same_bits(wave.albedo_xyz, per_path.albedo_xyz));
    EXPECT_TRUE(same_bits(wave.normal, per_path.normal));
    EXPECT_TRUE(same_bits(wave.depth, per_path.depth));
    EXPECT_GT(mean_y(wave.xyz), 0.01);
    // A crop split into odd pieces merges into the same bits (the wavefronts then hold
    // partial tile rows).
    const pr::Region left{0, 0, 7, full.y1}, right{7, 0, full.x1, full.y1};
    const pr::FilmResult a = pr::render_region(l->scene, left, {1, true, std::nullopt});
    const pr::FilmResult b = pr::render_region(l->scene, right, {2, true, std::nullopt});
    int differing = 0;
    for (int y = 0; y < full.y1; ++y)
        for (int x = 0; x < full.x1; ++x)
            for (int k = 0; k < 3; ++k) {
                const int i = x < 7 ? (y * 7 + x) * 3 + k : (y * (full.x1 - 7) + x - 7) * 3 + k;
                const float v = (x < 7 ? a : b).xyz[static_cast<size_t>(i)];
                const float w = wave.xyz[static_cast<size_t>((y * full.x1 + x) * 3 + k)];
                differing += std::memcmp(&v, &w, sizeof v) != 0 ? 1 : 0;
            }
    EXPECT_EQ(differing, 0);
}

// Other counts of hero wavelengths than 4 take the one-sample set-up in the wavefront's
// camera batches (4 takes the batched one): still bitwise the per-path loop.
TEST(Wavefront, OtherWavelengthCountsBitwiseAsThePerPathLoop)
{
    auto l = load(write_scene("wavefront_mixed", kMixedScene));
    const pr::Region full{0, 0, l->scene.film.width, l->scene.film.height};
    for (int count : {3, 8}) {
        l->scene.film.wavelengths = count;
        const pr::FilmResult wave = pr::render_region(l->scene, full, {2, true, std::nullopt});
        pr::FilmResult per_path;
        {
            PerPathLoop force;
            per_path = pr::render_region(l->scene, full, {2, true, std::nullopt});
        }
        EXPECT_TRUE(same_bits(wave.xyz, per_path.xyz)) << count << " wavelengths";
        EXPECT_GT(mean_y(wave.xyz), 0.01);
    }
}

TEST(Wavefront, BsdfOnlyIntegratorBitwiseAsThePerPathLoop)
{
    std::string text = kMixedScene;
    text.replace(text.find("aovs"), 0, "integrator = \"bsdf\"\n");
    auto l = load(write_scene("wavefront_bsdf", text));
    ASSERT_FALSE(l->scene.film.mis);
    const pr::Region full{0, 0, l->scene.film.width, l->scene.film.height};
    const pr::FilmResult wave = pr::render_region(l->scene, full, {2, true, std::nullopt});
    PerPathLoop force;
    const pr::FilmResult per_path = pr::render_region(l->scene, full, {2, true, std::nullopt});
    EXPECT_TRUE(same_bits(wave.xyz, per_path.xyz));
    EXPECT_GT(mean_y(wave.xyz), 0.01);
}

TEST(Wavefront, ThinLensCameraBitwiseAsThePerPathLoop)
{
    // A thin lens draws two more numbers per camera sample: the wavefront's camera stage
    // must draw them in the same place.
    std::string text = kMixedScene;
    text.replace(text.find("fov_deg = 50"), 12,
                 "fov_deg = 50\naperture_radius = 0.05\nfocus_distance = 5.0");
    auto l = load(write_scene("wavefront_lens", text));
    ASSERT_FALSE(l->scene.camera.is_pinhole());
    const pr::Region full{0, 0, l->scene.film.width, l->scene.film.height};
    const pr::FilmResult wave = pr::render_region(l->scene, full, {2, true, std::nullopt});
    PerPathLoop force;
    const pr::FilmResult per_path = pr::render_region(l->scene, full, {2, true, std::nullopt});
    EXPECT_TRUE(same_bits(wave.xyz, per_path.xyz));
    EXPECT_TRUE(same_bits(wave.depth, per_path.depth));
    EXPECT_GT(mean_y(wave.xyz), 0.01);
}

TEST(Wavefront, ScenesWithMediaKeepThePerPathLoop)
{
    auto surfaces = load(write_scene("wavefront_mixed", kMixedScene));
    EXPECT_TRUE(pr::wavefront_supported(surfaces->scene));
    auto fog = load(write_scene("wavefront_media", R"(
[film]
width = 4
height = 4
spp = 1
[camera]
from = [0, 0, 3]
to = [0, 0, 0]
fov_deg = 30
[environment]
color = [1, 1, 1]
[[shader]]
name = "fog"
type = "homogeneous"
sigma_a = 0.5
sigma_s = 1.0
[[object]]
shape = "sphere"
radius = 0.8
interior = "fog"
)"));
    EXPECT_FALSE(pr::wavefront_supported(fog->scene));
}
