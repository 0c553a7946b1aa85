#include "texgen/deposit/deposit_baker.h"

#include "texgen/deposit/source_visibility.h"
#include "texgen/wetness/bake_fixture.h"

#include <gtest/gtest.h>

#include "texgen/bake_test_util.h"
#include <tbb/global_control.h>

#include "test_util.h"

#include <cmath>
#include <numbers>

namespace patina::texgen {
namespace {

    using patina::test::message_of;
    using namespace patina::texgen::test;

    constexpr double kPi = std::numbers::pi;

    TriangleMesh ground()
    {
        return make_plane(Imath::V3f(0.0f), 200.0f);
    }

    // Visibility of one source from a sample, through the baker (accessibility weight 0,
    // visibility weight 1), so the whole evaluate path is exercised.
    float visibility_of(const EmbreeScene& scene, const DepositSource& source,
                        const SurfaceSample& s, int rays = 4096)
    {
        DepositParameters p;
        p.sources = {source};
        p.rays = rays;
        p.accessibility_weight = 0.0f;
        p.visibility_weight = 1.0f;
        const DepositBaker baker(scene, scene.bounds(), p);
        return bake_one(baker, s);
    }

    DepositSource sphere(const Imath::V3f& c, float r)
    {
        DepositSource s;
        s.kind = DepositSource::Kind::Sphere;
        s.center = c;
        s.radius = r;
        return s;
    }

    TEST(Deposit, SphereStraightAboveHasFormFactorRadiusOverDistanceSquared)
    {
        // Nusselt's analogue: the cone of half-angle asin(R/d) straight above projects onto a disc
        // of radius R/d in the unit disc, so F = (1/pi) int cos dw = (R/d)^2 (Howell, "A Catalog
        // of Radiation Heat Transfer Configuration Factors", differential area to sphere).
        const auto scene = make_scene({ground()});
        const SurfaceSample s = sample_at(Imath::V3f(0.0f), {0, 1, 0});
        for (const auto& [r, d] : {std::pair{1.0f, 4.0f}, std::pair{0.5f, 1.0f}, {2.0f, 2.5f}}) {
            const double expected = (r / d) * (r / d);
            EXPECT_NEAR(visibility_of(*scene, sphere({0.0f, d, 0.0f}, r), s), expected,
                        0.005 * expected)
                << "R " << r << " d " << d;
        }
    }

    TEST(Deposit, TiltedSphereFullyAboveHasFormFactorTimesCosine)
    {
        // A sphere wholly above the element's plane, its centre at angle beta from the normal:
        // F = (R/d)^2 cos(beta) (Howell's catalog, differential area to sphere).
        const auto scene = make_scene({ground()});
        const SurfaceSample s = sample_at(Imath::V3f(0.0f), {0, 1, 0});
        const float d = 5.0f, r = 1.0f;
        for (float beta_deg : {30.0f, 60.0f}) {
            const float beta = beta_deg * static_cast<float>(kPi) / 180.0f;
            const DepositSource src = sphere({d * std::sin(beta), d * std::cos(beta), 0.0f}, r);
            const double expected = (r / d) * (r / d) * std::cos(beta);
            EXPECT_NEAR(visibility_of(*scene, src, s), expected, 0.005 * expected) << beta_deg;
        }
    }

    TEST(Deposit, CoaxialDiscAndCornerRectangleMatchTheirFormFactors)
    {
        const auto scene = make_scene({ground()});
        const SurfaceSample s = sample_at(Imath::V3f(0.0f), {0, 1, 0});
        // Element to a parallel coaxial disc of radius R at height h: F = R^2 / (R^2 + h^2)
        // (Howell's catalog, differential planar element to parallel disc).
        DepositSource disc;
        disc.kind = DepositSource::Kind::Disc;
        disc.center = {0.0f, 2.0f, 0.0f};
        disc.normal = {0.0f, -1.0f, 0.0f};
        disc.radius = 1.5f;
        EXPECT_NEAR(visibility_of(*scene, disc, s), 2.25 / (2.25 + 4.0), 0.005);
        // The disc deposits on both sides.
        disc.normal = {0.0f, 1.0f, 0.0f};
        EXPECT_NEAR(visibility_of(*scene, disc, s), 2.25 / (2.25 + 4.0), 0.005);
        // Element to a parallel a x b rectangle at height c, the normal through a corner:
        // F = 1/(2 pi) [X/sqrt(1+X^2) atan(Y/sqrt(1+X^2)) + Y/sqrt(1+Y^2) atan(X/sqrt(1+Y^2))],
        // X = a/c, Y = b/c (Howell's catalog, differential element to parallel rectangle).
        DepositSource rect;
        rect.kind = DepositSource::Kind::Rectangle;
        rect.corner = {0.0f, 1.0f, 0.0f};
        rect.edge1 = {2.0f, 0.0f, 0.0f};
        rect.edge2 = {0.0f, 0.0f, 1.0f};
        const double x = 2.0, y = 1.0;
        const double expected = (x / std::sqrt(1 + x * x) * std::atan(y / std::sqrt(1 + x * x)) +
                                 y / std::sqrt(1 + y * y) * std::atan(x / std::sqrt(1 + y * y))) /
                                (2.0 * kPi);
        EXPECT_NEAR(visibility_of(*scene, rect, s), expected, 0.01 * expected);
    }

    TEST(Deposit, AnOccluderBlocksTheSource)
    {
        const TriangleMesh plane = ground();
        const DepositSource src = sphere({0.0f, 4.0f, 0.0f}, 1.0f);
        const SurfaceSample s = sample_at(Imath::V3f(0.0f), {0, 1, 0});
        // A 4 m square at y = 2 hides the whole sphere (its cone reaches 0.52 m at that height).
        const auto blocked =
            make_scene({plane, make_quad({0.0f, 2.0f, 0.0f}, 4.0f, Imath::V3f(0.0f, -1.0f, 0.0f))});
        EXPECT_EQ(visibility_of(*blocked, src, s), 0.0f);
        // A half-plane over x < 0 at y = 2 hides exactly half of the cone (symmetry about x = 0).
        const auto half = make_scene(
            {plane, make_quad({-50.0f, 2.0f, 0.0f}, 100.0f, Imath::V3f(0.0f, -1.0f, 0.0f))});
        EXPECT_NEAR(visibility_of(*half, src, s), 0.5 * 0.0625, 0.005 * 0.0625);
        // Geometry beyond the source does not block it.
        const auto behind = make_scene(
            {plane, make_quad({0.0f, 6.0f, 0.0f}, 10.0f, Imath::V3f(0.0f, -1.0f, 0.0f))});
        EXPECT_NEAR(visibility_of(*behind, src, s), 0.0625, 0.005 * 0.0625);
    }

    TEST(Deposit, DirectionalSourceIsTheNormalisedCatch)
    {
        const auto scene = make_scene({ground()});
        DepositSource wind;
        wind.kind = DepositSource::Kind::Directional;
        wind.direction = {0.0f, -1.0f, 0.0f};
        wind.spread_deg = 20.0f;
        // An open surface facing the source: exactly 1 (ratio estimator, directional_catch.h).
        EXPECT_NEAR(visibility_of(*scene, wind, sample_at(Imath::V3f(0.0f), {0, 1, 0}), 64), 1.0f,
                    1e-6f);
        // Facing away: nothing.
        EXPECT_EQ(visibility_of(*scene, wind, sample_at({0.0f, -1.0f, 0.0f}, {0, -1, 0}), 64),
                  0.0f);
    }

    TEST(Deposit, StrengthsAddAndVisibilityClampsAtOne)
    {
        const auto scene = make_scene({ground()});
        const SurfaceSample s = sample_at(Imath::V3f(0.0f), {0, 1, 0});
        DepositParameters p;
        p.sources = {sphere({0.0f, 4.0f, 0.0f}, 1.0f), sphere({0.0f, 2.0f, 0.0f}, 1.0f)};
        p.sources[0].strength = 2.0f;
        p.rays = 1024;
        const DepositBaker baker(*scene, scene->bounds(), p);
        Pcg32 rng(3);
        // 2 (1/4)^2 + (1/2)^2 = 0.375.
        EXPECT_NEAR(baker.visibility(s, 1, rng), 0.375f, 0.005f);
        p.sources[1].strength = 10.0f;
        const DepositBaker strong(*scene, scene->bounds(), p);
        EXPECT_EQ(strong.visibility(s, 1, rng), 1.0f);
    }

    TEST(Deposit, CombinesAccessibilityFromAMapAsDocumented)
    {
        // deposit = clamp(w_a (1 - A)^a + w_v V, 0, 1), or (1 - A)^a V with combine = product.
        const int w = 4, h = 2;
        const auto map =
            write_map(scratch("deposit_test", "accessibility.exr"), "accessibility", w, h,
                      [](int x, int y) { return 0.25f * static_cast<float>(x) + 0.1f * y; });
        const auto scene = make_scene({ground()});
        DepositParameters p;
        p.sources = {sphere({0.0f, 2.0f, 0.0f}, 1.0f)}; // F = 1/4 from the origin
        p.rays = 1024;
        p.accessibility_map = map;
        p.accessibility_power = 2.0f;
        p.accessibility_weight = 0.6f;
        p.visibility_weight = 0.8f;
        const DepositBaker sum(*scene, scene->bounds(), p, kOcioConfig);
        p.combine = DepositParameters::Combine::Product;
        const DepositBaker product(*scene, scene->bounds(), p, kOcioConfig);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const SurfaceSample s =
                    sample_at(Imath::V3f(0.0f), {0, 1, 0}, texel_centre(x, y, w, h));
                const float a = 0.25f * static_cast<float>(x) + 0.1f * y;
                const float hidden = (1.0f - a) * (1.0f - a);
                EXPECT_NEAR(bake_one(sum, s), std::min(1.0f, 0.6f * hidden + 0.8f * 0.25f), 0.002f);
                EXPECT_NEAR(bake_one(product, s), hidden * 0.25f, 0.002f);
            }
        // A map without the channel names its file and channels.
        p.accessibility_map =
            write_map(scratch("deposit_test", "ao.exr"), "ao", 2, 2, [](int, int) { return 1.0f; });
        const std::string msg =
            message_of([&] { DepositBaker b(*scene, scene->bounds(), p, kOcioConfig); });
        EXPECT_NE(msg.find("ao.exr"), std::string::npos) << msg;
        EXPECT_NE(msg.find("no channel 'accessibility' (it has: ao)"), std::string::npos) << msg;
    }

    TEST(Deposit, InlineAccessibilityIsOneInTheOpenAndAHalfAtACrease)
    {
        // Without a map, A is the cosine-weighted unoccluded fraction. On an open plane A = 1; at
        // the foot of a wall (a right-angle crease) the wall's plane contains the normal and
        // cuts the projected unit disc in half (Nusselt's analogue): A = 1/2.
        const TriangleMesh plane = ground();
        const TriangleMesh wall = make_plane({0.0f, 50.0f, 0.0f}, 100.0f, 1, Imath::V3f(1, 0, 0));
        const auto scene = make_scene({plane, wall});
        DepositParameters p;
        p.access_rays = 4096;
        p.access_distance = 1000.0f;
        p.accessibility_weight = 1.0f;
        p.visibility_weight = 0.0f;
        const DepositBaker baker(*scene, scene->bounds(), p);
        const auto open_scene = make_scene({plane});
        const DepositBaker open(*open_scene, open_scene->bounds(), p);
        Pcg32 rng(5);
        EXPECT_EQ(open.accessibility(sample_at({30.0f, 0.0f, 0.0f}, {0, 1, 0}), 1, rng), 1.0f);
        EXPECT_NEAR(baker.accessibility(sample_at({1e-3f, 0.0f, 0.0f}, {0, 1, 0}), 1, rng), 0.5f,
                    0.01f);
        // deposit = (1 - A)^1 with weights (1, 0).
        EXPECT_EQ(bake_one(open, sample_at({30.0f, 0.0f, 0.0f}, {0, 1, 0})), 0.0f);
        EXPECT_NEAR(bake_one(baker, sample_at({1e-3f, 0.0f, 0.0f}, {0, 1, 0})), 0.5f, 0.01f);
        // The default ray length is a tenth of the scene's bounding-box diagonal.
        p.access_distance = 0.0f;
        const DepositBaker defaults(*scene, scene->bounds(), p);
        const Imath::Box3f b = scene->bounds();
        EXPECT_FLOAT_EQ(defaults.access_distance(), 0.1f * (b.max - b.min).length());
    }

    TEST(Deposit, SameSeedSameBitsForAnyThreadCount)
    {
        const TriangleMesh plane = ground();
        const auto scene = make_scene(
            {plane, make_quad({-50.0f, 1.0f, 0.0f}, 100.0f, Imath::V3f(0.0f, -1.0f, 0.0f))});
        DepositParameters p;
        p.sources = {sphere({0.0f, 3.0f, 0.0f}, 1.0f)};
        DepositSource disc;
        disc.kind = DepositSource::Kind::Disc;
        disc.center = {2.0f, 2.0f, 0.0f};
        disc.radius = 1.0f;
        p.sources.push_back(disc);
        p.rays = 8;
        p.access_rays = 8;
        const DepositBaker baker(*scene, scene->bounds(), p);
        std::vector<SurfaceSample> samples;
        for (int i = 0; i < 500; ++i)
            samples.push_back(
                sample_at({-1.0f + 0.004f * static_cast<float>(i), 0.0f, 0.0f}, {0, 1, 0}));
        const SampleGroups groups = one_per_group(samples);
        const std::vector<float> one =
            patina::test::bake_with_threads(groups, baker, {11, 1001, nullptr}, 1);
        const std::vector<float> two =
            patina::test::bake_with_threads(groups, baker, {11, 1001, nullptr}, 2);
        EXPECT_EQ(one, two);
        EXPECT_NE(one, bake_groups(groups, baker, {12, 1001, nullptr}));
    }

    TEST(Deposit, NeedsASourceUnlessVisibilityIsUnused)
    {
        const auto scene = make_scene({ground()});
        DepositParameters p;
        const std::string msg = message_of([&] { DepositBaker b(*scene, scene->bounds(), p); });
        EXPECT_NE(msg.find("--source"), std::string::npos) << msg;
        p.visibility_weight = 0.0f;
        EXPECT_NO_THROW(DepositBaker(*scene, scene->bounds(), p));
        p.accessibility_power = -1.0f;
        EXPECT_NE(message_of([&] {
                      DepositBaker b(*scene, scene->bounds(), p);
                  }).find("--accessibility-power"),
                  std::string::npos);
    }

} // namespace
} // namespace patina::texgen
