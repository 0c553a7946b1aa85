// The slab_volume medium: Beer-Lambert in a homogeneous slab, ratio and delta tracking
// against the closed-form transmittance of a linear density ramp, the majorant grid's walk
// and bounds, the albedo mixed from the voxels' composition, and errors naming the file.
#include "slab_fixture.h"

#include <patina/volume/majorant_grid.h>
#include <patina/volume/tracking.h>

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace slab_test;

namespace {

/// Mean and standard error of `n` estimates.
struct Stats {
    double mean = 0.0, stderr_ = 0.0;
};
template <typename F> Stats estimate(int n, F&& f)
{
    double sum = 0.0, sum2 = 0.0;
    for (int i = 0; i < n; ++i) {
        const double x = f(i);
        sum += x;
        sum2 += x * x;
    }
    Stats s;
    s.mean = sum / n;
    s.stderr_ = std::sqrt(std::max(0.0, sum2 / n - s.mean * s.mean) / n);
    return s;
}

/// The i-th of n stratified uniform numbers, scrambled so neighbours are far apart.
float uniform_number(int i, int n)
{
    const uint32_t scrambled = static_cast<uint32_t>(i) * 2654435761u;
    return (static_cast<float>(scrambled % static_cast<uint32_t>(n)) + 0.5f) /
           static_cast<float>(n);
}

/// A stone block of density 1 over [-1, 1]³ (4³ voxels).
fs::path solid_block()
{
    return write_volume("solid", 4, 4, 4, Vec3(-1, -1, -1), Vec3(1, 1, 1), uniform(Voxel{}));
}

/// Density ramp ρ = x over [0, 1]³ on 16 × 2 × 2 voxels: the voxel centres hold x, and
/// trilinear interpolation reproduces ρ(x) = x exactly for x in [1/32, 31/32].
fs::path ramp()
{
    return write_volume("ramp", 16, 2, 2, Vec3(0, 0, 0), Vec3(1, 1, 1), [](int i, int, int) {
        Voxel v;
        v.density = (static_cast<float>(i) + 0.5f) / 16.0f;
        return v;
    });
}

} // namespace

TEST(SlabVolume, HomogeneousSlabTransmittanceIsBeerLambert)
{
    const fs::path file = solid_block();
    const Medium m(make("slab_volume", "file = \"solid.exr\"\nsigma_t = 2.0\n"));
    // Through 0.7 m of stone, and from outside the box through its whole 2 m width:
    // Beer-Lambert T = exp(−σt d) (Dorsey et al. 1999 §5.1 Eq. 2 with constant κ)
    struct Case {
        Vec3 o;
        float t, expected_depth;
    } cases[] = {{Vec3(-0.35f, 0.1f, 0.2f), 0.7f, 0.7f}, {Vec3(-3.0f, 0.1f, 0.2f), 10.0f, 2.0f}};
    for (const Case& c : cases) {
        const double expected = std::exp(-2.0 * c.expected_depth);
        const int n = 40000;
        const Stats tr = estimate(n, [&](int i) {
            return m.transmittance(c.o, Vec3(1, 0, 0), c.t, uniform_number(i, n));
        });
        EXPECT_NEAR(tr.mean, expected, 4.0 * tr.stderr_ + 1e-4) << "depth " << c.expected_depth;
        // Delta tracking passes with the same probability
        const Stats pass = estimate(n, [&](int i) {
            return m.sample_distance(c.o, Vec3(1, 0, 0), c.t, uniform_number(i, n)).scattered ? 0.0
                                                                                              : 1.0;
        });
        EXPECT_NEAR(pass.mean, expected, 4.0 * pass.stderr_ + 1e-4) << "depth " << c.expected_depth;
    }
}

TEST(SlabVolume, RatioTrackingIsUnbiasedOnALinearRamp)
{
    ramp();
    const float sigma = 3.0f;
    const Medium m(make("slab_volume", "file = \"ramp.exr\"\nsigma_t = 3.0\n"));
    // Along x from 0.1 to 0.9: ∫ρ = (0.9² − 0.1²)/2 = 0.4; obliquely from (0.1, 0.2, 0.5)
    // along (0.8, 0.6, 0) for 1 m: ∫ (0.1 + 0.8 s) ds = 0.5. T = exp(−σ ∫ρ) (Eq. 2).
    struct Case {
        Vec3 o, d;
        float t;
        double optical_depth;
    } cases[] = {{Vec3(0.1f, 0.5f, 0.5f), Vec3(1, 0, 0), 0.8f, 0.4 * sigma},
                 {Vec3(0.1f, 0.2f, 0.5f), Vec3(0.8f, 0.6f, 0), 1.0f, 0.5 * sigma},
                 {Vec3(0.9f, 0.5f, 0.5f), Vec3(-1, 0, 0), 0.8f, 0.4 * sigma}};
    for (const Case& c : cases) {
        const int n = 100000;
        const Stats tr =
            estimate(n, [&](int i) { return m.transmittance(c.o, c.d, c.t, uniform_number(i, n)); });
        const double expected = std::exp(-c.optical_depth);
        EXPECT_NEAR(tr.mean, expected, 4.0 * tr.stderr_ + 1e-4)
            << "optical depth " << c.optical_depth << ", standard error " << tr.stderr_;
    }
}

TEST(SlabVolume, DeltaTrackingCollisionsFollowTheRampTransmittance)
{
    ramp();
    const Medium m(make("slab_volume",
                        "file = \"ramp.exr\"\nsigma_t = 3.0\nstone_albedo = 0.5\n"));
    // P(first collision before s) = 1 − T(s), T(s) = exp(−3 ((0.1 + s)² − 0.1²)/2)
    const Vec3 o(0.1f, 0.5f, 0.5f), d(1, 0, 0);
    const int n = 100000;
    const float checkpoints[] = {0.2f, 0.4f, 0.6f, 0.8f};
    int before[4] = {0, 0, 0, 0};
    for (int i = 0; i < n; ++i) {
        const auto s = m.sample_distance(o, d, 0.8f, uniform_number(i, n));
        if (!s.scattered)
            continue;
        ASSERT_GE(s.t, 0.0f);
        ASSERT_LT(s.t, 0.8f);
        // A real collision scatters with weight σs/σt = the albedo
        ASSERT_NEAR(s.weight[0], 0.5f, 1e-6f);
        for (int c = 0; c < 4; ++c)
            before[c] += s.t < checkpoints[c] ? 1 : 0;
    }
    for (int c = 0; c < 4; ++c) {
        const double x = 0.1 + checkpoints[c];
        const double p = 1.0 - std::exp(-3.0 * (x * x - 0.01) / 2.0);
        const double sd = std::sqrt(p * (1.0 - p) / n);
        EXPECT_NEAR(static_cast<double>(before[c]) / n, p, 4.0 * sd) << "s " << checkpoints[c];
    }
}

TEST(SlabVolume, MajorantGridBoundsTheDensityAlongEveryRay)
{
    using patina::volume::MajorantGrid;
    using patina::volume::VoxelGrid;
    std::mt19937 rng(5);
    std::uniform_real_distribution<float> u01(0.0f, 1.0f);
    VoxelGrid grid(13, 9, 7, Vec3(-1.0f, 0.0f, 2.0f), Vec3(1.5f, 1.0f, 3.0f));
    for (int k = 0; k < 7; ++k)
        for (int j = 0; j < 9; ++j)
            for (int i = 0; i < 13; ++i)
                grid.density_at(i, j, k) = u01(rng) < 0.3f ? 0.0f : u01(rng);
    const MajorantGrid majorants(grid, 4);
    ASSERT_EQ(majorants.size(0), 4);
    ASSERT_EQ(majorants.size(2), 2);
    for (int r = 0; r < 500; ++r) {
        const Vec3 o(-2.0f + 4.5f * u01(rng), -1.0f + 3.0f * u01(rng), 1.0f + 3.0f * u01(rng));
        const Vec3 d = patina::shading::normalize(
            Vec3(u01(rng) - 0.5f, u01(rng) - 0.5f, u01(rng) - 0.5f));
        const double t_max = 5.0 * u01(rng);
        double last = -1.0, covered = 0.0;
        majorants.traverse(o, d, t_max, [&](double t0, double t1, float bound) {
            // Segments come in order, without gaps, inside [0, t_max]
            EXPECT_GE(t0, 0.0);
            EXPECT_LE(t1, t_max + 1e-9);
            if (last >= 0.0) {
                EXPECT_NEAR(t0, last, 1e-5);
            }
            last = t1;
            covered += t1 - t0;
            for (int s = 0; s < 8; ++s) {
                const double t = t0 + (t1 - t0) * u01(rng);
                EXPECT_LE(grid.density(o + d * static_cast<float>(t)), bound + 1e-6f);
            }
            return true;
        });
        // The segments cover the part of the ray inside the box: check by sampling
        double inside = 0.0;
        const int steps = 2000;
        for (int s = 0; s < steps; ++s) {
            const double t = t_max * (s + 0.5) / steps;
            inside += grid.contains(o + d * static_cast<float>(t)) ? t_max / steps : 0.0;
        }
        EXPECT_NEAR(covered, inside, 2.0 * t_max / steps + 1e-4);
    }
}

TEST(SlabVolume, AlbedoMixesTheComposition)
{
    // Greys uplift exactly, so the scatter weight is the mixture itself: with crust 0.25,
    // iron 0.5 and stone the rest, 0.25·0.8 + 0.25·0 + 0.5·0.4 = 0.4
    write_volume("mixed", 2, 2, 2, Vec3(0, 0, 0), Vec3(1, 1, 1),
                 uniform(Voxel{1.0f, 0.25f, 0.5f, 0.0f}));
    const std::string albedos = "stone_albedo = 0.8\ncrust_albedo = 0.0\niron_albedo = 0.4\n"
                                "salt_albedo = 1.0\nsigma_t = 1000.0\n";
    const Medium m(make("slab_volume", "file = \"mixed.exr\"\n" + albedos));
    const auto s = m.sample_distance(Vec3(0.5f, 0.5f, -1.0f), Vec3(0, 0, 1), 10.0f, 0.3f);
    ASSERT_TRUE(s.scattered);
    EXPECT_GT(s.t, 1.0f);
    for (int i = 0; i < 4; ++i)
        EXPECT_NEAR(s.weight[i], 0.4f, 1e-5f);

    // Fractions summing above 1 are scaled to sum 1: iron 1 and salt 1 count half each
    write_volume("oversalted", 2, 2, 2, Vec3(0, 0, 0), Vec3(1, 1, 1),
                 uniform(Voxel{1.0f, 0.0f, 1.0f, 1.0f}));
    const Medium salty(make("slab_volume", "file = \"oversalted.exr\"\n" + albedos));
    const auto t = salty.sample_distance(Vec3(0.5f, 0.5f, -1.0f), Vec3(0, 0, 1), 10.0f, 0.3f);
    ASSERT_TRUE(t.scattered);
    EXPECT_NEAR(t.weight[0], 0.7f, 1e-5f);

    // Gains turn small concentrations into cover: iron 0.05 × 10 = 0.5 → 0.5·0.8 + 0.5·0.4
    write_volume("traces", 2, 2, 2, Vec3(0, 0, 0), Vec3(1, 1, 1),
                 uniform(Voxel{1.0f, 0.0f, 0.05f, 0.0f}));
    const Medium traces(make("slab_volume", "file = \"traces.exr\"\niron_gain = 10.0\n" + albedos));
    const auto g = traces.sample_distance(Vec3(0.5f, 0.5f, -1.0f), Vec3(0, 0, 1), 10.0f, 0.3f);
    ASSERT_TRUE(g.scattered);
    EXPECT_NEAR(g.weight[0], 0.6f, 1e-5f);

    // A coloured albedo differs per wavelength: iron oxide reflects red more than blue
    write_volume("rusty", 2, 2, 2, Vec3(0, 0, 0), Vec3(1, 1, 1),
                 uniform(Voxel{1.0f, 0.0f, 1.0f, 0.0f}));
    const Medium rusty(make("slab_volume", "file = \"rusty.exr\"\nsigma_t = 1000.0\n"));
    const auto r = rusty.sample_distance(Vec3(0.5f, 0.5f, -1.0f), Vec3(0, 0, 1), 10.0f, 0.3f);
    ASSERT_TRUE(r.scattered);
    EXPECT_GT(r.weight[3], r.weight[0] + 0.2f) << "680 nm against 450 nm";
}

TEST(SlabVolume, OutsideTheVolumeNothingHappens)
{
    solid_block();
    const Medium m(make("slab_volume", "file = \"solid.exr\"\nsigma_t = 50.0\n"));
    // A ray that misses the box: transmittance 1, no collision
    EXPECT_EQ(m.transmittance(Vec3(-3, 2, 0), Vec3(1, 0, 0), 10.0f, 0.4f), 1.0f);
    EXPECT_FALSE(m.sample_distance(Vec3(-3, 2, 0), Vec3(1, 0, 0), 10.0f, 0.4f).scattered);
    // Same inputs, same answer (the tracking stream is a function of u and the ray)
    const auto a = m.sample_distance(Vec3(-3, 0, 0), Vec3(1, 0, 0), 10.0f, 0.4f);
    const auto b = m.sample_distance(Vec3(-3, 0, 0), Vec3(1, 0, 0), 10.0f, 0.4f);
    EXPECT_TRUE(a.scattered);
    EXPECT_EQ(a.t, b.t);
}

TEST(SlabVolume, BadFilesGiveErrorsNamingTheFile)
{
    // Missing: the host refuses the file parameter
    EXPECT_NE(error_of("slab_volume", "file = \"missing.exr\"").find("missing.exr"),
              std::string::npos);
    // None given
    EXPECT_NE(error_of("slab_volume", "sigma_t = 1.0").find("no slab volume file"),
              std::string::npos);

    // One part only: no bounds
    {
        const fs::path path = scratch_dir() / "one_part.exr";
        auto out = OIIO::ImageOutput::create(path.string());
        const OIIO::ImageSpec spec(4, 16, 4, OIIO::TypeDesc::FLOAT);
        std::vector<float> pixels(4 * 16 * 4, 0.5f);
        ASSERT_TRUE(out && out->open(path.string(), spec) &&
                    out->write_image(OIIO::TypeDesc::FLOAT, pixels.data()) && out->close());
        const std::string e = error_of("slab_volume", "file = \"one_part.exr\"");
        EXPECT_NE(e.find("one_part.exr"), std::string::npos) << e;
        EXPECT_NE(e.find("cannot read part 1"), std::string::npos) << e;
        EXPECT_NE(e.find("the file has 1 readable part "), std::string::npos) << e;
    }

    // The bounds claim 5 × 4 × 4 voxels, the voxel part holds 4 × 16
    {
        const float counts[3] = {5.0f, 4.0f, 4.0f};
        write_volume("wrong_dims", 4, 4, 4, Vec3(0, 0, 0), Vec3(1, 1, 1), uniform(Voxel{}), counts);
        const std::string e = error_of("slab_volume", "file = \"wrong_dims.exr\"");
        EXPECT_NE(e.find("wrong_dims.exr"), std::string::npos) << e;
        EXPECT_NE(e.find("4 x 16 pixels"), std::string::npos) << e;
        EXPECT_NE(e.find("5 x 4 x 4 voxels"), std::string::npos) << e;
    }
    // A voxel count that is not an integer
    {
        const float counts[3] = {4.0f, 4.5f, 4.0f};
        write_volume("fractional", 4, 4, 4, Vec3(0, 0, 0), Vec3(1, 1, 1), uniform(Voxel{}), counts);
        const std::string e = error_of("slab_volume", "file = \"fractional.exr\"");
        EXPECT_NE(e.find("fractional.exr"), std::string::npos) << e;
        EXPECT_NE(e.find("axis y"), std::string::npos) << e;
    }
    // Inverted bounds
    {
        write_volume("inverted", 2, 2, 2, Vec3(0, 1, 0), Vec3(1, 0, 1), uniform(Voxel{}));
        const std::string e = error_of("slab_volume", "file = \"inverted.exr\"");
        EXPECT_NE(e.find("inverted.exr"), std::string::npos) << e;
        EXPECT_NE(e.find("axis y"), std::string::npos) << e;
    }
    // A density above 1
    {
        write_volume("too_dense", 2, 2, 2, Vec3(0, 0, 0), Vec3(1, 1, 1), [](int i, int j, int k) {
            Voxel v;
            if (i == 1 && j == 0 && k == 1)
                v.density = 1.5f;
            return v;
        });
        const std::string e = error_of("slab_volume", "file = \"too_dense.exr\"");
        EXPECT_NE(e.find("too_dense.exr"), std::string::npos) << e;
        EXPECT_NE(e.find("voxel (1, 0, 1) has density = 1.5"), std::string::npos) << e;
    }
}
