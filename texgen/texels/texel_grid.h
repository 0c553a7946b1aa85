// Texel set-up: every UV triangle rasterised into a texel grid per UDIM tile, with
// conservative coverage and supersampling; each covered texel holds the surface samples a
// baker evaluates (world position, shading and geometric normal).
#pragma once

#include "core/mesh.h"
#include "texgen/texels/surface_samples.h"

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

/// One group per vertex, holding the vertex itself ("triangulations as texture maps",
/// Dorsey & Hanrahan 1996 §3.3): N is the vertex normal (area-weighted face normals when
/// the mesh has none), Ng equals N.
SampleGroups vertex_samples(const TriangleMesh& mesh);

}  // namespace patina::texgen
