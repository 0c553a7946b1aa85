#include "texgen/slabs/slab_shell.h"

#include "core/embree_scene.h"
#include "texgen/slabs/slab_mapping.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <stdexcept>
#include <unordered_map>

namespace patina::texgen::stone {

using Imath::V3d;

namespace {

    V3d to_d(const Imath::V3f& v) { return V3d(v.x, v.y, v.z); }

    double angle_between(const V3d& a, const V3d& b)
    {
        return std::atan2(a.cross(b).length(), a.dot(b));
    }

    /// Weld vertices whose positions agree to 1e-7 of the mesh's size; returns the welded
    /// index of every vertex and the welded positions.
    std::vector<int> weld(const TriangleMesh& mesh, std::vector<V3d>& points)
    {
        Imath::Box3d box;
        for (const auto& p : mesh.positions)
            box.extendBy(to_d(p));
        const double q = std::max(1e-12, (box.max - box.min).length() * 1e-7);
        std::map<std::array<long long, 3>, int> index;
        std::vector<int> of(mesh.positions.size());
        for (size_t i = 0; i < mesh.positions.size(); ++i) {
            const V3d p = to_d(mesh.positions[i]);
            const std::array<long long, 3> key{std::llround(p.x / q), std::llround(p.y / q),
                                               std::llround(p.z / q)};
            auto [it, added] = index.emplace(key, static_cast<int>(points.size()));
            if (added)
                points.push_back(p);
            of[i] = it->second;
        }
        return of;
    }

    /// Distance along the ray to the mesh, or infinity.
    double ray_distance(const EmbreeScene& scene, const V3d& origin, const V3d& dir,
                        double start)
    {
        const Imath::V3f o(float(origin.x), float(origin.y), float(origin.z));
        const Imath::V3f d(float(dir.x), float(dir.y), float(dir.z));
        auto hit = scene.intersect(o, d, float(start));
        return hit ? double(hit->t) : std::numeric_limits<double>::infinity();
    }

} // namespace

double slab_jacobian_determinant(const SlabCorners& c, const V3d& uvw)
{
    V3d du, dv, dw;
    slab_derivatives(c, uvw, du, dv, dw);
    return du.cross(dv).dot(dw);
}

SlabShell build_slab_shell(const TriangleMesh& base, const ShellOptions& options)
{
    if (!(options.depth > 0.0) || options.outer_margin < 0.0 || !(options.clearance > 0.0) ||
        options.clearance >= 1.0)
        throw std::runtime_error(fmt::format(
            "slab shell: depth must be > 0 (got {}), outer margin >= 0 (got {}), clearance in "
            "(0, 1) (got {})", options.depth, options.outer_margin, options.clearance));
    SlabShell shell;
    std::vector<V3d>& pts = shell.points;
    const std::vector<int> welded = weld(base, pts);
    const size_t vertex_count = pts.size();

    // Triangles on welded vertices; degenerate ones (collapsed poles, zero area) are dropped.
    std::vector<std::array<int, 3>> tris;
    std::vector<V3d> face_normals;
    for (size_t t = 0; t < base.triangle_count(); ++t) {
        const int a = welded[base.indices[3 * t]], b = welded[base.indices[3 * t + 1]],
                  c = welded[base.indices[3 * t + 2]];
        if (a == b || b == c || a == c)
            continue;
        const V3d n = (pts[b] - pts[a]).cross(pts[c] - pts[a]);
        if (n.length() <= 1e-20)
            continue;
        tris.push_back({a, b, c});
        face_normals.push_back(n.normalized());
    }
    if (tris.empty())
        throw std::runtime_error(fmt::format("slab shell: mesh '{}' has no triangle of non-zero "
                                             "area", base.name));

    // Split each triangle into three quads: (a, m_ab, centroid, m_ca), and so on.
    std::map<std::pair<int, int>, int> midpoint;
    auto midpoint_of = [&](int a, int b) {
        const auto key = std::minmax(a, b);
        auto [it, added] = midpoint.emplace(key, static_cast<int>(pts.size()));
        if (added)
            pts.push_back(0.5 * (pts[a] + pts[b]));
        return it->second;
    };
    // Angle-weighted normals of the split mesh: each quad corner contributes its angle times
    // the face normal (an edge midpoint sees each adjacent face with the angle pi).
    std::vector<V3d> normal_sum;
    for (size_t t = 0; t < tris.size(); ++t) {
        const auto [a, b, c] = tris[t];
        const int mab = midpoint_of(a, b), mbc = midpoint_of(b, c), mca = midpoint_of(c, a);
        const int f = static_cast<int>(pts.size());
        pts.push_back((pts[a] + pts[b] + pts[c]) / 3.0);
        normal_sum.resize(pts.size(), V3d(0.0));
        const V3d& n = face_normals[t];
        const int corner[3] = {a, b, c};
        for (int k = 0; k < 3; ++k) {
            const int p = corner[k], q = corner[(k + 1) % 3], r = corner[(k + 2) % 3];
            normal_sum[p] += angle_between(pts[q] - pts[p], pts[r] - pts[p]) * n;
        }
        normal_sum[mab] += M_PI * n;
        normal_sum[mbc] += M_PI * n;
        normal_sum[mca] += M_PI * n;
        normal_sum[f] += 2.0 * M_PI * n;
        shell.quads.push_back({a, mab, f, mca});
        shell.quads.push_back({b, mbc, f, mab});
        shell.quads.push_back({c, mca, f, mbc});
    }
    (void)vertex_count;
    const size_t n_pts = pts.size();
    shell.normals.resize(n_pts);
    for (size_t i = 0; i < n_pts; ++i) {
        const double l = normal_sum[i].length();
        if (!(l > 0.0))
            throw std::runtime_error("slab shell: a point without a normal (mesh not closed?)");
        shell.normals[i] = normal_sum[i] / l;
    }

    // Depth limits: half the way (clearance) to the opposite wall, inwards and outwards.
    EmbreeScene scene;
    scene.add_mesh(base);
    scene.commit();
    const Imath::Box3f b3 = scene.bounds();
    const double size = (to_d(b3.max) - to_d(b3.min)).length();
    const double start = size * 1e-5;
    shell.depths.assign(n_pts, options.depth);
    shell.margins.assign(n_pts, options.outer_margin);
    tbb::parallel_for(size_t(0), n_pts, [&](size_t i) {
        const V3d& p = pts[i];
        const V3d& n = shell.normals[i];
        const double in = ray_distance(scene, p, -n, start);
        shell.depths[i] = std::min(shell.depths[i], options.clearance * in);
        if (options.outer_margin > 0.0) {
            const double out = ray_distance(scene, p, n, start);
            shell.margins[i] = std::min(shell.margins[i], options.clearance * out);
        }
    });

    // Curvature limit on every quad edge, then Lipschitz smoothing.
    std::vector<std::pair<int, int>> edges;
    for (const auto& q : shell.quads)
        for (int k = 0; k < 4; ++k)
            edges.emplace_back(std::minmax(q[k], q[(k + 1) % 4]));
    std::sort(edges.begin(), edges.end());
    edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
    for (const auto& [a, b] : edges) {
        const V3d e = pts[b] - pts[a];
        const double k = e.dot(shell.normals[b] - shell.normals[a]);
        const double e2 = e.dot(e);
        if (k > 0.0) {
            const double limit = 0.7 * e2 / k;
            shell.depths[a] = std::min(shell.depths[a], limit);
            shell.depths[b] = std::min(shell.depths[b], limit);
        } else if (k < 0.0) {
            const double limit = 0.7 * e2 / -k;
            shell.margins[a] = std::min(shell.margins[a], limit);
            shell.margins[b] = std::min(shell.margins[b], limit);
        }
    }
    for (int pass = 0; pass < 32; ++pass) {
        bool changed = false;
        for (const auto& [a, b] : edges) {
            const double l = 0.5 * (pts[b] - pts[a]).length();
            for (std::vector<double>* d : {&shell.depths, &shell.margins}) {
                double& da = (*d)[a];
                double& db = (*d)[b];
                if (da > db + l) { da = db + l; changed = true; }
                if (db > da + l) { db = da + l; changed = true; }
            }
        }
        if (!changed)
            break;
    }

    // Build the slabs; pull in the inner corners of any slab whose Jacobian changes sign.
    const size_t n_slabs = shell.quads.size();
    shell.slabs.resize(n_slabs);
    auto build = [&](size_t s) {
        const auto& q = shell.quads[s];
        const int uv_corner[4] = {0, 1, 3, 2}; // quad order (0,0),(1,0),(1,1),(0,1)
        for (int k = 0; k < 4; ++k) {
            const int p = q[k];
            shell.slabs[s][uv_corner[k]] = pts[p] + shell.margins[p] * shell.normals[p];
            shell.slabs[s][uv_corner[k] + 4] = pts[p] - shell.depths[p] * shell.normals[p];
        }
    };
    auto folds = [&](size_t s) {
        // Valid slabs have det J < 0 everywhere (u x v outwards, w inwards). The det is
        // normalised by |du| |dv| |dw| (the sine-like measure of how far w leans over the
        // face), so corners of different depths and skinny quads compare alike; a fold is a
        // point where w (nearly) lies in the face.
        for (int i = 0; i < 27; ++i) {
            const V3d uvw(0.5 * (i % 3), 0.5 * ((i / 3) % 3), 0.5 * (i / 9));
            V3d du, dv, dw;
            slab_derivatives(shell.slabs[s], uvw, du, dv, dw);
            const double scale = du.length() * dv.length() * dw.length();
            if (!(du.cross(dv).dot(dw) < -1e-3 * scale))
                return true;
        }
        return false;
    };
    for (size_t s = 0; s < n_slabs; ++s)
        build(s);
    std::vector<char> fixed(n_slabs, 0);
    for (int pass = 0; pass < 40; ++pass) {
        bool any = false;
        for (size_t s = 0; s < n_slabs; ++s) {
            if (!folds(s))
                continue;
            any = true;
            fixed[s] = 1;
            for (int p : shell.quads[s]) {
                shell.depths[p] *= 0.7;
                shell.margins[p] *= 0.7;
            }
        }
        if (!any)
            break;
        for (size_t s = 0; s < n_slabs; ++s)
            build(s);
    }
    for (size_t s = 0; s < n_slabs; ++s)
        if (folds(s))
            throw std::runtime_error(fmt::format(
                "slab shell: slab {} still folds after pulling its corners in (mesh '{}' may "
                "not be closed or consistently wound)", s, base.name));
    // Overlaps between slabs that are not neighbours (the inner faces of opposite sides of a
    // ridge or a narrow part): sample each slab's lower half; where a sample lies in another
    // slab, pull both slabs' inner corners up, until no sample does. A new overlap can only
    // involve a slab whose corners moved, so after the first pass only the moved slabs and
    // the slabs whose boxes meet theirs are sampled again (on fine meshes this pass was
    // most of the shell's set-up time).
    std::vector<std::vector<int>> slabs_of_point(n_pts);
    for (size_t s = 0; s < n_slabs; ++s)
        for (int p : shell.quads[s])
            slabs_of_point[size_t(p)].push_back(int(s));
    std::vector<char> moved(n_slabs, 1);
    for (int pass = 0; pass < 30; ++pass) {
        const SlabLocator locator(shell.slabs);
        std::vector<char> check = moved;
        if (pass > 0)
            for (size_t m = 0; m < n_slabs; ++m)
                if (moved[m])
                    locator.for_each_near(locator.box(m), [&](int t) { check[size_t(t)] = 1; });
        std::vector<char> overlapping(n_slabs, 0);
        tbb::parallel_for(size_t(0), n_slabs, [&](size_t s) {
            if (!check[s])
                return;
            for (int i = 0; i < 18; ++i) {
                const V3d uvw(0.1 + 0.4 * (i % 3), 0.1 + 0.4 * ((i / 3) % 3), i < 9 ? 0.6 : 0.95);
                for (const SlabPoint& at : locator.locate_all(slab_to_world(shell.slabs[s], uvw), 0.0))
                    if (at.slab != int(s)) {
                        overlapping[s] = 1;
                        return;
                    }
            }
        });
        std::fill(moved.begin(), moved.end(), 0);
        bool any = false;
        for (size_t s = 0; s < n_slabs; ++s)
            if (overlapping[s]) {
                any = true;
                fixed[s] = 1;
                for (int p : shell.quads[s]) {
                    shell.depths[size_t(p)] *= 0.8;
                    for (int t : slabs_of_point[size_t(p)])
                        moved[size_t(t)] = 1;
                }
            }
        if (!any)
            break;
        for (size_t s = 0; s < n_slabs; ++s)
            if (moved[s])
                build(s);
    }
    shell.folded_fixes = static_cast<int>(std::count(fixed.begin(), fixed.end(), 1));

    // Neighbours across each edge (two slabs share an edge when they share its two points).
    std::map<std::pair<int, int>, std::vector<std::pair<int, int>>> by_edge;
    for (size_t s = 0; s < n_slabs; ++s) {
        const auto& q = shell.quads[s];
        for (int k = 0; k < 4; ++k)
            by_edge[std::minmax(q[k], q[(k + 1) % 4])].emplace_back(int(s), k);
    }
    // Quad edge k runs q[k] -> q[k+1]: k = 0 is v = 0, 1 is u = 1, 2 is v = 1, 3 is u = 0.
    shell.neighbours.assign(n_slabs, {-1, -1, -1, -1});
    for (const auto& [edge, users] : by_edge)
        if (users.size() == 2) {
            shell.neighbours[users[0].first][users[0].second] = users[1].first;
            shell.neighbours[users[1].first][users[1].second] = users[0].first;
        }
    return shell;
}

} // namespace patina::texgen::stone
