#include "texgen/accessibility/tangent_sphere_baker.h"

#include "core/mesh.h"
#include "texgen/accessibility/test_wedge.h"
#include "texgen/bake/bake_driver.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include "texgen/bake_test_util.h"
#include <tbb/global_control.h>

#include <cmath>
#include <numbers>

namespace patina::texgen {
namespace {

    constexpr double kPi = std::numbers::pi;

    TEST(ClosestPoint, TriangleRegions)
    {
        // Ericson 2005 §5.1.5: the face, edge and vertex Voronoi regions.
        const Imath::V3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
        const Imath::V3d face = closest_point_on_triangle({0.2, 0.3, 5.0}, a, b, c);
        EXPECT_NEAR((face - Imath::V3d(0.2, 0.3, 0)).length(), 0.0, 1e-15);
        const Imath::V3d edge = closest_point_on_triangle({1.0, 1.0, -2.0}, a, b, c);
        EXPECT_NEAR((edge - Imath::V3d(0.5, 0.5, 0)).length(), 0.0, 1e-15);
        const Imath::V3d vertex = closest_point_on_triangle({-1.0, -2.0, 0.5}, a, b, c);
        EXPECT_EQ(vertex, a);
    }

    TEST(TangentSphere, OpenPlaneGetsTheCap)
    {
        EmbreeScene scene;
        scene.add_mesh(make_plane(Imath::V3f(0), 10.0f, 4));
        scene.commit();
        const ClosestPointScene closest(scene);
        EXPECT_EQ(largest_tangent_sphere(closest, {0.3f, 0.0f, -1.2f}, {0, 1, 0}, 2.0), 2.0);
    }

    // A sphere tangent to face 1 at distance d from the crease, centre (d, r), touches
    // face 2 (the line through the origin at angle alpha) when d sin(alpha) - r cos(alpha)
    // = r, i.e. r = d sin(alpha) / (1 + cos(alpha)) = d tan(alpha / 2); the touching point,
    // at distance d from the crease on face 2, lies on the face. For the right-angle corner
    // r = d: the sphere centred at (d, d) touching both faces.
    TEST(TangentSphere, RightAngleCornerAndVGroove)
    {
        for (double alpha_deg : {90.0, 60.0, 120.0}) {
            const double alpha = alpha_deg * kPi / 180.0;
            EmbreeScene scene;
            scene.add_mesh(test::make_wedge(alpha, 20.0f, 20.0f));
            scene.commit();
            const ClosestPointScene closest(scene);
            for (float d : {0.01f, 0.1f, 0.37f, 1.5f}) {
                const double expected = d * std::tan(alpha / 2);
                const double r = largest_tangent_sphere(closest, {d, 0, 0}, {0, 1, 0}, 10.0);
                EXPECT_NEAR(r, expected, 1e-3 * expected) << "alpha " << alpha_deg << ", d " << d;
                // Proved empty: never above the true radius by more than the tolerance.
                EXPECT_LE(r, expected * (1 + 2e-5));
            }
        }
    }

    TEST(TangentSphere, SharpCreaseHasZeroRadius)
    {
        // At the crease itself every tangent sphere cuts the other face.
        EmbreeScene scene;
        scene.add_mesh(test::make_wedge(kPi / 3, 5.0f, 5.0f));
        scene.commit();
        const ClosestPointScene closest(scene);
        EXPECT_LT(largest_tangent_sphere(closest, {0, 0, 0}, {0, 1, 0}, 1.0), 1e-6);
    }

    TEST(TangentSphere, InsideASphereTheRadiusIsTheSpheres)
    {
        // Seen from inside a sphere of radius R, the largest tangent sphere is the sphere
        // itself. On the tessellated sphere, at the foot F of the centre on an equatorial
        // facet (these facets are the nearest to the centre, at d0), the sphere centred at
        // the centre O with radius d0 is tangent at F and meets no facet; any larger one
        // crosses the opposite equatorial facet. So r = d0 exactly, and d0 -> R.
        const float R = 1.0f;
        const Imath::V3f O(0.2f, -0.1f, 0.3f);
        const TriangleMesh sphere = make_uv_sphere(O, R, 64, 128);
        EmbreeScene scene;
        scene.add_mesh(sphere);
        scene.commit();
        const ClosestPointScene closest(scene);
        // The facet whose centroid is nearest the equator plane y = O.y.
        size_t best = 0;
        float best_y = 1e30f;
        for (size_t t = 0; t < sphere.triangle_count(); ++t) {
            const Imath::V3f c = (sphere.positions[sphere.indices[3 * t]] +
                                  sphere.positions[sphere.indices[3 * t + 1]] +
                                  sphere.positions[sphere.indices[3 * t + 2]]) / 3.0f;
            const float area = (sphere.positions[sphere.indices[3 * t + 1]] -
                                sphere.positions[sphere.indices[3 * t]])
                                   .cross(sphere.positions[sphere.indices[3 * t + 2]] -
                                          sphere.positions[sphere.indices[3 * t]])
                                   .length();
            if (area > 1e-6f && std::abs(c.y - O.y) < best_y) {
                best_y = std::abs(c.y - O.y);
                best = t;
            }
        }
        const Imath::V3d p0(sphere.positions[sphere.indices[3 * best]]);
        const Imath::V3d p1(sphere.positions[sphere.indices[3 * best + 1]]);
        const Imath::V3d p2(sphere.positions[sphere.indices[3 * best + 2]]);
        Imath::V3d inward = (p1 - p0).cross(p2 - p0).normalized();
        const Imath::V3d o(O.x, O.y, O.z);
        if (inward.dot(o - p0) < 0)
            inward = -inward;
        const double d0 = inward.dot(o - p0);
        const Imath::V3d foot = o - d0 * inward;
        const Imath::V3f F(foot.x, foot.y, foot.z), n(inward.x, inward.y, inward.z);
        const double r = largest_tangent_sphere(closest, F, n, 3.0);
        EXPECT_NEAR(r, d0, 1e-4 * d0);
        EXPECT_NEAR(r, R, 2e-3 * R);
    }

    TEST(TangentSphereBaker, ChannelsAndDeterminism)
    {
        EmbreeScene scene;
        scene.add_mesh(test::make_wedge(kPi / 2, 10.0f, 10.0f));
        scene.commit();
        TangentSphereBaker baker(scene, {0.5f});
        ASSERT_EQ(baker.channels(), (std::vector<std::string>{"accessibility",
                                                              "accessibility_radius"}));
        SampleGroups groups;
        for (int i = 0; i < 200; ++i)
            groups.add_group({test::wedge_face_sample(0.005f * (i + 1))});
        const std::vector<float> one =
            patina::test::bake_with_threads(groups, baker, {3, 0, nullptr}, 1);
        const std::vector<float> two =
            patina::test::bake_with_threads(groups, baker, {3, 0, nullptr}, 2);
        EXPECT_EQ(one, two);
        for (int i = 0; i < 200; ++i) {
            // Right-angle corner: r = d, capped at 0.5 m, normalised by the cap.
            const double d = 0.005 * (i + 1);
            const double r = std::min(d, 0.5);
            EXPECT_NEAR(one[2 * i + 1], r, 1e-3 * r) << i;
            EXPECT_NEAR(one[2 * i], r / 0.5, 1e-3 * r / 0.5) << i;
        }
    }

    TEST(TangentSphereBaker, BadRadiusIsNamed)
    {
        EmbreeScene scene;
        scene.add_mesh(make_plane(Imath::V3f(0), 1.0f));
        scene.commit();
        EXPECT_NE(test::message_of([&] { TangentSphereBaker(scene, {0.0f}); }).find("--max-radius"),
                  std::string::npos);
    }

}  // namespace
}  // namespace patina::texgen
