// The surface lattice: a plane is a plain grid; on a cube whose six faces are separate uv
// islands every border texel is linked across its cube edge and a diffused field is as
// smooth across the seams as inside the faces (the seam test of issue 5, D&H 1996 §1); a
// uv sphere's u = 0/1 seam and two UDIM tiles are crossed; no uvs is an error; node order
// and the map back to texel groups; same result for any thread count.
#include "texgen/growth/surface_lattice.h"

#include "test_util.h"
#include "texgen/texgen_meshes.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <vector>

namespace patina::texgen {
namespace {

    using Imath::V3f;

    SurfaceLatticeOptions lattice_options(int resolution)
    {
        SurfaceLatticeOptions o;
        o.width = o.height = resolution;
        o.supersampling = 2;
        return o;
    }

    size_t link_count(const Lattice& l)
    {
        size_t n = 0;
        for (const auto& nb : l.neighbours)
            n += static_cast<size_t>(
                std::count_if(nb.begin(), nb.end(), [](int32_t b) { return b >= 0; }));
        return n;
    }

    /// Every link has its way back, no node links to itself or twice to the same node.
    void expect_symmetric(const Lattice& l)
    {
        for (size_t a = 0; a < l.size(); ++a) {
            for (int s = 0; s < 4; ++s) {
                const int32_t b = l.neighbours[a][s];
                if (b < 0)
                    continue;
                ASSERT_LT(static_cast<size_t>(b), l.size());
                ASSERT_NE(static_cast<size_t>(b), a);
                const auto& back = l.neighbours[b];
                ASSERT_EQ(std::count(back.begin(), back.end(), static_cast<int32_t>(a)), 1)
                    << "link " << a << " -> " << b << " (slot " << s << ") has no single way back";
                ASSERT_EQ(std::count(l.neighbours[a].begin(), l.neighbours[a].end(), b), 1);
            }
        }
    }

    /// The cube face a point of the unit cube at the origin lies on: 2 axis + (sign < 0).
    int face_of(const V3f& p)
    {
        int axis = 0;
        for (int a = 1; a < 3; ++a)
            if (std::abs(p[a]) > std::abs(p[axis]))
                axis = a;
        return 2 * axis + (p[axis] < 0.0f ? 1 : 0);
    }

    // ---------------------------------------------------------------------------------

    TEST(SurfaceLattice, PlaneIsAGrid)
    {
        // A 2 m square in 4 x 4 cells (32 triangles), 32 x 32 texels: the lattice is
        // make_grid_lattice's 32 x 32 grid, node = texel, cell 2 / 32 m.
        const TriangleMesh plane = make_plane(V3f(0.0f), 2.0f, 4);
        const int n = 32;
        const Lattice l = build_surface_lattice(plane, lattice_options(n));
        const Lattice grid = make_grid_lattice(n, n, 2.0f / n);
        ASSERT_EQ(l.size(), static_cast<size_t>(n * n));
        ASSERT_EQ(l.tiles.size(), 1u);
        EXPECT_EQ(l.tiles[0].udim, 1001);
        EXPECT_EQ(l.tiles[0].node_of_texel, grid.tiles[0].node_of_texel);
        EXPECT_EQ(l.neighbours, grid.neighbours);
        expect_symmetric(l);
        int interior_full = 0;
        for (int y = 1; y + 1 < n; ++y)
            for (int x = 1; x + 1 < n; ++x) {
                const auto& nb = l.neighbours[y * n + x];
                interior_full +=
                    std::all_of(nb.begin(), nb.end(), [](int32_t b) { return b >= 0; });
            }
        EXPECT_EQ(interior_full, (n - 2) * (n - 2));
        for (size_t i = 0; i < l.size(); ++i) {
            ASSERT_NEAR(l.cell_size[i], 2.0f / n, 1e-5f) << "node " << i;
            // The texel's centre on the plane: u along +x, v along -z (make_plane, up).
            const int x = static_cast<int>(i) % n, y = static_cast<int>(i) / n;
            const V3f centre(-1.0f + (x + 0.5f) * 2.0f / n, 0.0f, -1.0f + (y + 0.5f) * 2.0f / n);
            ASSERT_NEAR((l.position[i] - centre).length(), 0.0f, 1e-5f) << "node " << i;
        }
    }

    /// The links of the atlas cube between different faces, per cube edge (pair of faces).
    struct SeamLinks {
        int links_between[6][6] = {};
        std::vector<std::pair<int32_t, int32_t>> links; // a < b
    };
    SeamLinks seam_links(const Lattice& l)
    {
        SeamLinks s;
        for (size_t a = 0; a < l.size(); ++a)
            for (int32_t b : l.neighbours[a])
                if (b > static_cast<int32_t>(a) &&
                    face_of(l.position[a]) != face_of(l.position[b])) {
                    ++s.links_between[face_of(l.position[a])][face_of(l.position[b])];
                    ++s.links_between[face_of(l.position[b])][face_of(l.position[a])];
                    s.links.emplace_back(static_cast<int32_t>(a), b);
                }
        return s;
    }

    /// The seam test's geometric part for one resolution of the atlas cube (unit cube).
    void check_atlas_cube_links(int resolution)
    {
        SCOPED_TRACE("resolution " + std::to_string(resolution));
        const TriangleMesh cube = test::make_atlas_cube();
        const Lattice l = build_surface_lattice(cube, lattice_options(resolution));
        expect_symmetric(l);
        const double texels_per_edge = resolution * test::kAtlasIsland; // 5/16 of the tile
        const float cell = static_cast<float>(1.0 / texels_per_edge);

        // Every node's cell size is near the texel's side on the cube (1 m / island texels):
        // across a 90 degree fold a link is shorter (0.71 of a cell for aligned texels), and
        // a partly covered texel's position (the mean of its samples) sits off its centre.
        float min_cell = 1e9f, max_cell = 0.0f, max_link = 0.0f;
        for (size_t i = 0; i < l.size(); ++i) {
            min_cell = std::min(min_cell, l.cell_size[i]);
            max_cell = std::max(max_cell, l.cell_size[i]);
        }
        // Every link, inside a face or across an edge, spans at most 1.5 cells in 3D.
        for (size_t a = 0; a < l.size(); ++a)
            for (int32_t b : l.neighbours[a])
                if (b >= 0)
                    max_link = std::max(max_link, (l.position[a] - l.position[b]).length());
        std::printf("resolution %d: cell size %.3f .. %.3f cells, longest link %.3f cells\n",
                    resolution, min_cell / cell, max_cell / cell, max_link / cell);
        EXPECT_GT(min_cell, 0.35f * cell);
        EXPECT_LT(max_cell, 1.25f * cell);
        EXPECT_LE(max_link, 1.5f * cell);

        // Every border node of a face (fewer than four neighbours on its own face) that is
        // not at a corner of the cube (within 1.5 cells of two edges) has its missing
        // neighbours on the face across its edge: four neighbours in all.
        int border = 0, linked = 0;
        for (size_t a = 0; a < l.size(); ++a) {
            const V3f& p = l.position[a];
            const int face = face_of(p);
            int own = 0, across = 0, edges = 0, across_face = -1;
            for (int32_t b : l.neighbours[a])
                if (b >= 0)
                    face_of(l.position[b]) == face ? ++own : ++across;
            for (int axis = 0; axis < 3; ++axis)
                if (axis != face / 2 && std::abs(p[axis]) > 0.5f - 1.5f * cell) {
                    ++edges;
                    across_face = 2 * axis + (p[axis] < 0.0f ? 1 : 0);
                }
            if (own == 4 || edges != 1)
                continue;
            ++border;
            bool on_face = true;
            for (int32_t b : l.neighbours[a])
                if (b >= 0 && face_of(l.position[b]) != face)
                    on_face = on_face && face_of(l.position[b]) == across_face;
            const bool ok = own + across == 4 && across >= 1 && on_face;
            linked += ok;
            EXPECT_TRUE(ok) << "node " << a << " at (" << p.x << ", " << p.y << ", " << p.z
                            << ") of face " << face << ": " << own << " neighbours on its face, "
                            << across << " across the edge to face " << across_face;
        }
        EXPECT_EQ(linked, border);
        // 24 face sides, each with (texels along the edge - 3 near corners) border texels.
        EXPECT_GE(border, static_cast<int>(24 * (std::floor(texels_per_edge) - 3)));

        // Each of the 12 cube edges carries about one link per texel along it; opposite
        // faces are never linked.
        const SeamLinks s = seam_links(l);
        int edges_seen = 0;
        for (int f = 0; f < 6; ++f)
            for (int g = f + 1; g < 6; ++g) {
                if (f / 2 == g / 2) {
                    EXPECT_EQ(s.links_between[f][g], 0);
                    continue;
                }
                ++edges_seen;
                EXPECT_GE(s.links_between[f][g], std::floor(texels_per_edge) - 1)
                    << "faces " << f << ", " << g;
                EXPECT_LE(s.links_between[f][g], std::ceil(texels_per_edge) + 1)
                    << "faces " << f << ", " << g;
            }
        EXPECT_EQ(edges_seen, 12);
        std::printf("resolution %d: %d border nodes, all linked across; %zu links between "
                    "faces\n",
                    resolution, border, s.links.size());
    }

    TEST(SurfaceLattice, AtlasCubeSeamsAreLinkedAlignedTexels)
    {
        // 64 texels: each island spans exactly 20 texels from a texel boundary.
        check_atlas_cube_links(64);
    }

    TEST(SurfaceLattice, AtlasCubeSeamsAreLinkedPartialTexels)
    {
        // 90 texels: islands of 28.125 texels starting mid-texel, so border texels are
        // partly covered and the two sides of an edge do not line up.
        check_atlas_cube_links(90);
    }

    /// Explicit diffusion on a lattice (forward Euler of the graph Laplacian, step 0.2 < 1/4
    /// for stability with four neighbours) from a unit source.
    std::vector<double> diffuse(const Lattice& l, int32_t source, int steps)
    {
        std::vector<double> u(l.size(), 0.0), next(l.size());
        u[source] = 1.0;
        for (int step = 0; step < steps; ++step) {
            for (size_t i = 0; i < l.size(); ++i) {
                double flow = 0.0;
                for (int32_t b : l.neighbours[i])
                    if (b >= 0)
                        flow += u[b] - u[i];
                next[i] = u[i] + 0.2 * flow;
            }
            std::swap(u, next);
        }
        return u;
    }

    struct Smoothness {
        double across = 0.0; ///< mean |difference| over the links between faces
        double inside = 0.0; ///< mean |difference| over links inside a face, near the edges
    };
    /// Differences of `u` over the seam links of `seams` and over the in-face links of
    /// `full` whose two ends are within 2 cells of a cube edge, both within `radius` of the
    /// source.
    Smoothness smoothness(const Lattice& full, const std::vector<double>& u, int32_t source,
                          float radius, float cell)
    {
        const auto near = [&](int32_t i) {
            return (full.position[i] - full.position[source]).length() < radius;
        };
        const auto near_edge = [&](int32_t i) {
            const V3f& p = full.position[i];
            const int face = face_of(p);
            for (int axis = 0; axis < 3; ++axis)
                if (axis != face / 2 && std::abs(p[axis]) > 0.5f - 2.0f * cell)
                    return true;
            return false;
        };
        double across = 0.0, inside = 0.0;
        int n_across = 0, n_inside = 0;
        for (size_t a = 0; a < full.size(); ++a)
            for (int32_t b : full.neighbours[a]) {
                const int32_t ia = static_cast<int32_t>(a);
                if (b <= ia || !near(ia) || !near(b))
                    continue;
                const double d = std::abs(u[a] - u[b]);
                if (face_of(full.position[a]) != face_of(full.position[b])) {
                    across += d;
                    ++n_across;
                } else if (near_edge(ia) && near_edge(b)) {
                    inside += d;
                    ++n_inside;
                }
            }
        EXPECT_GT(n_across, 10);
        EXPECT_GT(n_inside, 10);
        return {across / std::max(n_across, 1), inside / std::max(n_inside, 1)};
    }

    /// The seam test's field part: diffusion from a source near a cube edge.
    void check_atlas_cube_diffusion(int resolution)
    {
        SCOPED_TRACE("resolution " + std::to_string(resolution));
        const float cell = 1.0f / (resolution * test::kAtlasIsland);
        const TriangleMesh cube = test::make_atlas_cube();
        const Lattice l = build_surface_lattice(cube, lattice_options(resolution));

        // A source two cells from the edge between faces +x and +y, off centre along it.
        const V3f target(0.5f, 0.5f - 2.0f * cell, 0.1f);
        int32_t source = 0;
        for (size_t i = 1; i < l.size(); ++i)
            if ((l.position[i] - target).length() < (l.position[source] - target).length())
                source = static_cast<int32_t>(i);
        ASSERT_EQ(face_of(l.position[source]), 0);
        const int steps = 300; // spreads sqrt(4 * 0.2 * 300) ~ 15 cells
        const std::vector<double> u = diffuse(l, source, steps);
        const Smoothness s = smoothness(l, u, source, 12.0f * cell, cell);
        EXPECT_LE(s.across, 1.5 * s.inside) << "across " << s.across << ", inside " << s.inside;

        // Mass crosses the edge as on a flat sheet: 1.5 cells beyond the edge (3.5 cells from
        // the source) the field is about what it is 3.5 cells from the source on its own
        // face, on the far side.
        const auto node_near = [&](const V3f& p) {
            int32_t best = 0;
            for (size_t i = 1; i < l.size(); ++i)
                if ((l.position[i] - p).length() < (l.position[best] - p).length())
                    best = static_cast<int32_t>(i);
            return best;
        };
        const int32_t beyond = node_near(V3f(0.5f - 1.5f * cell, 0.5f, 0.1f));
        const int32_t mirror = node_near(V3f(0.5f, 0.5f - 5.5f * cell, 0.1f));
        ASSERT_EQ(face_of(l.position[beyond]), 2);
        EXPECT_GT(u[beyond], 0.5 * u[mirror]) << "beyond " << u[beyond] << ", mirror " << u[mirror];
        EXPECT_LT(u[beyond], 2.0 * u[mirror]) << "beyond " << u[beyond] << ", mirror " << u[mirror];
        std::printf("resolution %d: mean |difference| across seams %.3g, inside faces %.3g; "
                    "3.5 cells from the source across the edge %.3g, on its face %.3g\n",
                    resolution, s.across, s.inside, u[beyond], u[mirror]);

        // Control: the same diffusion with the seam links cut is discontinuous, so the
        // comparison above can fail.
        Lattice cut = l;
        for (size_t a = 0; a < cut.size(); ++a)
            for (int32_t& b : cut.neighbours[a])
                if (b >= 0 && face_of(cut.position[a]) != face_of(cut.position[b]))
                    b = -1;
        const std::vector<double> u_cut = diffuse(cut, source, steps);
        const Smoothness c = smoothness(l, u_cut, source, 12.0f * cell, cell);
        std::printf("resolution %d, seams cut: across %.3g, inside %.3g; beyond %.3g\n", resolution,
                    c.across, c.inside, u_cut[beyond]);
        EXPECT_GT(c.across, 3.0 * c.inside)
            << "cut: across " << c.across << ", inside " << c.inside;
        EXPECT_EQ(u_cut[beyond], 0.0);
    }

    TEST(SurfaceLattice, AtlasCubeDiffusionIsContinuousAcrossSeamsAlignedTexels)
    {
        check_atlas_cube_diffusion(64); // 20 texels per cube edge
    }

    TEST(SurfaceLattice, AtlasCubeDiffusionIsContinuousAcrossSeamsPartialTexels)
    {
        check_atlas_cube_diffusion(90); // 28.125 texels per cube edge, starting mid-texel
    }

    TEST(SurfaceLattice, SphereSeamAtUZeroOne)
    {
        // make_uv_sphere duplicates the vertices of longitude 0 at u = 0 and u = 1 (with
        // sin(2 pi) rounding in float): the right column's +x neighbour is the left column.
        const TriangleMesh sphere = make_uv_sphere(V3f(0.0f), 1.0f, 16, 32);
        const int n = 64;
        const Lattice l = build_surface_lattice(sphere, lattice_options(n));
        expect_symmetric(l);
        const Lattice::Tile& tile = l.tiles.at(0);
        int checked = 0;
        for (int y = 8; y < n - 8; ++y) {
            const int32_t a = tile.node_of_texel[y * n + (n - 1)];
            ASSERT_GE(a, 0);
            const int32_t b = l.neighbours[a][0];
            ASSERT_GE(b, 0) << "row " << y << " does not cross the seam";
            const auto it = std::find(tile.node_of_texel.begin(), tile.node_of_texel.end(), b);
            const int texel = static_cast<int>(it - tile.node_of_texel.begin());
            EXPECT_EQ(texel % n, 0) << "row " << y;
            EXPECT_LE(std::abs(texel / n - y), 1) << "row " << y;
            EXPECT_EQ(l.neighbours[b][1], a) << "row " << y;
            // One step along the equator-ish row: 2 pi r sin(theta) / 64, up to 1.5 of it.
            const float theta = 3.14159265f * (y + 0.5f) / n;
            EXPECT_LT((l.position[a] - l.position[b]).length(),
                      1.5f * 2.0f * 3.14159265f * std::sin(theta) / n)
                << "row " << y;
            ++checked;
        }
        EXPECT_EQ(checked, n - 16);
    }

    TEST(SurfaceLattice, UdimTilesAreJoined)
    {
        // A plane over UDIM 1001 and 1002 (one uv island): nodes are tile 1001's groups then
        // tile 1002's, and the right column of 1001 links to the left column of 1002.
        const TriangleMesh plane = test::make_udim_plane();
        const int n = 16;
        const std::vector<TexelGrid> grids = rasterize_uv(plane, {n, n, 2});
        ASSERT_EQ(grids.size(), 2u);
        const Lattice l = build_surface_lattice(plane, grids);
        ASSERT_EQ(l.size(), grids[0].groups.group_count() + grids[1].groups.group_count());
        ASSERT_EQ(l.tiles.size(), 2u);
        int32_t base = 0;
        for (size_t g = 0; g < 2; ++g) {
            EXPECT_EQ(l.tiles[g].udim, grids[g].udim);
            for (size_t t = 0; t < grids[g].texel_count(); ++t) {
                const int32_t group = grids[g].group_of_texel[t];
                ASSERT_EQ(l.tiles[g].node_of_texel[t], group < 0 ? -1 : base + group);
            }
            base += grids[g].covered_count();
        }
        expect_symmetric(l);
        for (int y = 0; y < n; ++y) {
            const int32_t a = l.tiles[0].node_of_texel[y * n + n - 1];
            const int32_t b = l.tiles[1].node_of_texel[y * n];
            EXPECT_EQ(l.neighbours[a][0], b) << "row " << y;
            EXPECT_EQ(l.neighbours[b][1], a) << "row " << y;
        }
        // Interior nodes of the whole 32 x 16 sheet have four neighbours.
        EXPECT_EQ(link_count(l), static_cast<size_t>(2 * (2 * n - 1) * n + 2 * (n - 1) * 2 * n));
    }

    TEST(SurfaceLattice, LatticeToGroups)
    {
        const TriangleMesh cube = test::make_atlas_cube();
        const std::vector<TexelGrid> grids = rasterize_uv(cube, {48, 48, 2});
        const Lattice l = build_surface_lattice(cube, grids);
        // Same grids: a copy, value of group i = value of node i.
        std::vector<float> values(l.size());
        for (size_t i = 0; i < values.size(); ++i)
            values[i] = static_cast<float>(i) * 0.5f + 1.0f;
        const std::vector<std::vector<float>> groups = lattice_to_groups(l, values, grids);
        ASSERT_EQ(groups.size(), 1u);
        ASSERT_EQ(groups[0].size(), l.size());
        for (size_t i = 0; i < values.size(); ++i)
            ASSERT_EQ(groups[0][i], values[i]);

        // Another resolution: each group takes a node near it. With node value = the
        // node's x, a group's value is within a few lattice cells of its samples' mean x.
        const std::vector<TexelGrid> coarse = rasterize_uv(cube, {24, 24, 2});
        std::vector<float> xs(l.size());
        for (size_t i = 0; i < l.size(); ++i)
            xs[i] = l.position[i].x;
        const std::vector<std::vector<float>> mapped = lattice_to_groups(l, xs, coarse);
        const SampleGroups& sg = coarse[0].groups;
        for (size_t g = 0; g < sg.group_count(); ++g) {
            float mean = 0.0f;
            for (uint32_t s = sg.offsets[g]; s < sg.offsets[g + 1]; ++s)
                mean += sg.samples[s].P.x;
            mean /= static_cast<float>(sg.group_size(g));
            ASSERT_NEAR(mapped[0][g], mean, 3.0f / 15.0f) << "group " << g;
        }

        const std::vector<float> wrong(l.size() + 1, 0.0f);
        EXPECT_NE(test::message_of([&] {
                      lattice_to_groups(l, wrong, grids);
                  }).find("values for a lattice of"),
                  std::string::npos);
        std::vector<TexelGrid> other = grids;
        other[0].udim = 1002;
        EXPECT_NE(test::message_of([&] { lattice_to_groups(l, values, other); }).find("1002"),
                  std::string::npos);
    }

    TEST(SurfaceLattice, MeshWithoutUvsIsAnError)
    {
        const TriangleMesh m = test::make_mesh_without_uvs();
        for (const std::string& message :
             {test::message_of([&] { build_surface_lattice(m, lattice_options(16)); }),
              test::message_of([&] { build_surface_lattice(m, std::vector<TexelGrid>{}); })}) {
            EXPECT_NE(message.find("mesh 'no_uvs'"), std::string::npos) << message;
            EXPECT_NE(message.find("no uvs"), std::string::npos) << message;
        }
    }

    TEST(SurfaceLattice, GridsOfAnotherMeshAreAnError)
    {
        const TriangleMesh cube = test::make_atlas_cube();
        const TriangleMesh quad = make_quad(V3f(0.0f), 1.0f);
        const std::vector<TexelGrid> grids = rasterize_uv(cube, {16, 16, 2});
        const std::string message = test::message_of([&] { build_surface_lattice(quad, grids); });
        EXPECT_NE(message.find("another mesh"), std::string::npos) << message;
    }

    Lattice build_with_threads(const TriangleMesh& mesh, int resolution, int threads)
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                                  static_cast<size_t>(threads));
        return build_surface_lattice(mesh, lattice_options(resolution));
    }

    TEST(SurfaceLattice, SameResultForAnyThreadCount)
    {
        for (const TriangleMesh& mesh :
             {test::make_atlas_cube(), make_uv_sphere(V3f(0.0f), 1.0f, 12, 24)}) {
            const Lattice one = build_with_threads(mesh, 90, 1);
            const Lattice two = build_with_threads(mesh, 90, 2);
            ASSERT_EQ(one.size(), two.size()) << mesh.name;
            EXPECT_EQ(one.neighbours, two.neighbours) << mesh.name;
            EXPECT_EQ(
                std::memcmp(one.position.data(), two.position.data(), one.size() * sizeof(V3f)), 0)
                << mesh.name;
            EXPECT_EQ(
                std::memcmp(one.cell_size.data(), two.cell_size.data(), one.size() * sizeof(float)),
                0)
                << mesh.name;
        }
    }

} // namespace
} // namespace patina::texgen
