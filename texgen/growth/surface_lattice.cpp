#include "texgen/growth/surface_lattice.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>
#include <tuple>

namespace patina::texgen {

namespace {

    using Imath::V2d;
    using Imath::V3d;

    /// A triangle whose corner angle has a sine below this (in uv or in 3D) is skipped, as
    /// rasterize_uv skips it.
    constexpr double kDegenerateSine = 1e-9;
    /// Vertices closer than this fraction of the bounding-box diagonal are one surface
    /// point (a uv seam duplicates vertices, sometimes with rounding: make_uv_sphere's
    /// sin(2 pi) in float is 1.7e-7, not 0).
    constexpr double kWeldTolerance = 1e-5;
    /// A link longer than this many expected texel steps (in 3D) is not a neighbour: two
    /// parts of the surface meet in the texture but not on the surface.
    constexpr double kMaxLinkSteps = 3.0;
    /// The walk across a seam advances in eighths of a texel step, up to two steps.
    constexpr int kWalkSubsteps = 8;
    constexpr int kWalkMaxSteps = 2;
    /// Edge crossings one advance may make before the walk gives up (a walk circling a
    /// vertex of many slivers).
    constexpr int kMaxCrossings = 64;

    constexpr int kSlots = 4;

    std::string mesh_label(const TriangleMesh& mesh)
    {
        return fmt::format("mesh '{}'", mesh.name.empty() ? std::string("(unnamed)") : mesh.name);
    }

    double cross(const V2d& a, const V2d& b)
    {
        return a.x * b.y - a.y * b.x;
    }

    int find_root(std::vector<int32_t>& parent, int32_t i)
    {
        while (parent[i] != i) {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        return i;
    }

    /// Union by the smaller index, so every root is its set's lowest index whatever the
    /// order of the unions.
    void unite(std::vector<int32_t>& parent, int32_t a, int32_t b)
    {
        a = find_root(parent, a);
        b = find_root(parent, b);
        if (a < b)
            parent[b] = a;
        else if (b < a)
            parent[a] = b;
    }

    /// One triangle's uv chart and its surface: P(uv) is affine inside the triangle.
    struct Chart {
        V2d uv[3];
        V3d P[3];

        Chart(const TriangleMesh& mesh, size_t t)
        {
            for (int c = 0; c < 3; ++c) {
                const uint32_t v = mesh.indices[3 * t + c];
                uv[c] = V2d(mesh.uvs[v]);
                P[c] = V3d(mesh.positions[v]);
            }
        }
        double det() const { return cross(uv[1] - uv[0], uv[2] - uv[0]); }
        /// Barycentric coordinates of a uv point, and of a uv displacement (summing to 0).
        V3d barycentric(const V2d& p) const
        {
            const double b1 = cross(p - uv[0], uv[2] - uv[0]) / det();
            const double b2 = cross(uv[1] - uv[0], p - uv[0]) / det();
            return V3d(1.0 - b1 - b2, b1, b2);
        }
        V3d barycentric_delta(const V2d& d) const
        {
            const double b1 = cross(d, uv[2] - uv[0]) / det();
            const double b2 = cross(uv[1] - uv[0], d) / det();
            return V3d(-b1 - b2, b1, b2);
        }
        /// The surface displacement of a uv displacement.
        V3d to_surface(const V2d& d) const
        {
            const V3d b = barycentric_delta(d);
            return b.y * (P[1] - P[0]) + b.z * (P[2] - P[0]);
        }
        /// The uv displacement of a displacement in the triangle's plane (least squares
        /// on the two edges, exact for vectors in the plane).
        V2d to_uv(const V3d& d) const
        {
            const V3d e1 = P[1] - P[0], e2 = P[2] - P[0];
            const double a11 = e1.dot(e1), a12 = e1.dot(e2), a22 = e2.dot(e2);
            const double r1 = e1.dot(d), r2 = e2.dot(d);
            const double g = a11 * a22 - a12 * a12;
            const double alpha = (r1 * a22 - r2 * a12) / g, beta = (a11 * r2 - a12 * r1) / g;
            return alpha * (uv[1] - uv[0]) + beta * (uv[2] - uv[0]);
        }
    };

    V2d closest_on_segment(const V2d& a, const V2d& b, const V2d& q)
    {
        const V2d ab = b - a;
        const double t = std::clamp((q - a).dot(ab) / ab.length2(), 0.0, 1.0);
        return a + t * ab;
    }

    /// The point of a triangle nearest q, in uv.
    V2d nearest_point(const Chart& c, const V2d& q)
    {
        const V3d b = c.barycentric(q);
        if (b.x >= 0.0 && b.y >= 0.0 && b.z >= 0.0)
            return q;
        V2d best = c.uv[0];
        double best_d2 = std::numeric_limits<double>::infinity();
        for (int v = 0; v < 3; ++v) {
            const V2d p = closest_on_segment(c.uv[v], c.uv[(v + 1) % 3], q);
            const double d2 = (p - q).length2();
            if (d2 < best_d2) {
                best_d2 = d2;
                best = p;
            }
        }
        return best;
    }

    bool degenerate(const Chart& c)
    {
        const V2d u1 = c.uv[1] - c.uv[0], u2 = c.uv[2] - c.uv[0];
        const V3d e1 = c.P[1] - c.P[0], e2 = c.P[2] - c.P[0];
        const bool flat_uv =
            !(std::abs(cross(u1, u2)) > kDegenerateSine * u1.length() * u2.length());
        const bool flat_surface =
            !(e1.cross(e2).length() > kDegenerateSine * e1.length() * e2.length());
        return flat_uv || flat_surface;
    }

    /// The mesh as a surface: welded vertices, the triangle across each edge, uv islands,
    /// and the tile each triangle was rasterised into.
    struct Topology {
        std::vector<int32_t> weld;                  ///< per vertex: lowest vertex at its point
        std::vector<std::array<int32_t, 3>> across; ///< per triangle, edge (v_e, v_e+1): -1 open
        std::vector<int32_t> island;                ///< per triangle: lowest triangle; -1 skipped
        std::vector<int32_t> grid;                  ///< per triangle: index into grids or -1
        std::vector<V2d> tile_origin;               ///< per triangle: (u0, v0) of its tile
    };

    std::vector<int32_t> weld_vertices(const TriangleMesh& mesh)
    {
        const size_t n = mesh.positions.size();
        Imath::V3d lo(std::numeric_limits<double>::infinity()), hi(-lo);
        for (const Imath::V3f& p : mesh.positions)
            for (int a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], double(p[a]));
                hi[a] = std::max(hi[a], double(p[a]));
            }
        const double eps = n ? kWeldTolerance * (hi - lo).length() : 0.0;
        // Sweep along a direction no axis-aligned layout lines up with, so that only the
        // points in a thin slab are compared.
        const V3d axis = V3d(0.5377, 0.3211, 0.7795).normalized();
        std::vector<double> key(n);
        for (size_t v = 0; v < n; ++v)
            key[v] = V3d(mesh.positions[v]).dot(axis);
        std::vector<int32_t> order(n);
        std::iota(order.begin(), order.end(), 0);
        std::sort(order.begin(), order.end(), [&](int32_t a, int32_t b) {
            return key[a] < key[b] || (key[a] == key[b] && a < b);
        });
        std::vector<int32_t> parent(n);
        std::iota(parent.begin(), parent.end(), 0);
        for (size_t i = 0; i < n; ++i)
            for (size_t j = i + 1; j < n && key[order[j]] - key[order[i]] <= eps; ++j)
                if ((V3d(mesh.positions[order[i]]) - V3d(mesh.positions[order[j]])).length() <= eps)
                    unite(parent, order[i], order[j]);
        for (size_t v = 0; v < n; ++v)
            parent[v] = find_root(parent, static_cast<int32_t>(v));
        return parent;
    }

    int udim_index(int udim)
    {
        return udim - 1001;
    }

    Topology build_topology(const TriangleMesh& mesh, const std::vector<TexelGrid>& grids)
    {
        Topology topo;
        topo.weld = weld_vertices(mesh);
        const size_t count = mesh.triangle_count();
        topo.across.assign(count, {-1, -1, -1});
        topo.island.assign(count, -1);
        topo.grid.assign(count, -1);
        topo.tile_origin.assign(count, V2d(0.0));

        // Tiles: the tile of the uv centroid, as rasterize_uv assigns them.
        std::vector<int32_t> grid_of_udim(1000, -1);
        for (size_t g = 0; g < grids.size(); ++g) {
            const int k = udim_index(grids[g].udim);
            if (k >= 0 && k < 1000)
                grid_of_udim[k] = static_cast<int32_t>(g);
        }
        std::vector<uint8_t> usable(count, 0);
        tbb::parallel_for(
            tbb::blocked_range<size_t>(0, count, 4096),
            [&](const tbb::blocked_range<size_t>& range) {
                for (size_t t = range.begin(); t != range.end(); ++t) {
                    const Chart c(mesh, t);
                    if (degenerate(c))
                        continue;
                    usable[t] = 1;
                    const V2d centroid = (c.uv[0] + c.uv[1] + c.uv[2]) / 3.0;
                    const double u0 = std::floor(centroid.x), v0 = std::floor(centroid.y);
                    topo.tile_origin[t] = V2d(u0, v0);
                    if (u0 >= 0 && u0 < 10 && v0 >= 0 && v0 < 100)
                        topo.grid[t] =
                            grid_of_udim[static_cast<int>(u0) + 10 * static_cast<int>(v0)];
                }
            });

        // Edge adjacency over welded vertices: sort the edges of the usable triangles by
        // their welded ends; an edge's neighbour is the lowest other triangle on it.
        struct EdgeRef {
            int32_t lo, hi, triangle, edge;
            auto tie() const { return std::tie(lo, hi, triangle, edge); }
        };
        std::vector<EdgeRef> edges;
        edges.reserve(3 * count);
        for (size_t t = 0; t < count; ++t) {
            if (!usable[t])
                continue;
            for (int e = 0; e < 3; ++e) {
                const int32_t a = topo.weld[mesh.indices[3 * t + e]];
                const int32_t b = topo.weld[mesh.indices[3 * t + (e + 1) % 3]];
                edges.push_back({std::min(a, b), std::max(a, b), static_cast<int32_t>(t), e});
            }
        }
        std::sort(edges.begin(), edges.end(),
                  [](const EdgeRef& x, const EdgeRef& y) { return x.tie() < y.tie(); });
        for (size_t i = 0; i < edges.size();) {
            size_t end = i + 1;
            while (end < edges.size() && edges[end].lo == edges[i].lo &&
                   edges[end].hi == edges[i].hi)
                ++end;
            for (size_t k = i; k < end; ++k)
                for (size_t m = i; m < end; ++m)
                    if (edges[m].triangle != edges[k].triangle) {
                        topo.across[edges[k].triangle][edges[k].edge] = edges[m].triangle;
                        break;
                    }
            i = end;
        }

        // Islands: triangles joined by edges whose ends have the same uv on both sides.
        std::vector<int32_t> parent(count);
        std::iota(parent.begin(), parent.end(), 0);
        for (size_t t = 0; t < count; ++t) {
            for (int e = 0; e < 3; ++e) {
                const int32_t other = topo.across[t][e];
                if (other < 0)
                    continue;
                bool same_uv = true;
                for (int end = 0; end < 2; ++end) {
                    const uint32_t v = mesh.indices[3 * t + (e + end) % 3];
                    bool found = false;
                    for (int c = 0; c < 3; ++c) {
                        const uint32_t w = mesh.indices[3 * other + c];
                        if (topo.weld[w] == topo.weld[v]) {
                            found = true;
                            same_uv = same_uv && mesh.uvs[w] == mesh.uvs[v];
                        }
                    }
                    same_uv = same_uv && found;
                }
                if (same_uv)
                    unite(parent, static_cast<int32_t>(t), other);
            }
        }
        for (size_t t = 0; t < count; ++t)
            if (usable[t])
                topo.island[t] = find_root(parent, static_cast<int32_t>(t));
        return topo;
    }

    /// The uv step of one texel in each slot direction (+x, -x, +y down the image, -y).
    V2d slot_step(int slot, const TexelGrid& grid)
    {
        switch (slot) {
        case 0:
            return V2d(1.0 / grid.width, 0.0);
        case 1:
            return V2d(-1.0 / grid.width, 0.0);
        case 2:
            return V2d(0.0, -1.0 / grid.height);
        default:
            return V2d(0.0, 1.0 / grid.height);
        }
    }

    /// The slot of `grid` whose direction is nearest a uv direction.
    int slot_of_direction(const V2d& d, const TexelGrid& grid)
    {
        const double x = d.x * grid.width, y = -d.y * grid.height; // image texels, y down
        if (std::abs(x) >= std::abs(y))
            return x >= 0.0 ? 0 : 1;
        return y >= 0.0 ? 2 : 3;
    }

    struct Candidate {
        int32_t node = -1;
        int32_t slot = -1; ///< the slot of `node` the link comes back through
        float distance = 0.0f;
    };

    struct Builder {
        const TriangleMesh& mesh;
        const std::vector<TexelGrid>& grids;
        Topology topo;
        std::vector<int32_t> base;                  ///< per grid: its first node
        std::vector<int32_t> node_grid;             ///< per node
        std::vector<int32_t> node_texel;            ///< per node: y * width + x in its grid
        std::vector<int32_t> home;                  ///< per node: home triangle
        std::vector<V2d> home_uv;                   ///< per node: the home sample's uv
        std::vector<int32_t> island;                ///< per node
        std::vector<std::array<float, 2>> expected; ///< 3D length of one step along x, y

        /// The node of the texel under uv point p of triangle t (its own tile), or -1.
        int32_t node_at(int32_t t, const V2d& p) const
        {
            const int32_t g = topo.grid[t];
            if (g < 0)
                return -1;
            const TexelGrid& grid = grids[g];
            const V2d o = topo.tile_origin[t];
            const double fx = std::floor((p.x - o.x) * grid.width);
            const double fy = std::floor((o.y + 1.0 - p.y) * grid.height);
            if (!(fx >= 0 && fx < grid.width && fy >= 0 && fy < grid.height))
                return -1;
            const int32_t group =
                grid.group_of_texel[static_cast<size_t>(fy) * grid.width + static_cast<size_t>(fx)];
            return group < 0 ? -1 : base[g] + group;
        }

        /// A point walking on the surface: its triangle, its uv in that triangle's chart,
        /// its direction (uv per step, in the same chart), and the vertex opposite the edge
        /// it entered through (not an exit).
        struct Walker {
            int32_t triangle;
            V2d p;
            V2d d;
            int entry = -1;
        };

        /// Move the walker by `amount` steps. Across an edge with the same uvs on both sides
        /// the uv line continues; across a seam the next triangle is unfolded about the
        /// shared edge into the current one's plane (3D lengths and angles kept: D&H 1996
        /// §3.3, the lattice follows the surface). False when the walk leaves the surface.
        bool advance(Walker& w, double amount) const
        {
            V2d rest = amount * w.d;
            for (int crossing = 0; crossing < kMaxCrossings; ++crossing) {
                const Chart c(mesh, w.triangle);
                V3d b = c.barycentric(w.p);
                const V3d db = c.barycentric_delta(rest);
                int exit_vertex = -1;
                double s_exit = 1.0;
                for (int i = 0; i < 3; ++i) {
                    if (i == w.entry || !(db[i] < 0.0))
                        continue;
                    const double s = std::max(0.0, b[i]) / -db[i];
                    if (s < s_exit) {
                        s_exit = s;
                        exit_vertex = i;
                    }
                }
                if (exit_vertex < 0) {
                    w.p += rest;
                    return true;
                }
                // Leave through the edge opposite exit_vertex, (v_j, v_k).
                const int i = exit_vertex, j = (i + 1) % 3, k = (i + 2) % 3;
                const int32_t next = topo.across[w.triangle][j];
                if (next < 0)
                    return false;
                b += s_exit * db;
                const double bj = std::max(0.0, b[j]), bk = std::max(0.0, b[k]);
                const double lambda = bj + bk > 0.0 ? bk / (bj + bk) : 0.5;
                const uint32_t vj = mesh.indices[3 * w.triangle + j];
                const uint32_t vk = mesh.indices[3 * w.triangle + k];
                int j2 = -1, k2 = -1;
                for (int m = 0; m < 3; ++m) {
                    const uint32_t v = mesh.indices[3 * next + m];
                    if (topo.weld[v] == topo.weld[vj])
                        j2 = m;
                    else if (topo.weld[v] == topo.weld[vk])
                        k2 = m;
                }
                if (j2 < 0 || k2 < 0)
                    return false;
                const int i2 = 3 - j2 - k2;
                const Chart n(mesh, next);
                rest = (1.0 - s_exit) * rest;
                const bool seam = !(mesh.uvs[vj] == mesh.uvs[mesh.indices[3 * next + j2]] &&
                                    mesh.uvs[vk] == mesh.uvs[mesh.indices[3 * next + k2]]);
                if (seam) {
                    // Unfold: a displacement's part along the edge stays along it, its part
                    // across the edge (out of the current triangle) turns into the next one.
                    const V3d e = (c.P[k] - c.P[j]).normalized();
                    V3d out = c.P[j] - c.P[i];
                    out = (out - out.dot(e) * e).normalized();
                    const V3d e2 = (n.P[k2] - n.P[j2]).normalized();
                    V3d in = n.P[i2] - n.P[j2];
                    in = (in - in.dot(e2) * e2).normalized();
                    const auto unfold = [&](const V2d& d) {
                        const V3d d3 = c.to_surface(d);
                        return n.to_uv(d3.dot(e) * e2 + d3.dot(out) * in);
                    };
                    rest = unfold(rest);
                    w.d = unfold(w.d);
                }
                w.triangle = next;
                w.p = (1.0 - lambda) * n.uv[j2] + lambda * n.uv[k2];
                w.entry = i2;
            }
            return false;
        }

        /// The link of node a in `slot` (see the header), or none.
        Candidate link(int32_t a, int slot, const std::vector<Imath::V3f>& position) const
        {
            const TexelGrid& grid = grids[node_grid[a]];
            const int x = node_texel[a] % grid.width, y = node_texel[a] / grid.width;
            const float reach = static_cast<float>(kMaxLinkSteps) * expected[a][slot / 2];
            const auto accept = [&](int32_t b, int back) -> Candidate {
                const float distance = (position[a] - position[b]).length();
                if (!(distance <= reach))
                    return {};
                return {b, back, distance};
            };
            // Inside an island: the texel next to it.
            const int nx = x + (slot == 0) - (slot == 1), ny = y + (slot == 2) - (slot == 3);
            if (nx >= 0 && nx < grid.width && ny >= 0 && ny < grid.height) {
                const int32_t group =
                    grid.group_of_texel[static_cast<size_t>(ny) * grid.width + nx];
                if (group >= 0) {
                    const int32_t b = base[node_grid[a]] + group;
                    if (island[b] == island[a]) {
                        const Candidate c = accept(b, slot ^ 1);
                        if (c.node >= 0)
                            return c;
                    }
                }
            }
            // Elsewhere: walk on the surface to the first other texel of the island walked on.
            Walker w{home[a], home_uv[a], slot_step(slot, grid)};
            for (int step = 0; step < kWalkSubsteps * kWalkMaxSteps; ++step) {
                if (!advance(w, 1.0 / kWalkSubsteps))
                    return {};
                const int32_t b = node_at(w.triangle, w.p);
                if (b < 0 || b == a || island[b] != topo.island[w.triangle])
                    continue;
                return accept(b, slot_of_direction(-w.d, grids[node_grid[b]]));
            }
            return {};
        }
    };

    void check_grids(const TriangleMesh& mesh, const std::vector<TexelGrid>& grids)
    {
        int previous = 0;
        for (const TexelGrid& grid : grids) {
            const bool sizes = grid.width > 0 && grid.height > 0 &&
                               grid.group_of_texel.size() == grid.texel_count();
            if (!sizes || grid.udim <= previous || grid.udim < 1001 || grid.udim > 1999)
                throw std::runtime_error(fmt::format(
                    "surface lattice of {}: the texel grids are not rasterize_uv's (UDIM {}, "
                    "{} x {} texels, {} texel entries)",
                    mesh_label(mesh), grid.udim, grid.width, grid.height,
                    grid.group_of_texel.size()));
            previous = grid.udim;
            for (const SurfaceSample& s : grid.groups.samples)
                if (s.triangle >= mesh.triangle_count())
                    throw std::runtime_error(fmt::format(
                        "surface lattice of {}: a sample of UDIM {} names triangle {} of {}; "
                        "the grids belong to another mesh",
                        mesh_label(mesh), grid.udim, s.triangle, mesh.triangle_count()));
        }
    }

} // namespace

Lattice build_surface_lattice(const TriangleMesh& mesh, const SurfaceLatticeOptions& options)
{
    if (!mesh.has_uvs())
        throw std::runtime_error(fmt::format(
            "{} has no uvs: a growth model runs on the texels of the uv layout; add uvs",
            mesh_label(mesh)));
    return build_surface_lattice(
        mesh, rasterize_uv(mesh, {options.width, options.height, options.supersampling}));
}

Lattice build_surface_lattice(const TriangleMesh& mesh, const std::vector<TexelGrid>& grids)
{
    if (!mesh.has_uvs())
        throw std::runtime_error(fmt::format(
            "{} has no uvs: a growth model runs on the texels of the uv layout; add uvs",
            mesh_label(mesh)));
    validate_mesh(mesh, mesh_label(mesh));
    check_grids(mesh, grids);

    Builder bld{mesh, grids, build_topology(mesh, grids), {}, {}, {}, {}, {}, {}, {}};
    Lattice lattice;

    // Nodes: the groups of every grid in order (group order is texel scan order).
    size_t count = 0;
    for (const TexelGrid& grid : grids) {
        bld.base.push_back(static_cast<int32_t>(count));
        count += grid.groups.group_count();
    }
    if (count > static_cast<size_t>(std::numeric_limits<int32_t>::max()))
        throw std::runtime_error(
            fmt::format("surface lattice of {}: {} texels are too many", mesh_label(mesh), count));
    bld.node_grid.resize(count);
    bld.node_texel.assign(count, -1);
    lattice.tiles.resize(grids.size());
    for (size_t g = 0; g < grids.size(); ++g) {
        const TexelGrid& grid = grids[g];
        Lattice::Tile& tile = lattice.tiles[g];
        tile.udim = grid.udim;
        tile.width = grid.width;
        tile.height = grid.height;
        tile.node_of_texel.assign(grid.texel_count(), -1);
        for (size_t texel = 0; texel < grid.texel_count(); ++texel) {
            const int32_t group = grid.group_of_texel[texel];
            if (group < 0)
                continue;
            if (static_cast<size_t>(group) >= grid.groups.group_count() ||
                bld.node_texel[bld.base[g] + group] >= 0)
                throw std::runtime_error(fmt::format(
                    "surface lattice of {}: UDIM {} has a bad group number {} at texel {}",
                    mesh_label(mesh), grid.udim, group, texel));
            const int32_t node = bld.base[g] + group;
            tile.node_of_texel[texel] = node;
            bld.node_grid[node] = static_cast<int32_t>(g);
            bld.node_texel[node] = static_cast<int32_t>(texel);
        }
    }

    // Per node: home triangle (the sample nearest the texel centre), island, position,
    // and the 3D length of a texel step in its home triangle.
    bld.home.assign(count, -1);
    bld.home_uv.resize(count);
    bld.island.assign(count, -1);
    bld.expected.resize(count);
    lattice.position.resize(count);
    lattice.cell_size.resize(count);
    lattice.neighbours.assign(count, {-1, -1, -1, -1});
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, count, 1024), [&](const tbb::blocked_range<size_t>& range) {
            for (size_t node = range.begin(); node != range.end(); ++node) {
                const int32_t g = bld.node_grid[node];
                const TexelGrid& grid = grids[g];
                if (bld.node_texel[node] < 0)
                    throw std::runtime_error(
                        fmt::format("surface lattice of {}: group {} of UDIM {} has no texel",
                                    mesh_label(mesh), node - bld.base[g], grid.udim));
                const int x = bld.node_texel[node] % grid.width;
                const int y = bld.node_texel[node] / grid.width;
                const int k = udim_index(grid.udim);
                const V2d centre((k % 10) + (x + 0.5) / grid.width,
                                 (k / 10) + 1.0 - (y + 0.5) / grid.height);
                const size_t group = node - bld.base[g];
                const uint32_t first = grid.groups.offsets[group],
                               last = grid.groups.offsets[group + 1];
                double best = std::numeric_limits<double>::infinity();
                for (uint32_t s = first; s < last; ++s) {
                    const SurfaceSample& sample = grid.groups.samples[s];
                    const double d2 = (V2d(sample.uv) - centre).length2();
                    if (d2 < best && bld.topo.island[sample.triangle] >= 0) {
                        best = d2;
                        bld.home[node] = static_cast<int32_t>(sample.triangle);
                        bld.home_uv[node] = V2d(sample.uv);
                    }
                }
                if (bld.home[node] < 0) {
                    // No sample on a usable triangle (an empty group): a node without links.
                    bld.expected[node] = {0.0f, 0.0f};
                    continue;
                }
                bld.island[node] = bld.topo.island[bld.home[node]];
                // Walks start from the island's point nearest the texel centre, so that the two
                // sides of a seam agree on where along it a texel sits.
                best = std::numeric_limits<double>::infinity();
                for (uint32_t s = first; s < last; ++s) {
                    const uint32_t tri = grid.groups.samples[s].triangle;
                    if (bld.topo.island[tri] != bld.island[node] ||
                        (s > first && grid.groups.samples[s - 1].triangle == tri))
                        continue;
                    const V2d q = nearest_point(Chart(mesh, tri), centre);
                    const double d2 = (q - centre).length2();
                    if (d2 < best) {
                        best = d2;
                        bld.home[node] = static_cast<int32_t>(tri);
                        bld.home_uv[node] = q;
                    }
                }
                const int32_t t = bld.home[node];
                V3d sum(0.0);
                int on_island = 0;
                for (uint32_t s = first; s < last; ++s) {
                    const SurfaceSample& sample = grid.groups.samples[s];
                    if (bld.topo.island[sample.triangle] == bld.island[node]) {
                        sum += V3d(sample.P);
                        ++on_island;
                    }
                }
                lattice.position[node] = Imath::V3f(sum / on_island);
                const Chart c(mesh, t);
                bld.expected[node] = {
                    static_cast<float>(c.to_surface(slot_step(0, grid)).length()),
                    static_cast<float>(c.to_surface(slot_step(2, grid)).length())};
            }
        });

    // Every node proposes a link per slot.
    std::vector<Candidate> candidates(count * kSlots);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 256),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t node = range.begin(); node != range.end(); ++node) {
                              if (bld.home[node] < 0)
                                  continue;
                              for (int slot = 0; slot < kSlots; ++slot)
                                  candidates[node * kSlots + slot] =
                                      bld.link(static_cast<int32_t>(node), slot, lattice.position);
                          }
                      });

    // Symmetry. A link both ends propose, whose slots nobody else claims, is kept as is
    // (almost every link inside an island). The others are accepted nearest first while
    // both slots are free: the same result as taking every link nearest first.
    const auto mutual = [&](size_t a, int slot) {
        const Candidate& c = candidates[a * kSlots + slot];
        const Candidate& back = candidates[static_cast<size_t>(c.node) * kSlots + c.slot];
        return back.node == static_cast<int32_t>(a) && back.slot == slot;
    };
    // Claims per slot: its own proposal, plus every one-sided proposal aimed at it (few:
    // they come from seams), counted in one sequential pass over those.
    std::vector<uint8_t> one_sided(count * kSlots, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t a = range.begin(); a != range.end(); ++a)
                              for (int slot = 0; slot < kSlots; ++slot)
                                  one_sided[a * kSlots + slot] =
                                      candidates[a * kSlots + slot].node >= 0 && !mutual(a, slot);
                      });
    std::vector<uint8_t> claims(count * kSlots, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count * kSlots, 16384),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t i = range.begin(); i != range.end(); ++i)
                              claims[i] = candidates[i].node >= 0;
                      });
    for (size_t i = 0; i < count * kSlots; ++i)
        if (one_sided[i]) {
            uint8_t& target =
                claims[static_cast<size_t>(candidates[i].node) * kSlots + candidates[i].slot];
            target = static_cast<uint8_t>(std::min(255, target + 1));
        }
    const auto proposes = [&](size_t a, int32_t b, int except) {
        for (int s = 0; s < kSlots; ++s)
            if (s != except && candidates[a * kSlots + s].node == b)
                return true;
        return false;
    };
    // Clean links: each end writes its own slot (the test is symmetric in the two ends);
    // the rest are marked contested.
    std::vector<uint8_t> is_contested(count * kSlots, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
                          for (size_t a = range.begin(); a != range.end(); ++a)
                              for (int slot = 0; slot < kSlots; ++slot) {
                                  const Candidate& c = candidates[a * kSlots + slot];
                                  if (c.node < 0)
                                      continue;
                                  const size_t b = static_cast<size_t>(c.node);
                                  const bool clean = !one_sided[a * kSlots + slot] &&
                                                     claims[a * kSlots + slot] == 1 &&
                                                     claims[b * kSlots + c.slot] == 1 &&
                                                     !proposes(a, c.node, slot) &&
                                                     !proposes(b, static_cast<int32_t>(a), c.slot);
                                  if (clean)
                                      lattice.neighbours[a][slot] = c.node;
                                  else
                                      is_contested[a * kSlots + slot] = 1;
                              }
                      });
    struct Contested {
        float distance;
        int32_t a, slot_a, b, slot_b;
        auto tie() const { return std::tie(distance, a, slot_a, b, slot_b); }
    };
    std::vector<Contested> contested;
    for (size_t i = 0; i < count * kSlots; ++i) {
        if (!is_contested[i])
            continue;
        const Candidate& c = candidates[i];
        const int32_t a = static_cast<int32_t>(i / kSlots), slot = static_cast<int32_t>(i % kSlots);
        if (!one_sided[i] && c.node < a)
            continue; // a two-sided link, listed from its lower end
        contested.push_back(a < c.node ? Contested{c.distance, a, slot, c.node, c.slot}
                                       : Contested{c.distance, c.node, c.slot, a, slot});
    }
    std::sort(contested.begin(), contested.end(),
              [](const Contested& x, const Contested& y) { return x.tie() < y.tie(); });
    for (const Contested& e : contested) {
        auto& na = lattice.neighbours[e.a];
        auto& nb = lattice.neighbours[e.b];
        if (na[e.slot_a] >= 0 || nb[e.slot_b] >= 0 ||
            std::find(na.begin(), na.end(), e.b) != na.end())
            continue;
        na[e.slot_a] = e.b;
        nb[e.slot_b] = e.a;
    }

    // Cell size: the mean length of the node's links, else of a texel step on its triangle.
    tbb::parallel_for(
        tbb::blocked_range<size_t>(0, count, 4096), [&](const tbb::blocked_range<size_t>& range) {
            for (size_t node = range.begin(); node != range.end(); ++node) {
                double sum = 0.0;
                int links = 0;
                for (int32_t b : lattice.neighbours[node])
                    if (b >= 0) {
                        sum += (lattice.position[node] - lattice.position[b]).length();
                        ++links;
                    }
                lattice.cell_size[node] =
                    links ? static_cast<float>(sum / links)
                          : 0.5f * (bld.expected[node][0] + bld.expected[node][1]);
            }
        });
    return lattice;
}

std::vector<std::vector<float>> lattice_to_groups(const Lattice& lattice,
                                                  std::span<const float> node_values,
                                                  const std::vector<TexelGrid>& grids)
{
    if (node_values.size() != lattice.size())
        throw std::runtime_error(fmt::format("lattice_to_groups: {} values for a lattice of {} "
                                             "nodes",
                                             node_values.size(), lattice.size()));
    std::vector<std::vector<float>> out(grids.size());
    for (size_t g = 0; g < grids.size(); ++g) {
        const TexelGrid& grid = grids[g];
        const auto tile_it =
            std::find_if(lattice.tiles.begin(), lattice.tiles.end(),
                         [&](const Lattice::Tile& t) { return t.udim == grid.udim; });
        if (tile_it == lattice.tiles.end())
            throw std::runtime_error(
                fmt::format("lattice_to_groups: the lattice has no UDIM {}", grid.udim));
        const Lattice::Tile& tile = *tile_it;
        std::vector<float>& values = out[g];
        values.assign(grid.groups.group_count(), 0.0f);
        const bool same_size = tile.width == grid.width && tile.height == grid.height;
        // For another resolution: the nearest texel, then a search of a few texels around.
        const int radius =
            same_size
                ? 0
                : 2 + static_cast<int>(std::ceil(std::max(double(tile.width) / grid.width,
                                                          double(tile.height) / grid.height)));
        tbb::parallel_for(
            tbb::blocked_range<int>(0, grid.height), [&](const tbb::blocked_range<int>& rows) {
                for (int y = rows.begin(); y != rows.end(); ++y)
                    for (int x = 0; x < grid.width; ++x) {
                        const int32_t group =
                            grid.group_of_texel[static_cast<size_t>(y) * grid.width + x];
                        if (group < 0)
                            continue;
                        const int tx =
                            same_size ? x : static_cast<int>((x + 0.5) * tile.width / grid.width);
                        const int ty =
                            same_size ? y : static_cast<int>((y + 0.5) * tile.height / grid.height);
                        int32_t node = -1;
                        int best = std::numeric_limits<int>::max();
                        for (int dy = -radius; dy <= radius; ++dy)
                            for (int dx = -radius; dx <= radius; ++dx) {
                                const int sx = tx + dx, sy = ty + dy;
                                const int d2 = dx * dx + dy * dy;
                                if (sx < 0 || sy < 0 || sx >= tile.width || sy >= tile.height ||
                                    d2 >= best)
                                    continue;
                                const int32_t n =
                                    tile.node_of_texel[static_cast<size_t>(sy) * tile.width + sx];
                                if (n >= 0) {
                                    node = n;
                                    best = d2;
                                }
                            }
                        if (node < 0)
                            throw std::runtime_error(fmt::format(
                                "lattice_to_groups: texel ({}, {}) of UDIM {} has no lattice node "
                                "within {} texels",
                                x, y, grid.udim, radius));
                        values[group] = node_values[node];
                    }
            });
    }
    return out;
}

} // namespace patina::texgen
