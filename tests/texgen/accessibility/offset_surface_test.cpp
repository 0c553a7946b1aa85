#include "texgen/accessibility/offset_surface_baker.h"

#include "core/mesh.h"
#include "texgen/accessibility/test_wedge.h"
#include "texgen/bake/bake_driver.h"
#include "test_util.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>

namespace patina::texgen {
namespace {

    constexpr double kPi = std::numbers::pi;

    TEST(ClosedSurface, OpenPlaneIsItsOwnClosing)
    {
        // Every point of a plane is touched by an r-ball: the closed surface is the plane.
        EmbreeScene scene;
        scene.add_mesh(make_plane(Imath::V3f(0), 2.0f, 2));
        scene.commit();
        const ClosestPointScene closest(scene);
        const ClosedSurface closed(closest, scene.bounds(), 0.2f, 64);
        for (float x : {-0.7f, -0.13f, 0.0f, 0.41f})
            EXPECT_NEAR(closed.height({x, 0.0f, 0.3f * x}, {0, 1, 0}), 0.0f,
                        0.25f * closed.voxel_size());
    }

    // The surface of a wedge of opening angle alpha closed by a ball of radius r: the ball
    // wedged in the groove touches both faces, its centre on the bisector at r / sin(alpha/2)
    // from the crease, so the closed surface passes over the crease at a height
    // r / sin(alpha / 2) - r along the bisector, and meets face 1 where the ball touches it,
    // at r / tan(alpha / 2) from the crease (height 0 beyond).
    TEST(ClosedSurface, VGrooveHeightMatchesTheWedgedBall)
    {
        const float r = 0.1f;
        for (double alpha_deg : {60.0, 90.0}) {
            const double alpha = alpha_deg * kPi / 180.0;
            EmbreeScene scene;
            scene.add_mesh(test::make_wedge(alpha, 0.5f, 0.5f));
            scene.commit();
            const ClosestPointScene closest(scene);
            const ClosedSurface closed(closest, scene.bounds(), r, 128);
            const float h = closed.voxel_size();
            const Imath::V3f bisector(std::cos(alpha / 2), std::sin(alpha / 2), 0.0f);
            const double expected = r / std::sin(alpha / 2) - r;
            EXPECT_NEAR(closed.height({0, 0, 0}, bisector), expected, 0.75 * h)
                << "alpha " << alpha_deg;
            // On face 1, beyond the contact point, the ball touches the face itself.
            const float contact = r / std::tan(alpha / 2);
            EXPECT_NEAR(closed.height({contact + 0.05f, 0, 0}, {0, 1, 0}), 0.0f, 0.25f * h);
            // Between the crease and the contact, the closed surface is the ball's arc:
            // straight up from (x, 0) it lies at y = c_y - sqrt(r^2 - (x - c_x)^2).
            const float x = 0.5f * contact;
            const double cx = contact, cy = r;
            const double arc = cy - std::sqrt(r * r - (x - cx) * (x - cx));
            EXPECT_NEAR(closed.height({x, 0, 0}, {0, 1, 0}), arc, 0.75 * h);
        }
    }

    TEST(OffsetSurfaceBaker, ChannelsAndDeterminism)
    {
        // A 45 deg groove and r = 0.1 m: over the crease the closed surface lies
        // r / sin(22.5 deg) - r = 0.161 m > r up the bisector (accessibility 0); the wedged
        // ball touches face 1 at r / tan(22.5 deg) = 0.241 m, so beyond it the ball
        // reaches the face (accessibility 1).
        const double alpha = kPi / 4;
        EmbreeScene scene;
        scene.add_mesh(test::make_wedge(alpha, 0.5f, 0.5f));
        scene.commit();
        SampleGroups groups;
        const Imath::V3f bisector(std::cos(alpha / 2), std::sin(alpha / 2), 0.0f);
        groups.add_group({test::make_sample(Imath::V3f(0.0f), bisector, bisector)});
        for (int i = 1; i < 64; ++i)
            groups.add_group({test::wedge_face_sample(0.26f + 0.003f * i)});
        std::vector<float> one, two;
        {
            tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
            OffsetSurfaceBaker baker(scene, scene.bounds(), {0.1f, 48});
            ASSERT_EQ(baker.channels(), (std::vector<std::string>{"accessibility",
                                                                  "offset_height"}));
            one = bake_groups(groups, baker, {0, 0, nullptr});
        }
        {
            tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
            OffsetSurfaceBaker baker(scene, scene.bounds(), {0.1f, 48});
            two = bake_groups(groups, baker, {0, 0, nullptr});
        }
        EXPECT_EQ(one, two);
        EXPECT_EQ(one[0], 0.0f);
        // 48 voxels: h = 0.016 m. The free-ball centres nearest the groove's apex lie up to
        // about h / sin(alpha / 2) from it in a narrow groove: allow 2 h.
        EXPECT_NEAR(one[1], 0.1 / std::sin(alpha / 2) - 0.1, 2 * 0.7 / 44);
        for (int i = 1; i < 64; ++i)
            EXPECT_GT(one[2 * i], 0.95f) << i;
        for (int i = 0; i < 64; ++i)
            EXPECT_FLOAT_EQ(one[2 * i], 1.0f - std::clamp(one[2 * i + 1] / 0.1f, 0.0f, 1.0f));
    }

    TEST(ClosedSurface, BadParametersAreNamed)
    {
        EmbreeScene scene;
        scene.add_mesh(make_plane(Imath::V3f(0), 1.0f));
        scene.commit();
        const ClosestPointScene closest(scene);
        EXPECT_NE(test::message_of([&] { ClosedSurface(closest, scene.bounds(), 0.1f, 4); })
                      .find("--voxels"),
                  std::string::npos);
        EXPECT_NE(test::message_of([&] { ClosedSurface(closest, scene.bounds(), -1.0f, 64); })
                      .find("--max-radius"),
                  std::string::npos);
    }

}  // namespace
}  // namespace patina::texgen
