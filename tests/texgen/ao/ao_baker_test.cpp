#include "texgen/ao/ao_baker.h"

#include "core/mesh.h"
#include "texgen/accessibility/test_wedge.h"
#include "texgen/ao/sobol02.h"
#include "texgen/bake/bake_driver.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include "texgen/bake_test_util.h"
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>
#include <set>

namespace patina::texgen {
namespace {

    constexpr double kPi = std::numbers::pi;

    /// Mean AO over `count` one-sample groups at distances d_i from the crease.
    double mean_ao(const SampleBaker& baker, const std::vector<SurfaceSample>& samples)
    {
        SampleGroups groups;
        for (const SurfaceSample& s : samples)
            groups.add_group({s});
        const std::vector<float> values = bake_groups(groups, baker, {7, 0, nullptr});
        double sum = 0.0;
        for (float v : values)
            sum += v;
        return sum / static_cast<double>(values.size());
    }

    TEST(Sobol02, FirstPointsAreAZeroTwoNet)
    {
        // Any 2^k first points of a (0,2)-sequence put one point in each of the 2^k
        // elementary intervals of every shape 2^-a x 2^-(k-a) (Niederreiter 1992, Def. 4.1),
        // whatever the XOR scramble.
        const uint32_t scramble0 = 0x9e3779b9u, scramble1 = 0x7f4a7c15u;
        const int k = 6, n = 1 << k;
        for (int a = 0; a <= k; ++a) {
            std::set<std::pair<uint32_t, uint32_t>> cells;
            for (int i = 0; i < n; ++i) {
                // (A shift by 32 is undefined, and on x86 shifts by 0: the a = 0 shape would
                // compare whole values. UBSan found it.)
                const uint32_t x = a == 0 ? 0 : sobol02_dimension0(i, scramble0) >> (32 - a);
                const uint32_t y = a == k ? 0 : sobol02_dimension1(i, scramble1) >> (32 - (k - a));
                cells.insert({x, y});
            }
            EXPECT_EQ(static_cast<int>(cells.size()), n) << "shape 2^-" << a;
        }
    }

    TEST(AoBaker, OpenPlaneIsExactlyOne)
    {
        EmbreeScene scene;
        scene.add_mesh(make_plane(Imath::V3f(0), 4.0f, 8));
        scene.commit();
        AoBaker baker(scene, {256});
        std::vector<SurfaceSample> samples;
        for (int i = 0; i < 16; ++i) {
            samples.push_back(test::make_sample(Imath::V3f(-1.5f + 0.2f * i, 0.0f, 0.1f * i - 0.8f),
                                                Imath::V3f(0, 1, 0), Imath::V3f(0, 1, 0)));
        }
        SampleGroups groups;
        groups.add_group(samples);
        const std::vector<float> values = bake_groups(groups, baker, {1, 0, nullptr});
        ASSERT_EQ(values.size(), 1u);
        EXPECT_EQ(values[0], 1.0f);
    }

    // The occluded directions at a point on one face of a V-groove of opening angle alpha
    // (long faces) are those that reach the other face: the lune between this face's plane
    // and the plane through P parallel to the other face, of dihedral angle pi - alpha. A
    // lune of dihedral angle phi bounded by the horizon projects onto the unit disk as a
    // half disk minus a half ellipse of semi-axes 1 and cos phi, so by Nusselt's analogue
    // its cosine-weighted fraction is (pi/2 - pi/2 cos phi) / pi = (1 - cos phi) / 2
    // (Cohen & Wallace 1993, "Radiosity and Realistic Image Synthesis", §4.6). Hence
    //   AO = 1 - (1 - cos(pi - alpha)) / 2 = (1 - cos alpha) / 2, independent of d.
    TEST(AoBaker, VGrooveMatchesTheVisibleLune)
    {
        for (double alpha_deg : {45.0, 90.0, 135.0}) {
            const double alpha = alpha_deg * kPi / 180.0;
            EmbreeScene scene;
            scene.add_mesh(test::make_wedge(alpha, 100.0f, 100.0f));
            scene.commit();
            AoBaker baker(scene, {1024});
            std::vector<SurfaceSample> samples;
            for (int i = 0; i < 32; ++i)
                samples.push_back(test::wedge_face_sample(0.01f + 0.002f * i));
            const double expected = (1.0 - std::cos(alpha)) / 2.0;
            EXPECT_NEAR(mean_ao(baker, samples), expected, 0.01 * expected)
                << "alpha " << alpha_deg << " deg";
        }
    }

    TEST(AoBaker, MaxDistanceIgnoresFartherOccluders)
    {
        // Right-angle groove, P at 1 m from the crease: every ray that reaches the other
        // face travels at least 1 m, so with a 0.5 m limit nothing occludes.
        EmbreeScene scene;
        scene.add_mesh(test::make_wedge(kPi / 2, 100.0f, 100.0f));
        scene.commit();
        AoBaker near_only(scene, {256, 0.5f});
        AoBaker unlimited(scene, {256});
        const std::vector<SurfaceSample> samples = {test::wedge_face_sample(1.0f)};
        EXPECT_EQ(mean_ao(near_only, samples), 1.0);
        EXPECT_NEAR(mean_ao(unlimited, samples), 0.5, 0.01);
    }

    TEST(AoBaker, DirectionsBelowTheFacetCountAsOccluded)
    {
        // Open plane, shading normal tilted 60 deg from Ng: the directions of the cosine
        // lobe about N that go below the facet form a lune of dihedral angle 60 deg, a
        // fraction (1 - cos 60 deg) / 2 = 1/4 (the lune formula above), so AO = 3/4.
        EmbreeScene scene;
        scene.add_mesh(make_plane(Imath::V3f(0), 4.0f));
        scene.commit();
        AoBaker baker(scene, {4096});
        const SurfaceSample s = test::make_sample(
            Imath::V3f(0.1f, 0.0f, 0.2f),
            Imath::V3f(std::sin(kPi / 3), std::cos(kPi / 3), 0.0f), Imath::V3f(0, 1, 0));
        EXPECT_NEAR(mean_ao(baker, {s}), 0.75, 0.005);
    }

    TEST(AoBaker, RayBudgetIsPerElement)
    {
        EmbreeScene scene;
        scene.add_mesh(make_plane(Imath::V3f(0), 1.0f));
        scene.commit();
        AoBaker baker(scene, {64});
        EXPECT_EQ(baker.rays_per_sample(1), 64u);
        EXPECT_EQ(baker.rays_per_sample(4), 16u);
        EXPECT_EQ(baker.rays_per_sample(3), 22u);  // rounded up: at least the budget
        EXPECT_EQ(baker.rays_per_sample(100), 1u); // at least one per sample
    }

    TEST(AoBaker, SameBitsForOneAndTwoThreads)
    {
        EmbreeScene scene;
        scene.add_mesh(make_plane(Imath::V3f(0), 4.0f, 4));
        scene.add_mesh(make_uv_sphere(Imath::V3f(0, 0.5f, 0), 0.6f, 16, 32));
        scene.commit();
        AoBaker baker(scene, {32});
        SampleGroups groups;
        for (int g = 0; g < 300; ++g) {
            std::vector<SurfaceSample> group;
            for (int k = 0; k < 3; ++k) {
                const Imath::V3f P(-1.5f + 0.01f * g, 0.0f, -0.5f + 0.3f * k);
                group.push_back(test::make_sample(P, Imath::V3f(0, 1, 0), Imath::V3f(0, 1, 0)));
            }
            groups.add_group(group);
        }
        const std::vector<float> one =
            patina::test::bake_with_threads(groups, baker, {42, 1001, nullptr}, 1);
        const std::vector<float> two =
            patina::test::bake_with_threads(groups, baker, {42, 1001, nullptr}, 2);
        EXPECT_EQ(one, two);
        // The sphere shadows the samples under it: some values are below 1.
        EXPECT_LT(*std::min_element(one.begin(), one.end()), 0.9f);
    }

    TEST(AoBaker, BadOptionsNameTheParameter)
    {
        EmbreeScene scene;
        scene.add_mesh(make_plane(Imath::V3f(0), 1.0f));
        scene.commit();
        EXPECT_NE(test::message_of([&] { AoBaker(scene, {0}); }).find("--rays"), std::string::npos);
        EXPECT_NE(test::message_of([&] { AoBaker(scene, {8, -1.0f}); }).find("--max-distance"),
                  std::string::npos);
    }

}  // namespace
}  // namespace patina::texgen
