#include "texgen/wetness/wetness_baker.h"

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

    // A large ground plane at y = 0 (the surface the samples lie on).
    TriangleMesh ground()
    {
        return make_plane(Imath::V3f(0.0f), 200.0f);
    }

    // A roof over x in [-100, 0], z in [-50, 50] at height h, facing down.
    TriangleMesh half_roof(float h)
    {
        return make_quad(Imath::V3f(-50.0f, h, 0.0f), 100.0f, Imath::V3f(0.0f, -1.0f, 0.0f));
    }

    TEST(Wetness, OpenHorizontalPlaneUnderVerticalRainIsOne)
    {
        // Catch max(0, -N.d) = 1 for N = up, d = down; incline = 1^p = 1: the documented maximum.
        const TriangleMesh plane = ground();
        const auto scene = make_scene({plane});
        for (float power : {0.0f, 1.0f, 3.0f}) {
            WetnessParameters p;
            p.inclination_power = power;
            const WetnessBaker baker(*scene, plane, p);
            EXPECT_FLOAT_EQ(bake_one(baker, sample_at({1.0f, 0.0f, 2.0f}, {0, 1, 0})), 1.0f);
        }
    }

    TEST(Wetness, OpenPlaneFacingSpreadRainIsOneExactly)
    {
        // The catch is normalised by the catch of an open surface facing the rain, computed with
        // the same directions (directional_catch.h), so it is 1 for any spread and ray count.
        const TriangleMesh plane = ground();
        const auto scene = make_scene({plane});
        WetnessParameters p;
        p.spread_deg = 60.0f;
        p.rays = 7;
        const WetnessBaker baker(*scene, plane, p);
        EXPECT_NEAR(bake_one(baker, sample_at({0.0f, 0.0f, 0.0f}, {0, 1, 0})), 1.0f, 1e-6f);
    }

    TEST(Wetness, VerticalWallCatchesNoVerticalRain)
    {
        // Catch factor max(0, -N.d) = 0 for N horizontal and d vertical.
        const TriangleMesh wall = make_plane(Imath::V3f(0.0f), 4.0f, 1, Imath::V3f(1, 0, 0));
        const auto scene = make_scene({wall});
        WetnessParameters p;
        p.inclination_power = 0.0f; // only the catch term can make it zero
        const WetnessBaker baker(*scene, wall, p);
        EXPECT_EQ(bake_one(baker, sample_at({0.0f, 0.5f, 0.0f}, {1, 0, 0})), 0.0f);
    }

    TEST(Wetness, WallFacingObliqueRainCatchesTheCosine)
    {
        // Rain travelling along (1, -1, 0)/sqrt(2) onto a wall facing -x: catch = cos 45 deg;
        // with inclination power 0 the inclination term is 1 (pow(0, 0) = 1).
        const TriangleMesh wall = make_plane(Imath::V3f(0.0f), 4.0f, 1, Imath::V3f(-1, 0, 0));
        const auto scene = make_scene({wall});
        WetnessParameters p;
        p.rain_direction = Imath::V3f(1.0f, -1.0f, 0.0f);
        p.inclination_power = 0.0f;
        const WetnessBaker baker(*scene, wall, p);
        EXPECT_NEAR(bake_one(baker, sample_at({0.0f, 0.5f, 0.0f}, {-1, 0, 0})), std::sqrt(0.5),
                    1e-6);
        // The default power 1 makes a vertical surface dry: max(0, N.U)^1 = 0.
        p.inclination_power = 1.0f;
        const WetnessBaker steep(*scene, wall, p);
        EXPECT_EQ(bake_one(steep, sample_at({0.0f, 0.5f, 0.0f}, {-1, 0, 0})), 0.0f);
    }

    TEST(Wetness, PlaneUnderRoofStaysDry)
    {
        const TriangleMesh plane = ground();
        const TriangleMesh roof =
            make_quad(Imath::V3f(0.0f, 2.0f, 0.0f), 10.0f, Imath::V3f(0.0f, -1.0f, 0.0f));
        const auto scene = make_scene({plane, roof});
        WetnessParameters p;
        const WetnessBaker baker(*scene, plane, p);
        EXPECT_EQ(bake_one(baker, sample_at({0.0f, 0.0f, 0.0f}, {0, 1, 0})), 0.0f);
        // Outside the roof's shadow the plane is wet again.
        EXPECT_FLOAT_EQ(bake_one(baker, sample_at({8.0f, 0.0f, 0.0f}, {0, 1, 0})), 1.0f);
        // A roof beyond --max-distance no longer shelters.
        p.max_distance = 1.5f;
        const WetnessBaker short_rays(*scene, plane, p);
        EXPECT_FLOAT_EQ(bake_one(short_rays, sample_at({0.0f, 0.0f, 0.0f}, {0, 1, 0})), 1.0f);
    }

    TEST(Wetness, TiltedPlaneFollowsTheInclinationLaw)
    {
        // Documented law (wetness_baker.h): vertical rain, no spread, open plane tilted by theta:
        // rain = cos(theta) (catch), incline = cos(theta)^p, wetness = cos(theta)^(1 + p).
        for (float deg : {10.0f, 30.0f, 60.0f}) {
            const double theta = deg * kPi / 180.0;
            const Imath::V3f n(static_cast<float>(std::sin(theta)),
                               static_cast<float>(std::cos(theta)), 0.0f);
            const TriangleMesh plane = make_plane(Imath::V3f(0.0f), 4.0f, 1, n);
            const auto scene = make_scene({plane});
            for (float power : {0.0f, 1.0f, 2.5f}) {
                WetnessParameters p;
                p.inclination_power = power;
                const WetnessBaker baker(*scene, plane, p);
                EXPECT_NEAR(bake_one(baker, sample_at(Imath::V3f(0.0f), n)),
                            std::pow(std::cos(theta), 1.0 + power), 1e-6)
                    << deg << " deg, power " << power;
            }
        }
    }

    // Under a half-roof at height h over x < 0, a point at x = a on the ground with N = up sees
    // rain from the cone of half-angle sigma about up. A direction (theta, phi) reaches the roof
    // plane at x = a + h tan(theta) cos(phi): it is blocked iff tan(theta) cos(phi) < -a/h, i.e.
    // for a fraction acos(t) / pi of phi with t = (a/h) / tan(theta) < 1. With mu = cos(theta)
    // uniform on [cos(sigma), 1] (uniform cone) and the catch weight mu, the normalised catch is
    //     W = int mu (1 - blocked(mu)) dmu / int mu dmu  over [cos(sigma), 1],
    // integrated here with Simpson's rule (a closed-form integrand).
    double half_roof_wetness(double a, double h, double sigma)
    {
        const auto f = [&](double mu) {
            const double tan_theta = std::sqrt(std::max(0.0, 1.0 - mu * mu)) / mu;
            // t = (a / h) / tan(theta); 0 under the edge (a = 0), infinite straight up.
            const double t = a == 0.0 ? 0.0 : (tan_theta > 0.0 ? (a / h) / tan_theta : 1e30);
            const double blocked = t < 1.0 ? std::acos(t) / kPi : 0.0;
            return mu * (1.0 - blocked);
        };
        const double lo = std::cos(sigma);
        const int n = 20000;
        const double step = (1.0 - lo) / n;
        double sum = f(lo) + f(1.0);
        for (int i = 1; i < n; ++i)
            sum += (i % 2 ? 4.0 : 2.0) * f(lo + i * step);
        const double numerator = sum * step / 3.0;
        const double denominator = 0.5 * (1.0 - lo * lo); // int mu dmu
        return numerator / denominator;
    }

    TEST(Wetness, SpreadUnderHalfRoofMatchesTheAnalyticConeFraction)
    {
        const TriangleMesh plane = ground();
        const auto scene = make_scene({plane, half_roof(1.0f)});
        WetnessParameters p;
        p.spread_deg = 40.0f;
        p.rays = 4096;
        const WetnessBaker baker(*scene, plane, p);
        for (double a : {0.0, 0.2, 0.5}) {
            const double expected = half_roof_wetness(a, 1.0, 40.0 * kPi / 180.0);
            const float got =
                bake_one(baker, sample_at({static_cast<float>(a), 0.0f, 0.0f}, {0, 1, 0}));
            // 4096 stratified rays: the estimate is within 0.005 of the integral.
            EXPECT_NEAR(got, expected, 0.005) << "a = " << a;
        }
        // Sanity of the reference: right under the edge half the cone is blocked (t = 0).
        EXPECT_NEAR(half_roof_wetness(0.0, 1.0, 0.7), 0.5, 1e-9);
        // Far from the edge, farther than h tan(sigma), nothing is blocked.
        EXPECT_NEAR(half_roof_wetness(2.0, 1.0, 40.0 * kPi / 180.0), 1.0, 1e-9);
    }

    TEST(Wetness, ExposureMapDriesAsDocumented)
    {
        // dry = 1 - drying * clamp(E / E_scale, 0, 1); E_scale = the map's maximum by default.
        const int w = 4, h = 4;
        const auto map = write_map(scratch("wetness_test", "exposure.exr"), "exposure", w, h,
                                   [](int x, int y) { return static_cast<float>(x + 4 * y); });
        const TriangleMesh plane = ground();
        const auto scene = make_scene({plane});
        WetnessParameters p;
        p.exposure_map = map;
        p.drying = 0.8f;
        const WetnessBaker baker(*scene, plane, p, kOcioConfig);
        EXPECT_FLOAT_EQ(baker.exposure_scale(), 15.0f);
        p.exposure_scale = 10.0f;
        const WetnessBaker scaled(*scene, plane, p, kOcioConfig);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const SurfaceSample s = sample_at({0, 0, 0}, {0, 1, 0}, texel_centre(x, y, w, h));
                const float e = static_cast<float>(x + 4 * y);
                // Bilinear lookups at texel centres return the texel.
                EXPECT_NEAR(bake_one(baker, s), 1.0f - 0.8f * e / 15.0f, 1e-5f) << x << "," << y;
                EXPECT_NEAR(bake_one(scaled, s), 1.0f - 0.8f * std::min(1.0f, e / 10.0f), 1e-5f);
            }
    }

    TEST(Wetness, ExposureMapErrorsNameTheFileAndChannels)
    {
        const auto map = write_map(scratch("wetness_test", "other.exr"), "thickness", 4, 4,
                                   [](int, int) { return 1.0f; });
        const TriangleMesh plane = ground();
        const auto scene = make_scene({plane});
        WetnessParameters p;
        p.exposure_map = map;
        const std::string msg =
            message_of([&] { WetnessBaker baker(*scene, plane, p, kOcioConfig); });
        EXPECT_NE(msg.find("other.exr"), std::string::npos) << msg;
        EXPECT_NE(msg.find("no channel 'exposure' or 'irradiance' (it has: thickness)"),
                  std::string::npos)
            << msg;
        p.exposure_map = scratch("wetness_test", "missing.exr");
        const std::string missing =
            message_of([&] { WetnessBaker baker(*scene, plane, p, kOcioConfig); });
        EXPECT_NE(missing.find("missing.exr"), std::string::npos) << missing;
        // A channel named explicitly is used.
        p.exposure_map = map;
        p.exposure_channel = "thickness";
        EXPECT_NO_THROW(WetnessBaker(*scene, plane, p, kOcioConfig));
    }

    TEST(Wetness, UdimExposureMapsAreReadPerTile)
    {
        const auto t1 = write_map(scratch("wetness_udim", "exp.1001.exr"), "exposure", 4, 4,
                                  [](int, int) { return 2.0f; });
        write_map(scratch("wetness_udim", "exp.1002.exr"), "exposure", 4, 4,
                  [](int, int) { return 4.0f; });
        const SurfaceMap map(t1.parent_path() / "exp.<UDIM>.exr", {"exposure"}, "exposure map",
                             kOcioConfig);
        EXPECT_EQ(map.udims(), (std::vector<int>{1001, 1002}));
        EXPECT_FLOAT_EQ(map.maximum(), 4.0f);
        EXPECT_FLOAT_EQ(map.at({0.3f, 0.6f}), 2.0f);
        EXPECT_FLOAT_EQ(map.at({1.3f, 0.6f}), 4.0f);
        // u = 3 is exactly on the right edge of tile 1003, which does not exist either.
        const std::string msg = message_of([&] { map.at({2.5f, 0.5f}); });
        EXPECT_NE(msg.find("no tile covers uv (2.5, 0.5)"), std::string::npos) << msg;
        // A uv exactly on the outer edge of the only tile reads that tile.
        const SurfaceMap single(t1, {"exposure"}, "exposure map", kOcioConfig);
        EXPECT_FLOAT_EQ(single.at({1.0f, 1.0f}), 2.0f);
    }

    TEST(Wetness, BaseAccumulationFallsOffLinearlyWithHeight)
    {
        // base = amount * max(0, 1 - (P.U - level) / height) on a wall (no rain caught).
        const TriangleMesh box = make_box(Imath::V3f(0.0f), Imath::V3f(2.0f)); // y in [-1, 1]
        const auto scene = make_scene({box});
        WetnessParameters p;
        p.base_height = 2.0f;
        p.base_amount = 0.5f;
        const WetnessBaker baker(*scene, box, p);
        EXPECT_FLOAT_EQ(baker.base_level(), -1.0f); // the mesh's lowest point
        for (float y : {-1.0f, -0.5f, 0.5f, 0.9f}) {
            const float expected = 0.5f * std::max(0.0f, 1.0f - (y + 1.0f) / 2.0f);
            EXPECT_NEAR(bake_one(baker, sample_at({1.0f, y, 0.0f}, {1, 0, 0})), expected, 1e-6f);
        }
        p.base_level = 0.0f;
        const WetnessBaker level(*scene, box, p);
        EXPECT_NEAR(bake_one(level, sample_at({1.0f, 0.5f, 0.0f}, {1, 0, 0})), 0.375f, 1e-6f);
        // Rain and base add up, then clamp to 1.
        EXPECT_FLOAT_EQ(bake_one(level, sample_at({0.0f, 1.0f, 0.0f}, {0, 1, 0})), 1.0f);
    }

    TEST(Wetness, SameSeedSameBitsForAnyThreadCount)
    {
        const TriangleMesh plane = ground();
        const auto scene = make_scene({plane, half_roof(0.5f)});
        WetnessParameters p;
        p.spread_deg = 30.0f;
        p.rays = 16;
        const WetnessBaker baker(*scene, plane, p);
        std::vector<SurfaceSample> samples;
        for (int i = 0; i < 500; ++i)
            samples.push_back(
                sample_at({-0.5f + 0.002f * static_cast<float>(i), 0.0f, 0.0f}, {0, 1, 0}));
        const SampleGroups groups = one_per_group(samples);
        const std::vector<float> one =
            patina::test::bake_with_threads(groups, baker, {7, 1001, nullptr}, 1);
        const std::vector<float> two =
            patina::test::bake_with_threads(groups, baker, {7, 1001, nullptr}, 2);
        EXPECT_EQ(one, two);
        EXPECT_NE(one, bake_groups(groups, baker, {8, 1001, nullptr}));
    }

    TEST(Wetness, BadParametersNameTheOption)
    {
        const TriangleMesh plane = ground();
        const auto scene = make_scene({plane});
        const auto message = [&](auto change) {
            WetnessParameters p;
            change(p);
            return message_of([&] { WetnessBaker baker(*scene, plane, p); });
        };
        EXPECT_NE(message([](WetnessParameters& p) { p.spread_deg = 90.0f; }).find("--spread-deg"),
                  std::string::npos);
        EXPECT_NE(message([](WetnessParameters& p) {
                      p.rain_direction = Imath::V3f(0.0f);
                  }).find("--rain-dir"),
                  std::string::npos);
        EXPECT_NE(message([](WetnessParameters& p) { p.drying = 1.5f; }).find("--drying"),
                  std::string::npos);
        EXPECT_NE(message([](WetnessParameters& p) { p.rays = 0; }).find("--rays"),
                  std::string::npos);
    }

} // namespace
} // namespace patina::texgen
