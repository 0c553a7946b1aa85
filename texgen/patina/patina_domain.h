// Where a patina script runs: the texels its maps are written to, the lattice its growth
// models run on, and the surface point of each (for baked maps, inclination and height).
// Node i of the lattice is group i of the texel grids, tile after tile, so one array per
// map serves the models, the operators and the output.
#pragma once

#include "core/mesh.h"
#include "texgen/growth/lattice.h"
#include "texgen/texels/texel_grid.h"

#include <Imath/ImathBox.h>
#include <Imath/ImathVec.h>

#include <vector>

namespace patina::texgen {

struct PatinaDomain {
    std::vector<TexelGrid> grids;   ///< the output texels
    Lattice lattice;                ///< one node per texel group, in grid order
    /// Per node: the surface point (the first sample of the texel), its unit normal, its uv.
    std::vector<Imath::V3f> position;
    std::vector<Imath::V3f> normal;
    std::vector<Imath::V2f> uv;
    /// Per node: the texel's share of the surface (coverage), the weight of "area" in
    /// `polish until F exposed`.
    std::vector<float> area_weight;
    Imath::Box3f bounds;            ///< of the surface
    /// A flat strip: a height field of `width` x `height` square cells `cell_size_m` wide
    /// (the operators that need the neighbourhood of a texel, offset, work on it directly).
    bool is_strip = false;
    GridBoundary boundary = GridBoundary::open;  ///< of a strip's lattice and offsets
    int width = 0, height = 0;
    double cell_size_m = 0;
    const TriangleMesh* mesh = nullptr;  ///< the mesh, when not a strip

    size_t size() const { return position.size(); }
    /// Per-tile values (as write_texel_map takes them) from per-node values.
    std::vector<std::vector<float>> per_tile(const std::vector<float>& node_values) const;
};

/// A flat copper strip (the paper's §5.1 strips) of width x height texels, `size_m` wide
/// along x: every texel covered, one sample at its centre, lying in the y = 0 plane facing
/// up (+y, so `inclination` is 1), uv covering [0, 1]^2 (tile 1001). The lattice is the
/// plain grid (make_grid_lattice) with the given boundary, node y * width + x.
PatinaDomain make_strip_domain(int width, int height, double size_m,
                               GridBoundary boundary = GridBoundary::open);

/// The covered texels of `mesh`'s uv layout (rasterize_uv) as the domain, with the surface
/// lattice continued across uv seams (surface_lattice.h). `mesh` must outlive the domain.
PatinaDomain make_mesh_domain(const TriangleMesh& mesh, const RasterOptions& options);

/// Per node: the share of its samples that lie on triangles of the source material
/// `material` (1 inside a part of that material, between 0 and 1 on a texel its border
/// crosses). Throws std::runtime_error naming the materials the mesh has when it has none
/// of that name, and for a strip (which has no source materials).
std::vector<float> material_fraction(const PatinaDomain& domain, const std::string& material);

}  // namespace patina::texgen
