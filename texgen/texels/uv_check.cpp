#include "texgen/texels/uv_check.h"

#include "texgen/texels/texel_grid.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cmath>
#include <limits>
#include <numeric>
#include <tuple>

namespace patina::texgen {

namespace {

    /// Union-find with path halving.
    struct DisjointSets {
        std::vector<uint32_t> parent;
        explicit DisjointSets(size_t n) : parent(n) { std::iota(parent.begin(), parent.end(), 0u); }
        uint32_t find(uint32_t i)
        {
            while (parent[i] != i)
                i = parent[i] = parent[parent[i]];
            return i;
        }
        void join(uint32_t a, uint32_t b)
        {
            a = find(a);
            b = find(b);
            if (a != b)
                parent[std::max(a, b)] = std::min(a, b);
        }
    };

    /// Island of every triangle (an id shared by the triangles of one island).
    std::vector<uint32_t> triangle_islands(const TriangleMesh& mesh, size_t& island_count)
    {
        // Vertices with equal position and uv are one uv-vertex (loaders split vertices
        // whose normals differ; that is no seam in the uv layout).
        const size_t n = mesh.positions.size();
        std::vector<uint32_t> order(n);
        std::iota(order.begin(), order.end(), 0u);
        const auto key = [&](uint32_t v) {
            const Imath::V3f& p = mesh.positions[v];
            const Imath::V2f& t = mesh.uvs[v];
            return std::make_tuple(p.x, p.y, p.z, t.x, t.y);
        };
        std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
            return std::make_pair(key(a), a) < std::make_pair(key(b), b);
        });
        std::vector<uint32_t> canonical(n);
        for (size_t i = 0; i < n; ++i)
            canonical[order[i]] = i > 0 && key(order[i]) == key(order[i - 1])
                                      ? canonical[order[i - 1]]
                                      : order[i];

        // Triangles sharing a uv edge (both ends the same uv-vertices) are one island;
        // islands touching at a single corner stay apart, as their texels do.
        const size_t triangles = mesh.triangle_count();
        std::vector<std::pair<uint64_t, uint32_t>> edges;
        edges.reserve(3 * triangles);
        for (size_t t = 0; t < triangles; ++t)
            for (int e = 0; e < 3; ++e) {
                const uint32_t a = canonical[mesh.indices[3 * t + e]];
                const uint32_t b = canonical[mesh.indices[3 * t + (e + 1) % 3]];
                if (a != b)
                    edges.emplace_back(uint64_t(std::min(a, b)) << 32 | std::max(a, b),
                                       static_cast<uint32_t>(t));
            }
        std::sort(edges.begin(), edges.end());
        DisjointSets sets(triangles);
        for (size_t i = 1; i < edges.size(); ++i)
            if (edges[i].first == edges[i - 1].first)
                sets.join(edges[i].second, edges[i - 1].second);
        std::vector<uint32_t> island(triangles);
        island_count = 0;
        for (size_t t = 0; t < triangles; ++t) {
            island[t] = sets.find(static_cast<uint32_t>(t));
            island_count += island[t] == t;
        }
        return island;
    }

    /// Sort and deduplicate `pairs` in place.
    void unique_pairs(std::vector<uint64_t>& pairs)
    {
        std::sort(pairs.begin(), pairs.end());
        pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
    }

    std::string density_text(double density)
    {
        return fmt::format("{:.4g} texels/m^2 ({:.3g} mm texels)", density, texel_size_mm(density));
    }

}  // namespace

double texel_size_mm(double texels_per_m2)
{
    return texels_per_m2 > 0.0 ? 1000.0 / std::sqrt(texels_per_m2)
                               : std::numeric_limits<double>::infinity();
}

UvCheck check_uvs(const TriangleMesh& mesh, const UvCheckOptions& options)
{
    UvCheck check;
    check.mesh_name = mesh.name;
    check.triangles = mesh.triangle_count();
    check.vertices = mesh.positions.size();
    check.has_uvs = mesh.has_uvs();
    check.uv_set = mesh.uv_set;
    check.uv_set_count = mesh.uv_set_count;
    check.width = options.width;
    check.height = options.height;
    check.supersampling = options.supersampling;
    if (!check.has_uvs) {
        validate_mesh(mesh, fmt::format("mesh '{}'", mesh.name));
        check.topology = mesh_topology(mesh);
        return check;
    }
    check.topology = mesh_topology(mesh);

    // Lenient: triangles outside the UDIM tiles and degenerate ones are counted, not fatal.
    const UvRasterizer raster(mesh, RasterOptions{options.width, options.height,
                                                  options.supersampling},
                              true);
    check.udims = raster.udims();
    check.triangles_outside_udims = raster.stats().outside_udims;
    check.zero_uv_area = raster.stats().zero_uv_area;
    check.zero_surface_area = raster.stats().zero_surface_area;
    for (const Imath::V2f& uv : mesh.uvs)
        check.vertices_outside_udims +=
            !(uv.x >= 0.0f && uv.x < 10.0f && uv.y >= 0.0f && uv.y < 100.0f);

    const std::vector<uint32_t> island = triangle_islands(mesh, check.islands);

    // Texel density: each triangle's uv area in texels over its surface area.
    const double texels_per_uv_area = double(options.width) * options.height;
    double texels = 0.0, area = 0.0;
    std::vector<std::pair<double, double>> densities;  // (density, surface) per triangle
    check.texel_density_min = std::numeric_limits<double>::infinity();
    check.texel_density_max = 0.0;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const uint32_t i0 = mesh.indices[3 * t], i1 = mesh.indices[3 * t + 1],
                       i2 = mesh.indices[3 * t + 2];
        const Imath::V2d e1 = Imath::V2d(mesh.uvs[i1]) - Imath::V2d(mesh.uvs[i0]);
        const Imath::V2d e2 = Imath::V2d(mesh.uvs[i2]) - Imath::V2d(mesh.uvs[i0]);
        const double signed_uv_area = 0.5 * (e1.x * e2.y - e1.y * e2.x);
        const double uv_area = std::abs(signed_uv_area);
        const Imath::V3d p0(mesh.positions[i0]);
        const double surface = 0.5 * (Imath::V3d(mesh.positions[i1]) - p0)
                                         .cross(Imath::V3d(mesh.positions[i2]) - p0)
                                         .length();
        check.mirrored_uv_triangles += signed_uv_area < 0.0 && surface > 0.0;
        if (!(uv_area > 0.0 && surface > 0.0))
            continue;
        const double density = uv_area * texels_per_uv_area / surface;
        texels += uv_area * texels_per_uv_area;
        area += surface;
        check.texel_density_min = std::min(check.texel_density_min, density);
        check.texel_density_max = std::max(check.texel_density_max, density);
        densities.emplace_back(density, surface);
    }
    if (area > 0.0) {
        check.texel_density_mean = texels / area;
        double weighted = 0.0;
        for (const auto& [density, surface] : densities) {
            const double l = std::log2(density / check.texel_density_mean);
            weighted += surface * l * l;
        }
        check.stretch_rms_log2 = std::sqrt(weighted / area);
    } else {
        check.texel_density_min = 0.0;
    }

    // Overlaps: per band of texel rows, sub-samples that two or more triangles claim, and
    // the triangle pairs that claim the same sub-sample.
    const size_t tiles = check.udims.size();
    const int bands = raster.band_count();
    struct Band {
        size_t covered = 0;
        size_t overlapping = 0;
        std::vector<uint64_t> pairs;
    };
    std::vector<Band> results(tiles * bands);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, results.size(), 1),
                      [&](const tbb::blocked_range<size_t>& range) {
        std::vector<TexelHit> hits;
        for (size_t job = range.begin(); job != range.end(); ++job) {
            Band& band = results[job];
            raster.band_hits(job / bands, static_cast<int>(job % bands), hits);
            size_t compacted = 0;
            for (size_t i = 0; i < hits.size();) {
                size_t end = i + 1;
                while (end < hits.size() && hits[end].x == hits[i].x && hits[end].y == hits[i].y)
                    ++end;
                uint64_t seen = 0, twice = 0;
                for (size_t h = i; h < end; ++h) {
                    const uint64_t shared = seen & hits[h].inside;
                    twice |= shared;
                    seen |= hits[h].inside;
                    if (!shared)
                        continue;
                    for (size_t g = i; g < h; ++g)
                        if (hits[g].inside & hits[h].inside)
                            band.pairs.push_back(uint64_t(hits[g].triangle) << 32 |
                                                 hits[h].triangle);
                }
                band.covered += std::popcount(seen);
                band.overlapping += std::popcount(twice);
                // Neighbouring texels repeat the same pairs: keep the list short.
                if (band.pairs.size() > 2 * compacted + 4096) {
                    unique_pairs(band.pairs);
                    compacted = band.pairs.size();
                }
                i = end;
            }
            unique_pairs(band.pairs);
        }
    });

    std::vector<uint64_t> pairs;
    for (Band& band : results) {
        check.covered_sub_samples += band.covered;
        check.overlapping_sub_samples += band.overlapping;
        pairs.insert(pairs.end(), band.pairs.begin(), band.pairs.end());
        band.pairs = {};
    }
    unique_pairs(pairs);
    check.overlapping_triangle_pairs = pairs.size();
    std::vector<uint32_t> islands_involved;
    for (uint64_t pair : pairs) {
        islands_involved.push_back(island[pair >> 32]);
        islands_involved.push_back(island[pair & 0xffffffffu]);
    }
    std::sort(islands_involved.begin(), islands_involved.end());
    check.overlapping_islands =
        std::unique(islands_involved.begin(), islands_involved.end()) - islands_involved.begin();
    return check;
}

std::string UvCheck::refusal() const
{
    if (!has_uvs)
        return "the mesh has no uvs: bake per vertex (--per-vertex out.ply), or give it a uv "
               "layout";
    if (triangles_outside_udims > 0)
        return fmt::format("{} triangles lie outside the UDIM tiles: --uv-wrap folds them into "
                           "tile 1001 as a renderer's repeat wrapping reads them",
                           triangles_outside_udims);
    if (zero_uv_area + zero_surface_area >= triangles)
        return "every triangle has zero uv or surface area";
    return {};
}

std::string format_uv_check(const UvCheck& c)
{
    std::string out = fmt::format("mesh             '{}'\n", c.mesh_name);
    out += fmt::format("triangles        {}\n", c.triangles);
    out += fmt::format("vertices         {}\n", c.vertices);
    const MeshTopology& t = c.topology;
    out += fmt::format("surface          {} piece(s); {} open edges, {} non-manifold edges, {} "
                       "flipped faces{}\n",
                       t.pieces, t.boundary_edges, t.non_manifold_edges, t.flipped_faces,
                       t.flipped_faces ? " (wound against their neighbours: they bake their "
                                         "inside)"
                                       : "");
    const std::string refusal = c.refusal();
    const auto verdict = [&] {
        return refusal.empty()
                   ? fmt::format("bakers           will bake {} triangles{}\n",
                                 c.triangles - c.zero_uv_area - c.zero_surface_area,
                                 c.uv_wrap ? fmt::format(" ({} folded into tile 1001 by --uv-wrap)",
                                                         c.wrapped_triangles)
                                           : std::string())
                   : fmt::format("bakers           will refuse the mesh: {}\n", refusal);
    };
    if (!c.has_uvs) {
        out += "uvs              missing: no uvs; bake per vertex with --per-vertex out.ply\n";
        return out + verdict();
    }
    out += fmt::format("uvs              set {} of {}{}\n", c.uv_set, c.uv_set_count,
                       c.uv_set_count > 1 ? " (--uv-set chooses the set to bake into)" : "");
    out += fmt::format("uv islands       {}\n", c.islands);
    if (c.overlaps())
        out += fmt::format("overlapping uvs  {:.3g}% of the covered uv area ({} of {} sub-samples "
                           "at {} x {}, {}x{} per texel): {} triangle pairs in {} islands\n",
                           100.0 * c.overlap_fraction(), c.overlapping_sub_samples,
                           c.covered_sub_samples, c.width, c.height, c.supersampling,
                           c.supersampling, c.overlapping_triangle_pairs, c.overlapping_islands);
    if (c.overlaps())
        out += "                 overlapping texels average different surface points: give the "
               "mesh a layout of its own (patina-texgen unwrap MESH -o OUT.glb, then bake OUT.glb "
               "with the --uv-set it names)\n";
    else
        out += fmt::format("overlapping uvs  none ({} covered sub-samples at {} x {}, {}x{} per "
                           "texel)\n",
                           c.covered_sub_samples, c.width, c.height, c.supersampling,
                           c.supersampling);
    std::string tiles;
    for (int udim : c.udims)
        tiles += fmt::format("{}{}", tiles.empty() ? "" : " ", udim);
    out += fmt::format("udim tiles       {}\n", tiles.empty() ? "none" : tiles);
    if (c.vertices_outside_udims || c.triangles_outside_udims)
        out += fmt::format("outside udims    {} vertices have uvs outside 0 <= u < 10, 0 <= v < "
                           "100; {} triangles by their uv centroid\n",
                           c.vertices_outside_udims, c.triangles_outside_udims);
    else
        out += "outside udims    none\n";
    if (c.zero_uv_area || c.zero_surface_area)
        out += fmt::format("degenerate       {} triangles with zero uv area, {} with zero surface "
                           "area (not baked)\n",
                           c.zero_uv_area, c.zero_surface_area);
    else
        out += "degenerate       none\n";
    if (c.mirrored_uv_triangles)
        out += fmt::format("mirrored uvs     {} triangles (clockwise in uv: a tangent-space normal "
                           "map flips there)\n", c.mirrored_uv_triangles);
    if (c.texel_density_mean > 0.0) {
        out += fmt::format("texel density    at {} x {}: mean {}\n", c.width, c.height,
                           density_text(c.texel_density_mean));
        out += fmt::format("                 min {}\n", density_text(c.texel_density_min));
        out += fmt::format("                 max {}\n", density_text(c.texel_density_max));
    } else {
        out += "texel density    none (no triangle has uv and surface area)\n";
    }
    return out + verdict();
}

}  // namespace patina::texgen
