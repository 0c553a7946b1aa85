#include "texgen/texels/texel_grid.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <bit>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace patina::texgen {

namespace {

    using Imath::V2d;

    constexpr int kUdimColumns = 10;  // UDIM: u0 in 0..9
    constexpr int kUdimRows = 100;    // v0 in 0..99 (UDIM 1001..1999)
    constexpr int kMaxResolution = 65536;
    /// Triangles whose corner angle has a sine below this are degenerate: their uvs or
    /// positions are collinear to within float rounding.
    constexpr double kDegenerateSine = 1e-9;
    /// Coverage of a texel the mesh only grazes when the exact area rounds to nothing.
    constexpr float kMinGrazeCoverage = 1e-6f;

    double cross(const V2d& a, const V2d& b) { return a.x * b.y - a.y * b.x; }

    bool lexicographic_less(const V2d& a, const V2d& b)
    {
        return a.x < b.x || (a.x == b.x && a.y < b.y);
    }

    /// One edge of a triangle for the inside test. The edge function is always evaluated
    /// from the lexicographically smaller endpoint, so the two triangles sharing an edge
    /// compute the same number and see it with opposite signs: a point is never inside
    /// both nor outside both (up to the test of their other edges). A point exactly on the
    /// edge counts as inside when moving it by (eps, eps^2) would take it inside: the same
    /// perturbation for every triangle, so shared edges and vertices are counted once.
    struct Edge {
        V2d a;                   ///< origin: the smaller endpoint
        V2d d;                   ///< the other endpoint minus a
        double sign = 1.0;       ///< sign * E(p) > 0 inside the triangle
        bool tie_inside = false;

        Edge(const V2d& from, const V2d& to, double orientation)
        {
            const bool swap = lexicographic_less(to, from);
            a = swap ? to : from;
            d = swap ? from - to : to - from;
            sign = swap ? -orientation : orientation;
            // dE/dx = -d.y, dE/dy = d.x (E below).
            tie_inside = sign * -d.y > 0.0 || (d.y == 0.0 && sign * d.x > 0.0);
        }
        double value(const V2d& p) const { return sign * (d.x * (p.y - a.y) - d.y * (p.x - a.x)); }
        bool contains(const V2d& p) const
        {
            const double e = value(p);
            return e > 0.0 || (e == 0.0 && tie_inside);
        }
    };

    struct TriangleEdges {
        Edge e[3];
        TriangleEdges(const V2d* p)
            : TriangleEdges(p, cross(p[1] - p[0], p[2] - p[0]) > 0.0 ? 1.0 : -1.0)
        {
        }
        TriangleEdges(const V2d* p, double orientation)
            : e{Edge(p[0], p[1], orientation), Edge(p[1], p[2], orientation),
                Edge(p[2], p[0], orientation)}
        {
        }
        bool contains(const V2d& q) const
        {
            return e[0].contains(q) && e[1].contains(q) && e[2].contains(q);
        }
    };

    /// Sine of the angle at p0 of a triangle, from the lengths of two edges and twice
    /// its area (0 for coincident points).
    template <class V>
    bool degenerate(double twice_area, const V& e1, const V& e2)
    {
        const double scale = std::sqrt(double(e1.length2())) * std::sqrt(double(e2.length2()));
        return !(std::abs(twice_area) > kDegenerateSine * scale);
    }

    V2d closest_on_segment(const V2d& a, const V2d& b, const V2d& q)
    {
        const V2d ab = b - a;
        const double t = std::clamp((q - a).dot(ab) / ab.length2(), 0.0, 1.0);
        return a + t * ab;
    }

    /// Area of the triangle inside the axis-aligned box (Sutherland-Hodgman clipping).
    double clipped_area(const V2d* tri, const V2d& lo, const V2d& hi)
    {
        V2d buffer[2][9];
        int n = 3;
        std::copy(tri, tri + 3, buffer[0]);
        int cur = 0;
        for (int side = 0; side < 4 && n > 0; ++side) {
            const int axis = side / 2;
            const bool keep_above = side % 2 == 0;
            const double bound = keep_above ? lo[axis] : hi[axis];
            const auto inside = [&](const V2d& p) {
                return keep_above ? p[axis] >= bound : p[axis] <= bound;
            };
            const V2d* in = buffer[cur];
            V2d* out = buffer[1 - cur];
            int m = 0;
            for (int i = 0; i < n; ++i) {
                const V2d& p = in[i];
                const V2d& q = in[(i + 1) % n];
                if (inside(p))
                    out[m++] = p;
                if (inside(p) != inside(q)) {
                    const double t = (bound - p[axis]) / (q[axis] - p[axis]);
                    out[m++] = p + t * (q - p);
                }
            }
            n = m;
            cur = 1 - cur;
        }
        double twice = 0.0;
        for (int i = 0; i < n; ++i)
            twice += cross(buffer[cur][i], buffer[cur][(i + 1) % n]);
        return 0.5 * std::abs(twice);
    }

    std::string mesh_label(const TriangleMesh& mesh)
    {
        return fmt::format("mesh '{}'", mesh.name.empty() ? std::string("(unnamed)") : mesh.name);
    }

    /// Sizes, index range, finite positions (validate_mesh) and finite uvs.
    void check_mesh_values(const TriangleMesh& mesh)
    {
        validate_mesh(mesh, mesh_label(mesh));
        for (size_t i = 0; i < mesh.uvs.size(); ++i)
            if (!std::isfinite(mesh.uvs[i].x) || !std::isfinite(mesh.uvs[i].y))
                throw std::runtime_error(fmt::format("{}: vertex {} has a non-finite uv ({}, {})",
                                                     mesh_label(mesh), i, mesh.uvs[i].x,
                                                     mesh.uvs[i].y));
        if (mesh.triangle_count() == 0)
            throw std::runtime_error(fmt::format("{} has no triangles", mesh_label(mesh)));
    }

    Imath::V3d twice_area_vector(const TriangleMesh& mesh, size_t t)
    {
        const Imath::V3d a(mesh.positions[mesh.indices[3 * t]]);
        const Imath::V3d b(mesh.positions[mesh.indices[3 * t + 1]]);
        const Imath::V3d c(mesh.positions[mesh.indices[3 * t + 2]]);
        return (b - a).cross(c - a);
    }

    bool zero_surface_area(const TriangleMesh& mesh, size_t t)
    {
        const Imath::V3d a(mesh.positions[mesh.indices[3 * t]]);
        const Imath::V3d b(mesh.positions[mesh.indices[3 * t + 1]]);
        const Imath::V3d c(mesh.positions[mesh.indices[3 * t + 2]]);
        return degenerate((b - a).cross(c - a).length(), b - a, c - a);
    }

    /// A surface sample at barycentric coordinates `b` of triangle `t`; `ng` is the unit
    /// geometric normal of the triangle (the winding's side).
    SurfaceSample make_sample(const TriangleMesh& mesh, uint32_t t, const Imath::V3d& b,
                              const Imath::V3f& ng)
    {
        const uint32_t i0 = mesh.indices[3 * t], i1 = mesh.indices[3 * t + 1],
                       i2 = mesh.indices[3 * t + 2];
        const float b0 = static_cast<float>(b.x), b1 = static_cast<float>(b.y),
                    b2 = static_cast<float>(b.z);
        SurfaceSample s;
        s.P = b0 * mesh.positions[i0] + b1 * mesh.positions[i1] + b2 * mesh.positions[i2];
        s.N = ng;
        if (mesh.has_normals()) {
            const Imath::V3f n = b0 * mesh.normals[i0] + b1 * mesh.normals[i1] +
                                 b2 * mesh.normals[i2];
            const float len2 = n.length2();
            if (std::isfinite(len2) && len2 > 1e-20f)
                s.N = n / std::sqrt(len2);
        }
        s.Ng = ng.dot(s.N) < 0.0f ? -ng : ng;
        s.uv = b0 * mesh.uvs[i0] + b1 * mesh.uvs[i1] + b2 * mesh.uvs[i2];
        s.triangle = t;
        return s;
    }

}  // namespace

int udim_of(int u0, int v0)
{
    if (u0 < 0 || u0 >= kUdimColumns || v0 < 0 || v0 >= kUdimRows)
        throw std::runtime_error(fmt::format("uv tile ({}, {}) is outside the UDIM range "
                                             "(u 0..9, v 0..99)", u0, v0));
    return 1001 + u0 + kUdimColumns * v0;
}

UvRasterizer::UvRasterizer(const TriangleMesh& mesh, const RasterOptions& options, bool lenient)
    : mesh_(mesh), options_(options)
{
    if (options.width < 1 || options.height < 1 || options.width > kMaxResolution ||
        options.height > kMaxResolution)
        throw std::runtime_error(
            fmt::format("resolution must be 1..{} texels per side (got {} x {})", kMaxResolution,
                        options.width, options.height));
    if (options.supersampling < 1 || options.supersampling > kMaxSupersampling)
        throw std::runtime_error(fmt::format("supersampling must be 1..{} (got {})",
                                             kMaxSupersampling, options.supersampling));
    if (!mesh.has_uvs())
        throw std::runtime_error(fmt::format(
            "{} has no uvs, so it has no texels to bake; add uvs, or bake per vertex with "
            "--per-vertex out.ply",
            mesh_label(mesh)));
    check_mesh_values(mesh);

    // Place every triangle in its tile (the tile of its uv centroid), in parallel.
    const size_t count = mesh.triangle_count();
    const double k = 2.0 * options.supersampling;
    const double scale_x = k * options.width, scale_y = k * options.height;
    enum : int { kPlaced = 0, kZeroUv, kZeroSurface, kOutside };
    std::vector<int> tile_key(count, -1);
    std::vector<uint8_t> status(count);
    triangles_.resize(count);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
        for (size_t t = range.begin(); t != range.end(); ++t) {
            const Imath::V2f* uv[3] = {&mesh.uvs[mesh.indices[3 * t]],
                                       &mesh.uvs[mesh.indices[3 * t + 1]],
                                       &mesh.uvs[mesh.indices[3 * t + 2]]};
            const V2d uv0(*uv[0]), uv1(*uv[1]), uv2(*uv[2]);
            if (degenerate(cross(uv1 - uv0, uv2 - uv0), uv1 - uv0, uv2 - uv0)) {
                status[t] = kZeroUv;
                continue;
            }
            if (zero_surface_area(mesh, t)) {
                status[t] = kZeroSurface;
                continue;
            }
            const V2d centroid = (uv0 + uv1 + uv2) / 3.0;
            const double u0 = std::floor(centroid.x), v0 = std::floor(centroid.y);
            if (!(u0 >= 0 && u0 < kUdimColumns && v0 >= 0 && v0 < kUdimRows)) {
                status[t] = kOutside;
                continue;
            }
            status[t] = kPlaced;
            tile_key[t] = static_cast<int>(u0) + kUdimColumns * static_cast<int>(v0);
            // Scaled texel space of the tile, y down (row 0 at v = v0 + 1). Exact for float
            // uvs: a float times an integer below 2^21 fits a double's mantissa.
            Placed& placed = triangles_[t];
            for (int i = 0; i < 3; ++i)
                placed.p[i] = V2d((double(uv[i]->x) - u0) * scale_x,
                                  (v0 + 1.0 - double(uv[i]->y)) * scale_y);
        }
    });

    size_t first_outside = count;
    std::array<bool, kUdimColumns * kUdimRows> used{};
    for (size_t t = 0; t < count; ++t) {
        switch (status[t]) {
        case kZeroUv: ++stats_.zero_uv_area; break;
        case kZeroSurface: ++stats_.zero_surface_area; break;
        case kOutside:
            ++stats_.outside_udims;
            first_outside = std::min(first_outside, t);
            break;
        default: used[tile_key[t]] = true;
        }
    }
    if (!lenient && first_outside < count) {
        const size_t t = first_outside;
        const Imath::V2f c = (mesh.uvs[mesh.indices[3 * t]] + mesh.uvs[mesh.indices[3 * t + 1]] +
                              mesh.uvs[mesh.indices[3 * t + 2]]) / 3.0f;
        throw std::runtime_error(fmt::format(
            "{}: triangle {} has its uv centroid at ({}, {}), outside the UDIM tiles "
            "(0 <= u < 10, 0 <= v < 100); {} triangles are outside. --uv-wrap folds them into "
            "tile 1001 as a renderer's repeat wrapping reads them (patina-texgen uv-check "
            "reports the layout)",
            mesh_label(mesh), t, c.x, c.y, stats_.outside_udims));
    }
    if (!lenient && stats_.zero_uv_area + stats_.zero_surface_area == count)
        throw std::runtime_error(fmt::format(
            "{}: zero-area mesh: all {} triangles have zero uv area ({}) or zero surface area "
            "({})",
            mesh_label(mesh), count, stats_.zero_uv_area, stats_.zero_surface_area));

    std::array<int, kUdimColumns * kUdimRows> tile_index{};
    for (int key = 0; key < kUdimColumns * kUdimRows; ++key)
        if (used[key]) {
            tile_index[key] = static_cast<int>(udims_.size());
            udims_.push_back(1001 + key);
        }

    // Bin the triangles into bands of rows by the rows their open squares can touch:
    // counts, prefix sums, then a fill in triangle order (so every band lists ascending).
    const int bands = band_count();
    const size_t tiles = udims_.size();
    band_begin_.assign(tiles, std::vector<uint32_t>(bands + 1, 0));
    band_triangles_.assign(tiles, {});
    const auto band_range = [&](const Placed& p, int& first, int& last) {
        const double y_min = std::min({p.p[0].y, p.p[1].y, p.p[2].y});
        const double y_max = std::max({p.p[0].y, p.p[1].y, p.p[2].y});
        const int row_first = std::max(0, static_cast<int>(std::floor(y_min / k)));
        const int row_last = std::min(options_.height - 1,
                                      static_cast<int>(std::ceil(y_max / k)) - 1);
        first = row_first / kBandRows;
        last = row_first <= row_last ? row_last / kBandRows : first - 1;
    };
    for (size_t t = 0; t < count; ++t) {
        if (status[t] != kPlaced)
            continue;
        Placed& p = triangles_[t];
        p.tile = tile_index[tile_key[t]];
        int first, last;
        band_range(p, first, last);
        for (int b = first; b <= last; ++b)
            ++band_begin_[p.tile][b + 1];
    }
    for (size_t tile = 0; tile < tiles; ++tile) {
        for (int b = 0; b < bands; ++b)
            band_begin_[tile][b + 1] += band_begin_[tile][b];
        band_triangles_[tile].resize(band_begin_[tile][bands]);
    }
    std::vector<std::vector<uint32_t>> fill = band_begin_;
    for (size_t t = 0; t < count; ++t) {
        if (status[t] != kPlaced)
            continue;
        const Placed& p = triangles_[t];
        int first, last;
        band_range(p, first, last);
        for (int b = first; b <= last; ++b)
            band_triangles_[p.tile][fill[p.tile][b]++] = static_cast<uint32_t>(t);
    }
}

void UvRasterizer::band_hits(size_t tile, int band, std::vector<TexelHit>& hits) const
{
    hits.clear();
    const int s = options_.supersampling;
    const double k = 2.0 * s;
    const int width = options_.width;
    const int row_begin = band * kBandRows;
    const int row_end = std::min(options_.height, row_begin + kBandRows);
    const uint64_t full_mask = s * s == 64 ? ~uint64_t(0) : (uint64_t(1) << (s * s)) - 1;
    // Slack when turning the exact slab extent into columns; the separating-axis test
    // below decides exactly.
    const double slack = 1e-9 * k;

    std::vector<TexelHit> raw;
    for (uint32_t i = band_begin_[tile][band]; i != band_begin_[tile][band + 1]; ++i) {
        const uint32_t t = band_triangles_[tile][i];
        const V2d* p = triangles_[t].p;
        const TriangleEdges edges(p);
        const double x_min = std::min({p[0].x, p[1].x, p[2].x});
        const double x_max = std::max({p[0].x, p[1].x, p[2].x});
        const double y_min = std::min({p[0].y, p[1].y, p[2].y});
        const double y_max = std::max({p[0].y, p[1].y, p[2].y});
        const int first_row = std::max(row_begin, static_cast<int>(std::floor(y_min / k)));
        const int last_row = std::min(row_end - 1, static_cast<int>(std::ceil(y_max / k)) - 1);
        for (int y = first_row; y <= last_row; ++y) {
            // The triangle's x extent inside the slab of this row: its vertices in the
            // slab and its edges' crossings of the slab's two lines.
            const double lo = y * k, hi = (y + 1) * k;
            double slab_min = std::numeric_limits<double>::infinity();
            double slab_max = -slab_min;
            for (int v = 0; v < 3; ++v) {
                const V2d& a = p[v];
                const V2d& b = p[(v + 1) % 3];
                if (a.y >= lo && a.y <= hi) {
                    slab_min = std::min(slab_min, a.x);
                    slab_max = std::max(slab_max, a.x);
                }
                if (a.y == b.y)
                    continue;
                for (double line : {lo, hi})
                    if ((line - a.y) * (line - b.y) <= 0.0) {
                        const double x = a.x + (line - a.y) / (b.y - a.y) * (b.x - a.x);
                        slab_min = std::min(slab_min, x);
                        slab_max = std::max(slab_max, x);
                    }
            }
            if (!(slab_min <= slab_max))
                continue;
            const int first_col = std::max(0, static_cast<int>(std::floor((slab_min - slack) / k)));
            const int last_col = std::min(width - 1,
                                          static_cast<int>(std::ceil((slab_max + slack) / k)) - 1);
            for (int x = first_col; x <= last_col; ++x) {
                // Separating axes of a triangle and the open texel square: the two box
                // axes, then each edge's normal (the edge function over the box corners).
                const double bx0 = x * k, bx1 = (x + 1) * k;
                if (x_max <= bx0 || x_min >= bx1 || y_max <= lo || y_min >= hi)
                    continue;
                bool separated = false, all_inside = true;
                for (const Edge& e : edges.e) {
                    double e_min = std::numeric_limits<double>::infinity(), e_max = -e_min;
                    for (const V2d& corner :
                         {V2d(bx0, lo), V2d(bx1, lo), V2d(bx0, hi), V2d(bx1, hi)}) {
                        const double value = e.value(corner);
                        e_min = std::min(e_min, value);
                        e_max = std::max(e_max, value);
                    }
                    separated = separated || e_max <= 0.0;
                    all_inside = all_inside && e_min > 0.0;
                }
                if (separated)
                    continue;
                uint64_t inside = 0;
                if (all_inside) {
                    inside = full_mask;
                } else {
                    // Sub-sample centres at odd coordinates of the scaled space.
                    for (int j = 0; j < s; ++j)
                        for (int i = 0; i < s; ++i)
                            if (edges.contains(V2d(bx0 + 2 * i + 1, lo + 2 * j + 1)))
                                inside |= uint64_t(1) << (j * s + i);
                }
                raw.push_back({x, y, t, inside});
            }
        }
    }

    // Counting sort by texel (stable: triangles stay ascending within a texel).
    const size_t texels = static_cast<size_t>(row_end - row_begin) * width;
    std::vector<uint32_t> start(texels + 1, 0);
    for (const TexelHit& h : raw)
        ++start[static_cast<size_t>(h.y - row_begin) * width + h.x + 1];
    for (size_t i = 0; i < texels; ++i)
        start[i + 1] += start[i];
    hits.resize(raw.size());
    for (const TexelHit& h : raw)
        hits[start[static_cast<size_t>(h.y - row_begin) * width + h.x]++] = h;
}

Imath::V2d UvRasterizer::nearest_point(uint32_t triangle, int x, int y) const
{
    const double k = 2.0 * options_.supersampling;
    const V2d* p = triangles_[triangle].p;
    const V2d q((x + 0.5) * k, (y + 0.5) * k);
    const double orientation = cross(p[1] - p[0], p[2] - p[0]) > 0.0 ? 1.0 : -1.0;
    bool inside = true;
    for (int v = 0; v < 3; ++v)
        inside = inside && orientation * cross(p[(v + 1) % 3] - p[v], q - p[v]) >= 0.0;
    if (inside)
        return q / k;
    V2d best = p[0];
    double best_d2 = std::numeric_limits<double>::infinity();
    for (int v = 0; v < 3; ++v) {
        const V2d c = closest_on_segment(p[v], p[(v + 1) % 3], q);
        const double d2 = (c - q).length2();
        if (d2 < best_d2) {
            best_d2 = d2;
            best = c;
        }
    }
    return best / k;
}

double UvRasterizer::area_in_texel(uint32_t triangle, int x, int y) const
{
    const double k = 2.0 * options_.supersampling;
    return clipped_area(triangles_[triangle].p, V2d(x * k, y * k), V2d((x + 1) * k, (y + 1) * k)) /
           (k * k);
}

UvRasterizer::BarycentricMap UvRasterizer::barycentric_map(uint32_t triangle, int x, int y) const
{
    // q - p0 = b1 e1 + b2 e2 (Cramer's rule), evaluated relative to p0 and the texel corner
    // so that large texel coordinates cost no precision.
    const double k = 2.0 * options_.supersampling;
    const V2d* p = triangles_[triangle].p;
    const V2d e1 = p[1] - p[0], e2 = p[2] - p[0];
    const double area = cross(e1, e2);
    const V2d d = V2d(x * k, y * k) - p[0];
    const double b1 = cross(d, e2) / area, b2 = cross(e1, d) / area;
    const double b1_x = k * e2.y / area, b1_y = -k * e2.x / area;
    const double b2_x = -k * e1.y / area, b2_y = k * e1.x / area;
    return {Imath::V3d(1.0 - b1 - b2, b1, b2), Imath::V3d(-b1_x - b2_x, b1_x, b2_x),
            Imath::V3d(-b1_y - b2_y, b1_y, b2_y)};
}

std::vector<TexelGrid> rasterize_uv(const TriangleMesh& mesh, const RasterOptions& options)
{
    RasterStats stats;
    return rasterize_uv(mesh, options, stats);
}

std::vector<TexelGrid> rasterize_uv(const TriangleMesh& mesh, const RasterOptions& options,
                                    RasterStats& stats)
{
    const UvRasterizer raster(mesh, options);
    stats = raster.stats();
    const int s = options.supersampling;
    const int width = options.width;
    const size_t tiles = raster.udims().size();
    const int bands = raster.band_count();
    const size_t texels = static_cast<size_t>(width) * options.height;

    std::vector<TexelGrid> grids(tiles);
    for (size_t t = 0; t < tiles; ++t) {
        grids[t].udim = raster.udims()[t];
        grids[t].width = width;
        grids[t].height = options.height;
        grids[t].group_of_texel.assign(texels, -1);
        grids[t].coverage.assign(texels, 0.0f);
    }

    // Pass 1, per band: which triangle each sub-sample centre belongs to (the
    // lowest-numbered where uvs overlap), or for a texel the mesh only grazes, the
    // triangle whose nearest point is closest to the texel centre (mask 0).
    struct Entry {
        size_t texel;
        uint32_t triangle;
        uint64_t mask;
    };
    struct Band {
        std::vector<Entry> entries;
        size_t groups = 0;
        size_t samples = 0;
    };
    std::vector<Band> results(tiles * bands);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, results.size(), 1),
                      [&](const tbb::blocked_range<size_t>& range) {
        std::vector<TexelHit> hits;
        for (size_t job = range.begin(); job != range.end(); ++job) {
            const size_t tile = job / bands;
            Band& band = results[job];
            raster.band_hits(tile, static_cast<int>(job % bands), hits);
            for (size_t i = 0; i < hits.size();) {
                size_t end = i + 1;
                while (end < hits.size() && hits[end].x == hits[i].x && hits[end].y == hits[i].y)
                    ++end;
                const int x = hits[i].x, y = hits[i].y;
                const size_t texel = static_cast<size_t>(y) * width + x;
                uint64_t taken = 0;
                for (size_t h = i; h < end; ++h) {
                    const uint64_t own = hits[h].inside & ~taken;
                    if (own) {
                        taken |= own;
                        band.entries.push_back({texel, hits[h].triangle, own});
                    }
                }
                if (taken) {
                    const int n = std::popcount(taken);
                    grids[tile].coverage[texel] = static_cast<float>(n) / static_cast<float>(s * s);
                    band.samples += n;
                } else {
                    const V2d centre(x + 0.5, y + 0.5);
                    double best_d2 = std::numeric_limits<double>::infinity(), area = 0.0;
                    uint32_t best = hits[i].triangle;
                    for (size_t h = i; h < end; ++h) {
                        const double d2 =
                            (raster.nearest_point(hits[h].triangle, x, y) - centre).length2();
                        if (d2 < best_d2) {
                            best_d2 = d2;
                            best = hits[h].triangle;
                        }
                        area += raster.area_in_texel(hits[h].triangle, x, y);
                    }
                    grids[tile].coverage[texel] =
                        std::clamp(static_cast<float>(area), kMinGrazeCoverage, 1.0f);
                    band.entries.push_back({texel, best, 0});
                    band.samples += 1;
                }
                band.groups += 1;
                i = end;
            }
        }
    });

    // Offsets of every band's groups and samples in its tile (texel scan order).
    std::vector<size_t> group_base(results.size()), sample_base(results.size());
    for (size_t t = 0; t < tiles; ++t) {
        size_t groups = 0, samples = 0;
        for (int b = 0; b < bands; ++b) {
            group_base[t * bands + b] = groups;
            sample_base[t * bands + b] = samples;
            groups += results[t * bands + b].groups;
            samples += results[t * bands + b].samples;
        }
        if (samples > std::numeric_limits<uint32_t>::max() ||
            groups > static_cast<size_t>(std::numeric_limits<int32_t>::max()))
            throw std::runtime_error(fmt::format(
                "{} x {} texels with {}x{} supersampling make {} samples in UDIM {}, more than "
                "2^32; lower the resolution or the supersampling",
                width, options.height, s, s, samples, grids[t].udim));
        grids[t].groups.offsets.assign(groups + 1, static_cast<uint32_t>(samples));
        grids[t].groups.samples.resize(samples);
    }

    // Pass 2: the samples themselves, written in place.
    std::vector<double> sub_centre(s);
    for (int i = 0; i < s; ++i)
        sub_centre[i] = (i + 0.5) / s;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, results.size(), 1),
                      [&](const tbb::blocked_range<size_t>& range) {
        for (size_t job = range.begin(); job != range.end(); ++job) {
            TexelGrid& grid = grids[job / bands];
            const std::vector<Entry>& entries = results[job].entries;
            size_t group = group_base[job];
            size_t next = sample_base[job];
            for (size_t i = 0; i < entries.size(); ++i) {
                const Entry& entry = entries[i];
                if (i == 0 || entries[i - 1].texel != entry.texel) {
                    grid.group_of_texel[entry.texel] = static_cast<int32_t>(group);
                    grid.groups.offsets[group++] = static_cast<uint32_t>(next);
                }
                const int x = static_cast<int>(entry.texel % width);
                const int y = static_cast<int>(entry.texel / width);
                const Imath::V3f ng(twice_area_vector(mesh, entry.triangle).normalized());
                const UvRasterizer::BarycentricMap b = raster.barycentric_map(entry.triangle, x, y);
                if (entry.mask == 0) {
                    const V2d q = raster.nearest_point(entry.triangle, x, y);
                    grid.groups.samples[next++] =
                        make_sample(mesh, entry.triangle, b.at(q.x - x, q.y - y), ng);
                    continue;
                }
                for (uint64_t mask = entry.mask; mask; mask &= mask - 1) {
                    const int bit = std::countr_zero(mask);
                    grid.groups.samples[next++] = make_sample(
                        mesh, entry.triangle, b.at(sub_centre[bit % s], sub_centre[bit / s]), ng);
                }
            }
        }
    });
    return grids;
}

SampleGroups vertex_samples(const TriangleMesh& mesh)
{
    check_mesh_values(mesh);
    const size_t vertices = mesh.positions.size();
    // Area-weighted face normals (the cross product's length is twice the area), and the
    // first triangle of non-zero area that uses each vertex.
    std::vector<Imath::V3d> face_sum(vertices, Imath::V3d(0.0));
    std::vector<uint32_t> first_triangle(vertices, std::numeric_limits<uint32_t>::max());
    size_t degenerate_count = 0;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        if (zero_surface_area(mesh, t)) {
            ++degenerate_count;
            continue;
        }
        const Imath::V3d n = twice_area_vector(mesh, t);
        for (int c = 0; c < 3; ++c) {
            const uint32_t v = mesh.indices[3 * t + c];
            face_sum[v] += n;
            first_triangle[v] = std::min(first_triangle[v], static_cast<uint32_t>(t));
        }
    }
    if (degenerate_count == mesh.triangle_count())
        throw std::runtime_error(fmt::format("{}: zero-area mesh: all {} triangles have zero "
                                             "surface area",
                                             mesh_label(mesh), degenerate_count));

    SampleGroups groups;
    groups.offsets.reserve(vertices + 1);
    groups.samples.reserve(vertices);
    for (size_t v = 0; v < vertices; ++v) {
        if (first_triangle[v] == std::numeric_limits<uint32_t>::max() ||
            !(face_sum[v].length2() > 0.0)) {
            groups.offsets.push_back(static_cast<uint32_t>(groups.samples.size()));
            continue;
        }
        SurfaceSample s;
        s.P = mesh.positions[v];
        s.N = Imath::V3f(face_sum[v].normalized());
        if (mesh.has_normals()) {
            const float len2 = mesh.normals[v].length2();
            if (std::isfinite(len2) && len2 > 1e-20f)
                s.N = mesh.normals[v] / std::sqrt(len2);
        }
        s.Ng = s.N;
        s.uv = mesh.has_uvs() ? mesh.uvs[v] : Imath::V2f(0.0f);
        s.triangle = first_triangle[v];
        groups.samples.push_back(s);
        groups.offsets.push_back(static_cast<uint32_t>(groups.samples.size()));
    }
    return groups;
}

}  // namespace patina::texgen
