#include "core/embree_scene.h"
#include "core/sampling.h"

#include <gtest/gtest.h>

#include <atomic>
#include <cmath>
#include <cstring>
#include <numbers>
#include <random>
#include <stdexcept>
#include <thread>
#include <vector>

namespace patina {
namespace {

    constexpr float kPi = std::numbers::pi_v<float>;

    /// Analytic ray-sphere intersection (nearest t > 0), or -1 on a miss.
    float sphere_t(const Imath::V3f& o, const Imath::V3f& d, const Imath::V3f& c, float r)
    {
        const Imath::V3f oc = o - c;
        const float b = oc.dot(d), cc = oc.dot(oc) - r * r;
        const float disc = b * b - cc;
        if (disc < 0)
            return -1;
        const float t = -b - std::sqrt(disc);
        return t > 0 ? t : -b + std::sqrt(disc);
    }

    Imath::V3f random_unit(std::mt19937& rng)
    {
        std::uniform_real_distribution<float> u(-1.0f, 1.0f);
        for (;;) {
            const Imath::V3f v(u(rng), u(rng), u(rng));
            if (v.length2() > 1e-3f && v.length2() <= 1.0f)
                return v.normalized();
        }
    }

    // Sphere of radius 1 at the origin, tessellated finely: 128 rings, 256 segments. The
    // largest distance between the polyhedron and the sphere is below 1 - cos(pi / 128).
    constexpr float kSagitta = 3.1e-4f;

    struct SphereScene {
        EmbreeScene scene;
        int id;
        SphereScene() : id(scene.add_mesh(make_uv_sphere(Imath::V3f(0), 1.0f, 128, 256))) { scene.commit(); }
    };

}  // namespace

TEST(EmbreeScene, RayHitsSphereAtAnalyticDistanceAndMisses)
{
    SphereScene s;
    EXPECT_EQ(s.id, 0);
    // (0, 0, -1) is a vertex of the tessellation: t is exact up to rounding.
    const auto hit = s.scene.intersect(Imath::V3f(0, 0, -5), Imath::V3f(0, 0, 1));
    ASSERT_TRUE(hit);
    EXPECT_NEAR(hit->t, 4.0f, 1e-5f);
    EXPECT_EQ(hit->mesh_id, 0);
    // Direction need not be unit: t is in units of |dir|.
    const auto scaled = s.scene.intersect(Imath::V3f(0, 0, -5), Imath::V3f(0, 0, 2));
    ASSERT_TRUE(scaled);
    EXPECT_NEAR(scaled->t, 2.0f, 1e-5f);

    EXPECT_FALSE(s.scene.intersect(Imath::V3f(0, 1.01f, -5), Imath::V3f(0, 0, 1)));
    EXPECT_FALSE(s.scene.intersect(Imath::V3f(0, 0, -5), Imath::V3f(0, 0, -1)));
    // tmax before the sphere, tmin past it.
    EXPECT_FALSE(s.scene.intersect(Imath::V3f(0, 0, -5), Imath::V3f(0, 0, 1), 0.0f, 3.9f));
    const auto far_side = s.scene.intersect(Imath::V3f(0, 0, -5), Imath::V3f(0, 0, 1), 4.5f);
    ASSERT_TRUE(far_side);
    EXPECT_NEAR(far_side->t, 6.0f, 1e-5f);
}

TEST(EmbreeScene, Occlusion)
{
    SphereScene s;
    const Imath::V3f o(0, 0, -5), d(0, 0, 1);
    EXPECT_TRUE(s.scene.occluded(o, d));
    EXPECT_TRUE(s.scene.occluded(o, d, 0.0f, 4.1f));
    EXPECT_FALSE(s.scene.occluded(o, d, 0.0f, 3.9f));
    EXPECT_FALSE(s.scene.occluded(o, Imath::V3f(0, 1, 0)));
}

TEST(EmbreeScene, InterpolatedNormalAndUvOnSphere)
{
    SphereScene s;
    // The ray meets (0, 0, -1): longitude pi (u = 1/2) on the equator (v = 1/2).
    const Imath::V3f o(0, 0, -5), d(0, 0, 1);
    const SurfacePoint sp = s.scene.interpolate(*s.scene.intersect(o, d), o, d);
    EXPECT_NEAR((sp.P - Imath::V3f(0, 0, -1)).length(), 0.0f, 1e-5f);
    EXPECT_NEAR((sp.N - Imath::V3f(0, 0, -1)).length(), 0.0f, 1e-4f);
    EXPECT_GT(sp.Ng.dot(sp.N), 0.99f);
    EXPECT_NEAR(sp.uv.x, 0.5f, 1e-4f);
    EXPECT_NEAR(sp.uv.y, 0.5f, 1e-4f);
    EXPECT_NEAR((sp.wo - Imath::V3f(0, 0, -1)).length(), 0.0f, 1e-6f);
    // p = (sin v' sin 2pi u, cos v', sin v' cos 2pi u) with v' = pi (1 - v): at u = v = 1/2,
    // dP/du = 2 pi (-1, 0, 0) and dP/dv = pi (0, 1, 0), up to the tessellation.
    EXPECT_NEAR((sp.dPdu - 2 * kPi * Imath::V3f(-1, 0, 0)).length(), 0.0f, 2e-2f * 2 * kPi);
    EXPECT_NEAR((sp.dPdv - kPi * Imath::V3f(0, 1, 0)).length(), 0.0f, 2e-2f * kPi);
    EXPECT_GT(sp.dPdu.cross(sp.dPdv).dot(sp.N), 0.0f); // right-handed around the outward normal
}

TEST(EmbreeScene, InterpolationOnAQuadIsExact)
{
    EmbreeScene scene;
    scene.add_mesh(make_box(Imath::V3f(0, -10, 0), Imath::V3f(1))); // id 0, out of the way
    const int quad = scene.add_mesh(make_quad(Imath::V3f(0), 2.0f));
    scene.commit();
    EXPECT_EQ(quad, 1);
    EXPECT_EQ(scene.mesh_count(), 2);
    const Imath::V3f o(0.5f, 1.0f, -0.25f), d(0, -1, 0);
    const auto hit = scene.intersect(o, d);
    ASSERT_TRUE(hit);
    EXPECT_EQ(hit->mesh_id, quad);
    const SurfacePoint sp = scene.interpolate(*hit, o, d);
    EXPECT_NEAR((sp.P - Imath::V3f(0.5f, 0.0f, -0.25f)).length(), 0.0f, 1e-6f);
    // make_plane: u along +x, v along -z (cross(du, dv) = +y), uv in [0,1]^2 over size 2.
    EXPECT_NEAR(sp.uv.x, 0.75f, 1e-6f);
    EXPECT_NEAR(sp.uv.y, 0.625f, 1e-6f);
    EXPECT_NEAR((sp.dPdu - Imath::V3f(2, 0, 0)).length(), 0.0f, 1e-5f);
    EXPECT_NEAR((sp.dPdv - Imath::V3f(0, 0, -2)).length(), 0.0f, 1e-5f);
    EXPECT_NEAR((sp.N - Imath::V3f(0, 1, 0)).length(), 0.0f, 1e-6f);
    EXPECT_NEAR((sp.Ng - Imath::V3f(0, 1, 0)).length(), 0.0f, 1e-6f);

    // From below, the surface is the same: normals still point up (the file's side).
    const Imath::V3f below(0.5f, -1.0f, -0.25f), up(0, 1, 0);
    const SurfacePoint back = scene.interpolate(*scene.intersect(below, up), below, up);
    EXPECT_GT(back.N.y, 0.99f);
    EXPECT_GT(back.Ng.y, 0.99f);
    EXPECT_EQ(scene.bounds().min.y, -10.5f);
}

TEST(EmbreeScene, MeshWithoutUvsOrNormalsGetsAFrame)
{
    TriangleMesh tri;
    tri.name = "tri";
    tri.positions = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
    tri.indices = {0, 1, 2};
    EmbreeScene scene;
    scene.add_mesh(tri);
    scene.commit();
    const Imath::V3f o(0.25f, 0.25f, 1.0f), d(0, 0, -1);
    const SurfacePoint sp = scene.interpolate(*scene.intersect(o, d), o, d);
    EXPECT_NEAR((sp.Ng - Imath::V3f(0, 0, 1)).length(), 0.0f, 1e-6f); // right-hand rule
    EXPECT_EQ(sp.N, sp.Ng);
    EXPECT_NEAR(sp.uv.x, 0.25f, 1e-6f); // barycentrics
    EXPECT_NEAR(sp.uv.y, 0.25f, 1e-6f);
    EXPECT_NEAR(sp.dPdu.dot(sp.N), 0.0f, 1e-6f);
    EXPECT_NEAR(sp.dPdu.cross(sp.dPdv).dot(sp.N), 1.0f, 1e-5f);
}

TEST(EmbreeScene, RandomRaysAgreeWithAnalyticSphere)
{
    SphereScene s;
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> unit(0.0f, 1.0f);
    int hits = 0, self_hits = 0, escapes_wrong = 0;
    for (int i = 0; i < 4000; ++i) {
        const Imath::V3f o = 3.0f * random_unit(rng);
        const bool aim_inside = i % 2 == 0;
        // Aim at a point inside (hits) or outside (mostly misses) the sphere.
        const float radius = aim_inside ? 0.95f * std::cbrt(unit(rng)) : 1.05f + unit(rng);
        const Imath::V3f target = radius * random_unit(rng);
        const Imath::V3f d = (target - o).normalized();
        const float t_exact = sphere_t(o, d, Imath::V3f(0), 1.0f);
        const auto hit = s.scene.intersect(o, d);
        // The closest approach of the line to the centre decides; grazing lines within the
        // tessellation's sagitta of the silhouette may go either way and are skipped.
        const float closest = (o - o.dot(d) * d).length();
        if (closest > 1.0f + kSagitta) {
            EXPECT_FALSE(hit) << i;
            continue;
        }
        if (closest > 1.0f - kSagitta)
            continue;
        ASSERT_GT(t_exact, 0.0f) << i;
        ASSERT_TRUE(hit) << i;
        ++hits;
        // The polyhedron lies inside the sphere, within kSagitta; along a ray at incidence
        // theta that is at most kSagitta / cos(theta) further.
        const SurfacePoint sp = s.scene.interpolate(*hit, o, d);
        const float cos_theta = std::abs(d.dot(sp.P.normalized()));
        EXPECT_GE(hit->t, t_exact - 1e-5f) << i;
        EXPECT_LE(hit->t, t_exact + kSagitta / cos_theta + 1e-5f) << i;
        EXPECT_LE(sp.P.length(), 1.0f + 1e-5f);
        EXPECT_GE(sp.P.length(), 1.0f - kSagitta);
        EXPECT_GT(sp.N.dot(sp.P), 0.99f);

        // Leaving the surface: an outward ray from the offset origin escapes the convex
        // sphere; an inward one crosses it and meets the far side, never its own triangle.
        Imath::V3f w = random_unit(rng);
        if (w.dot(sp.Ng) < 0)
            w = -w;
        for (const Imath::V3f& start : {offset_ray_origin(sp, w), offset_ray_origin(sp.P, sp.Ng, w)})
            escapes_wrong += s.scene.intersect(start, w).has_value();
        const Imath::V3f in = -w;
        for (const Imath::V3f& start : {offset_ray_origin(sp, in), offset_ray_origin(sp.P, sp.Ng, in)}) {
            const auto next = s.scene.intersect(start, in);
            self_hits += !next || (next->prim_id == hit->prim_id && next->t < 1e-3f);
        }
    }
    EXPECT_GT(hits, 2000);
    EXPECT_EQ(escapes_wrong, 0);
    EXPECT_EQ(self_hits, 0);
}

TEST(EmbreeScene, ParallelQueriesMatchSerial)
{
    SphereScene s;
    auto ray = [](int i) {
        const float a = 0.001f * static_cast<float>(i);
        return std::pair{Imath::V3f(std::cos(a) * 3, 0.3f * std::sin(3 * a), std::sin(a) * 3),
                         Imath::V3f(-std::cos(a), 0.05f, -std::sin(a))};
    };
    std::vector<float> serial(4000);
    for (int i = 0; i < 4000; ++i) {
        const auto [o, d] = ray(i);
        const auto h = s.scene.intersect(o, d);
        serial[static_cast<size_t>(i)] = h ? h->t : -1.0f;
    }
    std::atomic<int> mismatches{0};
    std::vector<std::thread> threads;
    for (int k = 0; k < 4; ++k)
        threads.emplace_back([&, k] {
            for (int i = k; i < 4000; i += 4) {
                const auto [o, d] = ray(i);
                const auto h = s.scene.intersect(o, d);
                mismatches += (h ? h->t : -1.0f) != serial[static_cast<size_t>(i)];
            }
        });
    for (auto& t : threads)
        t.join();
    EXPECT_EQ(mismatches.load(), 0);
}

TEST(EmbreeScene, ErrorsAreExceptionsWithText)
{
    EmbreeScene scene;
    TriangleMesh bad = make_quad(Imath::V3f(0), 1.0f);
    bad.name = "broken";
    bad.indices[2] = 99;
    try {
        scene.add_mesh(bad);
        FAIL() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("mesh 'broken'"), std::string::npos) << e.what();
    }
    TriangleMesh empty;
    empty.name = "empty";
    EXPECT_THROW(scene.add_mesh(empty), std::runtime_error);
    scene.add_mesh(make_quad(Imath::V3f(0), 1.0f));
    EXPECT_THROW((void)scene.intersect(Imath::V3f(0, 1, 0), Imath::V3f(0, -1, 0)), std::runtime_error);
    scene.commit();
    EXPECT_TRUE(scene.intersect(Imath::V3f(0, 1, 0), Imath::V3f(0, -1, 0)));
    EXPECT_THROW((void)scene.mesh(5), std::runtime_error);
}

}  // namespace patina

namespace patina {
namespace {

    // The stream query agrees with one occluded() call per ray, for batches longer than its
    // internal chunk and with finite and infinite tmax.
    TEST(EmbreeScene, CountUnoccludedMatchesOccludedPerRay)
    {
        EmbreeScene scene;
        scene.add_mesh(make_uv_sphere(Imath::V3f(0.0f), 1.0f, 16, 32));
        scene.commit();
        std::mt19937 gen(5);
        std::uniform_real_distribution<float> u(-1.0f, 1.0f);
        std::vector<ShadowRay> rays;
        size_t expected = 0;
        for (int i = 0; i < 300; ++i) {
            ShadowRay r;
            r.origin = Imath::V3f(3.0f * u(gen), 3.0f * u(gen), 3.0f * u(gen));
            // Aimed at points within 1.6 of the unit sphere's centre: about half hit it.
            const Imath::V3f target(1.6f * u(gen), 1.6f * u(gen), 1.6f * u(gen));
            r.dir = (target - r.origin).normalized();
            r.tmax = i % 2 ? std::numeric_limits<float>::infinity() : 2.0f;
            rays.push_back(r);
            expected += !scene.occluded(r.origin, r.dir, 0.0f, r.tmax);
        }
        EXPECT_GT(expected, 30u);
        EXPECT_LT(expected, 270u);
        EXPECT_EQ(scene.count_unoccluded(rays), expected);
        EXPECT_EQ(scene.count_unoccluded({}), 0u);
    }

}  // namespace
}  // namespace patina

namespace patina {

// The renderer's lean interpolation gives interpolate()'s fields bit for bit (all but wo),
// and says when (dPdu, dPdv, N) is already an orthonormal frame: for meshes without uvs.
TEST(EmbreeScene, InterpolateShadingMatchesInterpolate)
{
    TriangleMesh bare = make_uv_sphere(Imath::V3f(0), 1.0f, 16, 32);
    bare.uvs.clear();
    TriangleMesh flat;  // no normals, no uvs
    flat.name = "flat";
    flat.positions = {{-3, -2, -3}, {3, -2, -3}, {0, -2, 3}};
    flat.indices = {0, 2, 1};
    EmbreeScene scene;
    const int uv_id = scene.add_mesh(make_uv_sphere(Imath::V3f(0, 3, 0), 1.0f, 16, 32));
    const int bare_id = scene.add_mesh(bare);
    scene.add_mesh(flat);
    scene.commit();
    std::mt19937 rng(7);
    int seen[3] = {0, 0, 0};
    for (int i = 0; i < 300; ++i) {
        const Imath::V3f o = random_unit(rng) * 6.0f;
        const Imath::V3f target = Imath::V3f(0, (i % 3 == 0) ? 3.0f : 0.0f, 0) + 0.5f * random_unit(rng);
        const Imath::V3f d = (i % 3 == 2) ? Imath::V3f(0, -1, 0) : (target - o).normalized();
        const Imath::V3f origin = (i % 3 == 2) ? Imath::V3f(o.x * 0.3f, 5.0f, o.z * 0.3f) : o;
        const auto hit = scene.intersect(origin, d);
        if (!hit)
            continue;
        ++seen[hit->mesh_id];
        const SurfacePoint a = scene.interpolate(*hit, origin, d);
        SurfacePoint b;
        const bool orthonormal = scene.interpolate_shading(*hit, d, b);
        EXPECT_EQ(a.P, b.P);
        EXPECT_EQ(a.p_error, b.p_error);
        EXPECT_EQ(a.Ng, b.Ng);
        EXPECT_EQ(a.N, b.N);
        EXPECT_EQ(a.uv, b.uv);
        EXPECT_EQ(a.dPdu, b.dPdu);
        EXPECT_EQ(a.dPdv, b.dPdv);
        EXPECT_EQ(a.prim_id, b.prim_id);
        EXPECT_EQ(orthonormal, hit->mesh_id != uv_id);
        if (orthonormal) {
            EXPECT_NEAR(b.dPdu.length(), 1.0f, 1e-6f);
            EXPECT_NEAR(b.dPdu.dot(b.N), 0.0f, 1e-6f);
            EXPECT_NEAR((b.dPdu.cross(b.dPdv) - b.N).length(), 0.0f, 2e-6f);
        }
    }
    EXPECT_GT(seen[uv_id], 10);
    EXPECT_GT(seen[bare_id], 10);
    EXPECT_GT(seen[2], 10);
}

}  // namespace patina

// The wavefront renderer's bounce rays go through intersect_incoherent: one stream call,
// the same hits bit for bit as one intersect call per ray (rays from inside and outside a
// sphere, some missing it, some with a limited range; more than one 64-ray chunk).
TEST(EmbreeScene, IncoherentStreamGivesTheSameHitsAsSingleRays)
{
    patina::EmbreeScene scene;
    scene.add_mesh(patina::make_uv_sphere({0.3f, -0.2f, 0.1f}, 1.0f, 24, 12));
    scene.commit();
    patina::Pcg32 rng(5);
    std::vector<patina::RayQuery> rays(150);
    for (size_t i = 0; i < rays.size(); ++i) {
        patina::RayQuery& r = rays[i];
        r.origin = {4.0f * rng.uniform_float() - 2.0f, 4.0f * rng.uniform_float() - 2.0f,
                    4.0f * rng.uniform_float() - 2.0f};
        // Towards the sphere, give or take 1.5: most hit, some miss.
        r.dir = Imath::V3f(0.3f, -0.2f, 0.1f) - r.origin +
                Imath::V3f(3.0f * rng.uniform_float() - 1.5f, 3.0f * rng.uniform_float() - 1.5f,
                           3.0f * rng.uniform_float() - 1.5f);
        r.tmax = i % 3 == 0 ? 1.5f : std::numeric_limits<float>::infinity();
    }
    std::vector<std::optional<patina::Hit>> hits(rays.size());
    scene.intersect_incoherent(rays, hits);
    size_t found = 0;
    for (size_t i = 0; i < rays.size(); ++i) {
        const std::optional<patina::Hit> one =
            scene.intersect(rays[i].origin, rays[i].dir, rays[i].tmin, rays[i].tmax);
        ASSERT_EQ(one.has_value(), hits[i].has_value()) << "ray " << i;
        if (!one)
            continue;
        ++found;
        EXPECT_EQ(std::memcmp(&one->t, &hits[i]->t, sizeof(float)), 0) << "ray " << i;
        EXPECT_EQ(one->prim_id, hits[i]->prim_id);
        EXPECT_EQ(one->mesh_id, hits[i]->mesh_id);
        EXPECT_EQ(std::memcmp(&one->u, &hits[i]->u, sizeof(float)), 0);
        EXPECT_EQ(std::memcmp(&one->v, &hits[i]->v, sizeof(float)), 0);
    }
    EXPECT_GT(found, rays.size() / 4);
    EXPECT_LT(found, rays.size());
    std::vector<std::optional<patina::Hit>> too_few(3);
    EXPECT_THROW(scene.intersect_incoherent(rays, too_few), std::invalid_argument);
}
