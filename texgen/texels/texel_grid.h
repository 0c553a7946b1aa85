// Texel set-up: every UV triangle rasterised into a texel grid per UDIM tile, with
// conservative coverage and supersampling; each covered texel holds the surface samples a
// baker evaluates (world position, shading and geometric normal).
#pragma once

#include "core/mesh.h"
#include "texgen/texels/surface_samples.h"

#include <Imath/ImathVec.h>

#include <cstdint>
#include <vector>

namespace patina::texgen {

/// The UDIM number of the unit uv square [u0, u0 + 1) x [v0, v0 + 1): 1001 + u0 + 10 v0
/// (u0 in 0..9, v0 >= 0).
int udim_of(int u0, int v0);

/// The texels of one UDIM tile. Image convention: texel (x, y) covers
/// u in [u0 + x / width, u0 + (x + 1) / width) and v in [v0 + 1 - (y + 1) / height,
/// v0 + 1 - y / height): row 0 is the top (v = 1), as in every image file.
struct TexelGrid {
    int udim = 1001;
    int width = 0;
    int height = 0;
    /// Per texel (y * width + x): index of its group in `groups`, or -1 if no triangle
    /// touches it.
    std::vector<int32_t> group_of_texel;
    /// Per texel: the fraction of its area the mesh covers, in [0, 1] (0 for uncovered).
    std::vector<float> coverage;
    SampleGroups groups;

    size_t texel_count() const { return static_cast<size_t>(width) * height; }
    int covered_count() const { return static_cast<int>(groups.group_count()); }
};

struct RasterOptions {
    int width = 1024;
    int height = 1024;
    /// Sub-samples per texel along each axis (s x s per texel).
    int supersampling = 2;
};

/// Rasterise `mesh` (which must have uvs; throws std::runtime_error naming the mesh and
/// suggesting the per-vertex mode otherwise) into one TexelGrid per UDIM tile its uvs touch,
/// sorted by UDIM. Coverage is conservative: a texel any triangle touches is covered; its
/// samples are the sub-sample centres inside triangles, or, when none is, the point of the
/// touching triangle nearest the texel centre.
std::vector<TexelGrid> rasterize_uv(const TriangleMesh& mesh, const RasterOptions& options);

/// What rasterize_uv left out.
struct RasterStats {
    size_t zero_uv_area = 0;       ///< triangles whose three uvs are (nearly) collinear
    size_t zero_surface_area = 0;  ///< triangles with uv area but no surface area
    size_t outside_udims = 0;      ///< uv centroid outside u in [0, 10), v in [0, 100)
};

/// rasterize_uv that also reports the skipped triangles. Details of both: a triangle
/// belongs to the UDIM tile of its uv centroid and is clipped to that tile; degenerate
/// triangles are skipped and counted (a mesh with nothing else throws "zero-area mesh"); a
/// triangle outside the tiles throws, naming it. Where uvs overlap, a sub-sample
/// goes to the lowest-numbered triangle (uv-check reports overlaps). A texel the mesh only
/// grazes gets its exact covered area as coverage (at least 1e-6). Samples carry the mesh's
/// own uv (tile offset included). Parallel (TBB), and bitwise the same for any thread count.
std::vector<TexelGrid> rasterize_uv(const TriangleMesh& mesh, const RasterOptions& options,
                                    RasterStats& stats);

/// One texel a triangle touches: the triangle overlaps the texel's open square, and bit
/// (j * s + i) of `inside` is set when the centre of sub-sample (i, j) (i to the right, j
/// down the image) lies inside the triangle. Centres on an edge shared by two triangles
/// fall in exactly one of them (a fixed perturbation decides ties).
struct TexelHit {
    int x = 0;
    int y = 0;
    uint32_t triangle = 0;
    uint64_t inside = 0;
};

/// The uv triangles of a mesh placed in the texel grids of their UDIM tiles, for
/// rasterising band by band (rasterize_uv and uv-check share it). Triangles are checked and
/// assigned to tiles by their uv centroid on construction.
class UvRasterizer {
public:
    /// Rows of texels per band: small enough for many parallel jobs, large enough that few
    /// triangles straddle bands.
    static constexpr int kBandRows = 16;
    /// Largest `supersampling` (the sub-sample mask has 64 bits).
    static constexpr int kMaxSupersampling = 8;

    /// Throws std::runtime_error naming the mesh for: no uvs (suggesting the per-vertex
    /// mode), a non-finite position or uv (naming the vertex), bad options, and, unless
    /// `lenient`, a triangle outside the UDIM range or a mesh with no triangle of non-zero
    /// uv and surface area ("zero-area mesh"). Lenient (uv-check) counts and skips those.
    UvRasterizer(const TriangleMesh& mesh, const RasterOptions& options, bool lenient = false);

    /// UDIM numbers of the tiles holding at least one triangle, ascending.
    const std::vector<int>& udims() const { return udims_; }
    int band_count() const { return (options_.height + kBandRows - 1) / kBandRows; }
    const RasterStats& stats() const { return stats_; }
    const RasterOptions& options() const { return options_; }
    /// Index into udims() of the triangle's tile, or -1 when it was skipped.
    int tile_of(uint32_t triangle) const { return triangles_[triangle].tile; }

    /// Replace `hits` by every TexelHit of band `band` of tile `tile` (an index into
    /// udims()), in texel scan order and, per texel, in ascending triangle order.
    void band_hits(size_t tile, int band, std::vector<TexelHit>& hits) const;

    /// Texel-space helpers for a hit's triangle: the point of the triangle nearest the
    /// centre of texel (x, y), in texels, and the area of the triangle inside that texel as
    /// a fraction of the texel.
    Imath::V2d nearest_point(uint32_t triangle, int x, int y) const;
    double area_in_texel(uint32_t triangle, int x, int y) const;
    /// Barycentric coordinates of the triangle near texel (x, y), as an affine function of
    /// the offset (fx, fy) in texels from the texel's top-left corner:
    /// b = at_corner + fx per_x + fy per_y (relative to the texel, to keep precision).
    struct BarycentricMap {
        Imath::V3d at_corner, per_x, per_y;
        Imath::V3d at(double fx, double fy) const { return at_corner + fx * per_x + fy * per_y; }
    };
    BarycentricMap barycentric_map(uint32_t triangle, int x, int y) const;

private:
    /// A triangle in the scaled texel space of its tile: one texel spans 2 s units, so
    /// sub-sample centres sit on odd integers and the coordinates of float uvs are exact.
    struct Placed {
        Imath::V2d p[3];
        int tile = -1;
    };
    const TriangleMesh& mesh_;
    RasterOptions options_;
    RasterStats stats_;
    std::vector<Placed> triangles_;
    std::vector<int> udims_;
    /// Per tile: the triangles of band b are band_triangles_[t][band_begin_[t][b] ..
    /// band_begin_[t][b + 1]), ascending.
    std::vector<std::vector<uint32_t>> band_begin_;
    std::vector<std::vector<uint32_t>> band_triangles_;
};

/// One group per vertex, holding the vertex itself ("triangulations as texture maps",
/// Dorsey & Hanrahan 1996 §3.3): N is the vertex normal (area-weighted face normals when
/// the mesh has none), Ng equals N, uv the vertex's uv (0 without uvs), triangle the first
/// triangle using it. A vertex no triangle of non-zero area uses has no normal: its group is
/// empty (bake_groups gives it 0). Throws like rasterize_uv for non-finite values and for a
/// zero-area mesh; uvs are not needed.
SampleGroups vertex_samples(const TriangleMesh& mesh);

}  // namespace patina::texgen
