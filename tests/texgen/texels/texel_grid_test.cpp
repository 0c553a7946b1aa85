// Texel set-up: conservative coverage, supersampling, shared edges counted once, sample
// positions and normals, UDIM tiles, per-vertex samples, bad input, determinism.
#include "texgen/texels/texel_grid.h"

#include "test_util.h"
#include "core/sampling.h"
#include "texgen/texgen_meshes.h"

#include <gtest/gtest.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <vector>

namespace patina::texgen {
namespace {

    using Imath::V2d;
    using Imath::V2f;
    using Imath::V3f;

    /// A mesh of the given uv triangles lying in the z = 0 plane at P = (u, v, 0), so
    /// uv and surface coincide.
    TriangleMesh flat_mesh(const std::vector<V2f>& uvs, const std::vector<uint32_t>& indices)
    {
        TriangleMesh m;
        m.name = "flat";
        m.uvs = uvs;
        for (const V2f& uv : uvs)
            m.positions.emplace_back(uv.x, uv.y, 0.0f);
        m.indices = indices;
        return m;
    }

    /// Reference for the tests: the area of a triangle inside a box, by clipping the
    /// triangle polygon to each half plane of the box (Sutherland-Hodgman), in double.
    double clip_area(std::vector<V2d> poly, double x0, double y0, double x1, double y1)
    {
        const auto clip = [&](int axis, double bound, bool keep_greater) {
            std::vector<V2d> out;
            for (size_t i = 0; i < poly.size(); ++i) {
                const V2d a = poly[i], b = poly[(i + 1) % poly.size()];
                const bool ina = keep_greater ? a[axis] >= bound : a[axis] <= bound;
                const bool inb = keep_greater ? b[axis] >= bound : b[axis] <= bound;
                if (ina)
                    out.push_back(a);
                if (ina != inb)
                    out.push_back(a + (bound - a[axis]) / (b[axis] - a[axis]) * (b - a));
            }
            poly = out;
        };
        clip(0, x0, true);
        clip(0, x1, false);
        clip(1, y0, true);
        clip(1, y1, false);
        double twice = 0.0;
        for (size_t i = 0; i < poly.size(); ++i) {
            const V2d a = poly[i], b = poly[(i + 1) % poly.size()];
            twice += a.x * b.y - a.y * b.x;
        }
        return 0.5 * std::abs(twice);
    }

    /// uv box of texel (x, y) of a width x height grid of tile 1001 (row 0 at v = 1).
    void texel_box(int x, int y, int width, int height, double& u0, double& v0, double& u1,
                   double& v1)
    {
        u0 = double(x) / width;
        u1 = double(x + 1) / width;
        v0 = 1.0 - double(y + 1) / height;
        v1 = 1.0 - double(y) / height;
    }

    size_t total_samples(const TexelGrid& g) { return g.groups.samples.size(); }

    TEST(TexelGrid, UdimNumbers)
    {
        EXPECT_EQ(udim_of(0, 0), 1001);
        EXPECT_EQ(udim_of(1, 0), 1002);
        EXPECT_EQ(udim_of(9, 0), 1010);
        EXPECT_EQ(udim_of(0, 1), 1011);
        EXPECT_THROW(udim_of(10, 0), std::runtime_error);
        EXPECT_THROW(udim_of(0, -1), std::runtime_error);
    }

    TEST(TexelGrid, SingleTriangleCoverageSumsToItsArea)
    {
        const std::vector<V2f> uvs{{0.1f, 0.15f}, {0.83f, 0.3f}, {0.4f, 0.9f}};
        const TriangleMesh m = flat_mesh(uvs, {0, 1, 2});
        const double area =
            0.5 * std::abs((0.83 - 0.1) * (0.9 - 0.15) - (0.3 - 0.15) * (0.4 - 0.1));
        const double perimeter = (uvs[1] - uvs[0]).length() + (uvs[2] - uvs[1]).length() +
                                 (uvs[0] - uvs[2]).length();
        for (int s : {1, 2, 4, 8}) {
            const int w = 64;
            const auto grids = rasterize_uv(m, {w, w, s});
            ASSERT_EQ(grids.size(), 1u);
            double sum = 0.0;
            for (float c : grids[0].coverage)
                sum += c;
            sum /= double(w) * w;
            // Quantisation: a sub-sample's 1/s^2 of a texel is misjudged only when the
            // boundary crosses its cell; a segment of length L crosses at most 2 (L + 1)
            // cells of unit size, so the error is below 2 (perimeter * w * s + 3) cells.
            const double bound = 2.0 * (perimeter * w * s + 3.0) / (double(w) * w * s * s);
            EXPECT_NEAR(sum, area, bound) << "s = " << s;
            // Sub-samples are exact area integration in the limit: 8 x 8 is within 0.2%.
            if (s == 8) {
                EXPECT_NEAR(sum, area, 2e-3 * area);
            }
            std::printf("s = %d: coverage area %.6f, exact %.6f (error %.2e, bound %.2e)\n", s,
                        sum, area, sum - area, bound);
        }
    }

    TEST(TexelGrid, CoverageIsConservative)
    {
        // Random triangles, large and small and thin, against a brute-force texel/triangle
        // overlap by exact clipping.
        Pcg32 rng(hash_values(7, 1));
        const int w = 24, h = 16;
        for (int trial = 0; trial < 60; ++trial) {
            std::vector<V2f> uvs(3);
            const float size = trial < 20 ? 0.6f : trial < 40 ? 0.08f : 0.02f;
            const V2f c(0.1f + 0.8f * rng.uniform_float(), 0.1f + 0.8f * rng.uniform_float());
            for (V2f& uv : uvs)
                uv = c + size * V2f(rng.uniform_float() - 0.5f, rng.uniform_float() - 0.5f);
            if (trial >= 50)  // slivers thinner than a sub-sample spacing
                uvs[2] = 0.5f * (uvs[0] + uvs[1]) + V2f(0.0003f, -0.0002f);
            const TriangleMesh m = flat_mesh(uvs, {0, 1, 2});
            const auto grids = rasterize_uv(m, {w, h, 2});
            ASSERT_EQ(grids.size(), 1u);
            const TexelGrid& g = grids[0];
            // Triangles near the edge of the square may have their centroid in the next
            // tile: the texel boxes are offset to the grid's tile.
            const double tile_u = (g.udim - 1001) % 10, tile_v = (g.udim - 1001) / 10;
            std::vector<V2d> tri;
            for (const V2f& uv : uvs)
                tri.emplace_back(uv.x, uv.y);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    double u0, v0, u1, v1;
                    texel_box(x, y, w, h, u0, v0, u1, v1);
                    u0 += tile_u;
                    u1 += tile_u;
                    v0 += tile_v;
                    v1 += tile_v;
                    const double texel_area = (u1 - u0) * (v1 - v0);
                    const double a = clip_area(tri, u0, v0, u1, v1) / texel_area;
                    const int32_t group = g.group_of_texel[y * w + x];
                    if (a > 1e-7) {
                        EXPECT_GE(group, 0) << "trial " << trial << " texel " << x << "," << y
                                            << " holds " << a << " of the triangle";
                    }
                    // And not more: a covered texel touches the triangle (grown by 1e-7).
                    const double grown = clip_area(tri, u0 - 1e-7, v0 - 1e-7, u1 + 1e-7, v1 + 1e-7);
                    if (group >= 0) {
                        EXPECT_GT(grown, 0.0) << "trial " << trial << " texel " << x << "," << y;
                        EXPECT_GT(g.coverage[y * w + x], 0.0f);
                        EXPECT_GE(g.groups.group_size(group), 1u);
                    } else {
                        EXPECT_EQ(g.coverage[y * w + x], 0.0f);
                    }
                }
        }
    }

    TEST(TexelGrid, GrazedTexelGetsTheNearestPoint)
    {
        // A sliver along v = 0.5 + tiny: it touches a row of texels without containing a
        // single sub-sample centre.
        const int w = 8;
        const std::vector<V2f> uvs{
            {0.1f, 0.5f + 1e-4f}, {0.9f, 0.5f + 1e-4f}, {0.5f, 0.5f + 3e-4f}};
        const TriangleMesh m = flat_mesh(uvs, {0, 1, 2});
        const auto grids = rasterize_uv(m, {w, w, 2});
        ASSERT_EQ(grids.size(), 1u);
        const TexelGrid& g = grids[0];
        // Row 3 holds v in [0.5, 0.625): texels 0..7 whose u range meets [0.1, 0.9].
        int covered = 0;
        for (int x = 0; x < w; ++x) {
            const int32_t group = g.group_of_texel[3 * w + x];
            if (group < 0)
                continue;
            ++covered;
            ASSERT_EQ(g.groups.group_size(group), 1u);
            const SurfaceSample& s = g.groups.samples[g.groups.offsets[group]];
            const float centre_u = (x + 0.5f) / w;
            // The triangle spans u in [0.1, 0.9]: the nearest point shares the centre's u
            // when the centre is above it, else it is the nearest corner.
            EXPECT_NEAR(s.uv.x, std::clamp(centre_u, 0.1f, 0.9f), 2e-4f) << "texel " << x;
            EXPECT_GE(s.uv.y, 0.5f + 1e-4f - 1e-6f);
            EXPECT_LE(s.uv.y, 0.5f + 3e-4f + 1e-6f);
            EXPECT_GT(g.coverage[3 * w + x], 0.0f);
            EXPECT_LT(g.coverage[3 * w + x], 0.01f);
        }
        EXPECT_EQ(covered, 8);  // u in [0.1, 0.9] meets every column of width 1/8
        EXPECT_EQ(g.covered_count(), 8);
    }

    TEST(TexelGrid, SharedEdgesAreCountedOnce)
    {
        // The quad's diagonal runs through sub-sample centres when the grid is square.
        const TriangleMesh quad = make_quad(V3f(0.0f), 1.0f);
        for (int s : {1, 2, 3, 4, 7}) {
            for (auto [w, h] : {std::pair{16, 16}, std::pair{12, 6}}) {
                const auto grids = rasterize_uv(quad, {w, h, s});
                ASSERT_EQ(grids.size(), 1u);
                const TexelGrid& g = grids[0];
                ASSERT_EQ(g.covered_count(), w * h);
                for (size_t t = 0; t < g.texel_count(); ++t) {
                    ASSERT_EQ(g.groups.group_size(g.group_of_texel[t]), size_t(s * s))
                        << "s = " << s << " texel " << t;
                    ASSERT_EQ(g.coverage[t], 1.0f);
                }
            }
        }
    }

    TEST(TexelGrid, FanAroundASubSampleCentreCountsItOnce)
    {
        // Eight triangles around a vertex placed exactly on a sub-sample centre (texel (3, 4)
        // of an 8 x 8 grid, sub-sample (0, 0) of 2 x 2), covering the unit square.
        const int w = 8, s = 2;
        const V2f centre((3 + 0.25f) / w, 1.0f - (4 + 0.25f) / w);
        std::vector<V2f> uvs{centre,       {0.0f, 0.0f}, {0.3f, 0.0f}, {1.0f, 0.0f}, {1.0f, 0.7f},
                             {1.0f, 1.0f}, {0.2f, 1.0f}, {0.0f, 1.0f}, {0.0f, 0.4f}};
        std::vector<uint32_t> indices;
        for (uint32_t i = 1; i <= 8; ++i)
            indices.insert(indices.end(), {0, i, i % 8 + 1});
        const auto grids = rasterize_uv(flat_mesh(uvs, indices), {w, w, s});
        ASSERT_EQ(grids.size(), 1u);
        for (size_t t = 0; t < grids[0].texel_count(); ++t) {
            EXPECT_EQ(grids[0].groups.group_size(grids[0].group_of_texel[t]), size_t(s * s))
                << "texel " << t;
            EXPECT_EQ(grids[0].coverage[t], 1.0f);
        }
        EXPECT_EQ(total_samples(grids[0]), size_t(w * w * s * s));
    }

    TEST(TexelGrid, SamplesInterpolatePositionAndNormalOnAPlane)
    {
        // make_plane: P(u, v) = center + size ((u - 1/2) du + (v - 1/2) dv) with du = +x and
        // dv = normal x du = -z for an up-facing plane (core/mesh.h).
        const V3f center(1.0f, 2.0f, 3.0f);
        const float size = 2.0f;
        const TriangleMesh m = make_plane(center, size, 3);
        const int w = 20, h = 10;
        const auto grids = rasterize_uv(m, {w, h, 1});
        ASSERT_EQ(grids.size(), 1u);
        const TexelGrid& g = grids[0];
        ASSERT_EQ(g.covered_count(), w * h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const int32_t group = g.group_of_texel[y * w + x];
                ASSERT_EQ(g.groups.group_size(group), 1u);
                const SurfaceSample& s = g.groups.samples[g.groups.offsets[group]];
                const float u = (x + 0.5f) / w, v = 1.0f - (y + 0.5f) / h;
                const V3f expected = center + size * V3f(u - 0.5f, 0.0f, -(v - 0.5f));
                EXPECT_NEAR((s.P - expected).length(), 0.0f, 1e-5f) << x << "," << y;
                EXPECT_NEAR(s.uv.x, u, 1e-6f);
                EXPECT_NEAR(s.uv.y, v, 1e-6f);
                EXPECT_NEAR((s.N - V3f(0, 1, 0)).length(), 0.0f, 1e-6f);
                EXPECT_NEAR((s.Ng - V3f(0, 1, 0)).length(), 0.0f, 1e-6f);
                ASSERT_LT(s.triangle, m.triangle_count());
            }
    }

    TEST(TexelGrid, ShadingNormalIsInterpolatedAndNgFollowsIt)
    {
        // One triangle with three different vertex normals, wound clockwise seen from +z
        // (its geometric normal is -z) while the vertex normals lean to +z.
        TriangleMesh m = flat_mesh({{0.0f, 0.0f}, {0.0f, 1.0f}, {1.0f, 0.0f}}, {0, 1, 2});
        m.normals = {V3f(1, 0, 1).normalized(), V3f(0, 1, 1).normalized(), V3f(0, 0, 1)};
        const auto grids = rasterize_uv(m, {8, 8, 2});
        ASSERT_EQ(grids.size(), 1u);
        size_t checked = 0;
        for (const SurfaceSample& s : grids[0].groups.samples) {
            // P = (u, v, 0): the barycentric coordinates are (1 - u - v, v, u).
            const float b0 = 1.0f - s.uv.x - s.uv.y, b1 = s.uv.y, b2 = s.uv.x;
            const V3f expected =
                (b0 * m.normals[0] + b1 * m.normals[1] + b2 * m.normals[2]).normalized();
            EXPECT_NEAR((s.N - expected).length(), 0.0f, 1e-5f);
            EXPECT_NEAR(s.N.length(), 1.0f, 1e-6f);
            EXPECT_NEAR((s.Ng - V3f(0, 0, 1)).length(), 0.0f, 1e-6f);
            EXPECT_NEAR(s.P.x, s.uv.x, 1e-6f);
            EXPECT_NEAR(s.P.y, s.uv.y, 1e-6f);
            ++checked;
        }
        EXPECT_GT(checked, 100u);

        // Without vertex normals N is the geometric normal of the winding.
        m.normals.clear();
        const auto flat = rasterize_uv(m, {8, 8, 2});
        for (const SurfaceSample& s : flat[0].groups.samples) {
            EXPECT_EQ(s.N, V3f(0, 0, -1));
            EXPECT_EQ(s.Ng, V3f(0, 0, -1));
        }
    }

    TEST(TexelGrid, UdimPlaneGivesOneGridPerTile)
    {
        const TriangleMesh m = test::make_udim_plane(V3f(0.0f), 1.0f);
        const int w = 16, s = 2;
        const auto grids = rasterize_uv(m, {w, w, s});
        ASSERT_EQ(grids.size(), 2u);
        EXPECT_EQ(grids[0].udim, 1001);
        EXPECT_EQ(grids[1].udim, 1002);
        for (int tile = 0; tile < 2; ++tile) {
            const TexelGrid& g = grids[tile];
            ASSERT_EQ(g.covered_count(), w * w) << "tile " << tile;
            EXPECT_EQ(total_samples(g), size_t(w * w * s * s));
            for (const SurfaceSample& sample : g.groups.samples) {
                // Tile 1001 is the half x < 0 with u in [0, 1]; 1002 the half x > 0.
                EXPECT_EQ(sample.P.x > 0.0f, tile == 1);
                EXPECT_GE(sample.uv.x, float(tile));
                EXPECT_LE(sample.uv.x, float(tile + 1));
                // u = 1 + x / size (the plane spans x in [-1, 1] for u in [0, 2]).
                EXPECT_NEAR(sample.P.x, sample.uv.x - 1.0f, 1e-6f);
            }
        }
    }

    TEST(TexelGrid, AtlasCubeCoversItsIslandsOnly)
    {
        const TriangleMesh m = test::make_atlas_cube();
        const int w = 64, s = 2;
        RasterStats stats;
        const auto grids = rasterize_uv(m, {w, w, s}, stats);
        ASSERT_EQ(grids.size(), 1u);
        EXPECT_EQ(stats.zero_uv_area + stats.zero_surface_area + stats.outside_udims, 0u);
        // Islands of 5/16 x 5/16 at exact texel boundaries (64 * 5/16 = 20 texels): 6 x 400
        // texels, all fully covered; the gaps stay empty.
        EXPECT_EQ(grids[0].covered_count(), 6 * 20 * 20);
        double sum = 0.0;
        for (float c : grids[0].coverage)
            sum += c;
        EXPECT_EQ(sum, 6.0 * 400.0);
        for (const SurfaceSample& sample : grids[0].groups.samples) {
            // On the unit cube every sample lies on a face: one coordinate is +-0.5 and Ng is
            // that face's axis.
            const float face =
                std::max({std::abs(sample.P.x), std::abs(sample.P.y), std::abs(sample.P.z)});
            EXPECT_NEAR(face, 0.5f, 1e-6f);
            EXPECT_NEAR(sample.Ng.dot(sample.P), 0.5f, 1e-6f);
        }
    }

    TEST(TexelGrid, DegenerateTrianglesAreSkippedAndCounted)
    {
        TriangleMesh m = make_quad(V3f(0.0f), 1.0f);
        // A triangle with collinear uvs and one with a single repeated position.
        const uint32_t n = static_cast<uint32_t>(m.positions.size());
        m.positions.insert(m.positions.end(), {V3f(0, 1, 0), V3f(1, 1, 0), V3f(0, 1, 1)});
        m.normals.insert(m.normals.end(), 3, V3f(0, 1, 0));
        m.uvs.insert(m.uvs.end(), {V2f(0.1f, 0.1f), V2f(0.2f, 0.2f), V2f(0.3f, 0.3f)});
        m.indices.insert(m.indices.end(), {n, n + 1, n + 2});
        m.positions.insert(m.positions.end(), 3, V3f(5, 5, 5));
        m.normals.insert(m.normals.end(), 3, V3f(0, 1, 0));
        m.uvs.insert(m.uvs.end(), {V2f(0.1f, 0.1f), V2f(0.9f, 0.1f), V2f(0.5f, 0.9f)});
        m.indices.insert(m.indices.end(), {n + 3, n + 4, n + 5});
        RasterStats stats;
        const auto grids = rasterize_uv(m, {8, 8, 2}, stats);
        EXPECT_EQ(stats.zero_uv_area, 1u);
        EXPECT_EQ(stats.zero_surface_area, 1u);
        ASSERT_EQ(grids.size(), 1u);
        for (const SurfaceSample& s : grids[0].groups.samples)
            EXPECT_LT(s.triangle, 2u);
        EXPECT_EQ(total_samples(grids[0]), 8u * 8u * 4u);
    }

    TEST(TexelGrid, BadInputIsReportedClearly)
    {
        using test::message_of;
        const RasterOptions options{16, 16, 2};
        const std::string no_uvs =
            message_of([&] { rasterize_uv(test::make_mesh_without_uvs(), options); });
        EXPECT_NE(no_uvs.find("mesh 'no_uvs' has no uvs"), std::string::npos) << no_uvs;
        EXPECT_NE(no_uvs.find("--per-vertex"), std::string::npos) << no_uvs;

        TriangleMesh nan_position = make_quad(V3f(0.0f), 1.0f);
        nan_position.positions[2].y = std::numeric_limits<float>::quiet_NaN();
        EXPECT_NE(message_of([&] { rasterize_uv(nan_position, options); }).find("vertex 2"),
                  std::string::npos);
        EXPECT_NE(message_of([&] { vertex_samples(nan_position); }).find("vertex 2"),
                  std::string::npos);

        TriangleMesh nan_uv = make_quad(V3f(0.0f), 1.0f);
        nan_uv.uvs[3].x = std::numeric_limits<float>::quiet_NaN();
        const std::string uv_message = message_of([&] { rasterize_uv(nan_uv, options); });
        EXPECT_NE(uv_message.find("mesh 'quad': vertex 3 has a non-finite uv"), std::string::npos)
            << uv_message;

        TriangleMesh flat = make_quad(V3f(0.0f), 1.0f);
        for (V3f& p : flat.positions)
            p = V3f(1.0f, 2.0f, 3.0f);
        const std::string zero = message_of([&] { rasterize_uv(flat, options); });
        EXPECT_NE(zero.find("mesh 'quad': zero-area mesh"), std::string::npos) << zero;
        EXPECT_NE(message_of([&] { vertex_samples(flat); }).find("zero-area mesh"),
                  std::string::npos);
        TriangleMesh flat_uvs = make_quad(V3f(0.0f), 1.0f);
        for (V2f& uv : flat_uvs.uvs)
            uv = V2f(0.5f, 0.5f);
        EXPECT_NE(message_of([&] { rasterize_uv(flat_uvs, options); }).find("zero-area mesh"),
                  std::string::npos);

        TriangleMesh outside = make_quad(V3f(0.0f), 1.0f);
        for (V2f& uv : outside.uvs)
            uv.x -= 1.0f;
        const std::string out_message = message_of([&] { rasterize_uv(outside, options); });
        EXPECT_NE(out_message.find("triangle 0 has its uv centroid at"), std::string::npos)
            << out_message;

        EXPECT_NE(message_of([&] { rasterize_uv(make_quad(V3f(0.0f), 1.0f), {0, 16, 2}); })
                      .find("resolution"),
                  std::string::npos);
        EXPECT_NE(message_of([&] { rasterize_uv(make_quad(V3f(0.0f), 1.0f), {16, 16, 9}); })
                      .find("supersampling must be 1..8"),
                  std::string::npos);
    }

    TEST(TexelGrid, SameBitsWithOneThreadOrMany)
    {
        const TriangleMesh sphere = make_uv_sphere(V3f(0.0f), 1.0f, 24, 48);
        const RasterOptions options{96, 80, 3};
        std::vector<TexelGrid> one;
        tbb::task_arena arena(1);
        arena.execute([&] { one = rasterize_uv(sphere, options); });
        const std::vector<TexelGrid> many = rasterize_uv(sphere, options);
        ASSERT_EQ(one.size(), 1u);
        ASSERT_EQ(many.size(), 1u);
        const TexelGrid &a = one[0], &b = many[0];
        EXPECT_EQ(a.group_of_texel, b.group_of_texel);
        EXPECT_EQ(a.coverage, b.coverage);
        EXPECT_EQ(a.groups.offsets, b.groups.offsets);
        ASSERT_EQ(a.groups.samples.size(), b.groups.samples.size());
        EXPECT_EQ(std::memcmp(a.groups.samples.data(), b.groups.samples.data(),
                              a.groups.samples.size() * sizeof(SurfaceSample)),
                  0);
        // Groups follow texel scan order.
        int32_t last = -1;
        for (int32_t group : a.group_of_texel)
            if (group >= 0) {
                EXPECT_EQ(group, last + 1);
                last = group;
            }
    }

    TEST(VertexSamples, OneGroupPerVertex)
    {
        const TriangleMesh box = make_box(V3f(0.0f), V3f(1.0f, 2.0f, 3.0f));
        const SampleGroups groups = vertex_samples(box);
        ASSERT_EQ(groups.group_count(), box.positions.size());
        for (size_t v = 0; v < box.positions.size(); ++v) {
            ASSERT_EQ(groups.group_size(v), 1u);
            const SurfaceSample& s = groups.samples[groups.offsets[v]];
            EXPECT_EQ(s.P, box.positions[v]);
            EXPECT_EQ(s.N, box.normals[v]);
            EXPECT_EQ(s.Ng, s.N);
            EXPECT_EQ(s.uv, box.uvs[v]);
            // The first triangle using the vertex: a face's corners 0..2 are in its first
            // triangle (0, 1, 2), corner 3 only in the second (0, 2, 3).
            EXPECT_EQ(s.triangle, v / 4 * 2 + (v % 4 == 3));
        }
    }

    TEST(VertexSamples, AreaWeightedNormalsWithoutVertexNormals)
    {
        // A hinge: triangle 0 of area 1/2 in the z = 0 plane (normal +z) and triangle 1 of
        // area 3/2 in the y = 0 plane (normal (0, 0, 3) x (1, 0, 0) along +y), sharing the
        // edge from vertex 0 to 1; vertex 4 is used by nobody.
        TriangleMesh m;
        m.name = "hinge";
        m.positions = {V3f(0, 0, 0), V3f(1, 0, 0), V3f(0, 1, 0), V3f(0, 0, 3), V3f(9, 9, 9)};
        m.indices = {0, 1, 2, 0, 3, 1};
        const SampleGroups groups = vertex_samples(m);
        ASSERT_EQ(groups.group_count(), 5u);
        // Shared vertices: (1/2 * z + 3/2 * y) normalised.
        const V3f shared = V3f(0.0f, 1.5f, 0.5f).normalized();
        for (size_t v : {0u, 1u})
            EXPECT_NEAR((groups.samples[groups.offsets[v]].N - shared).length(), 0.0f, 1e-6f);
        EXPECT_NEAR((groups.samples[groups.offsets[2]].N - V3f(0, 0, 1)).length(), 0.0f, 1e-6f);
        EXPECT_NEAR((groups.samples[groups.offsets[3]].N - V3f(0, 1, 0)).length(), 0.0f, 1e-6f);
        EXPECT_EQ(groups.samples[groups.offsets[3]].triangle, 1u);
        EXPECT_EQ(groups.group_size(4), 0u);
        EXPECT_EQ(groups.samples.size(), 4u);
    }

}  // namespace
}  // namespace patina::texgen
