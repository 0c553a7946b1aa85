// uv-check: what a mesh's uv layout means for baking, before a bake: missing uvs,
// islands, overlapping uv area (texels two surfaces would share), texel density, UDIM tiles.
#pragma once

#include "core/mesh.h"
#include "texgen/texels/mesh_topology.h"

#include <string>
#include <vector>

namespace patina::texgen {

struct UvCheckOptions {
    int width = 1024;  ///< resolution of the maps the texel density is given for
    int height = 1024;
    int supersampling = 2;  ///< sub-samples per texel axis for the overlap measure
};

/// The numbers of a uv check. Overlap is measured on the sub-sample centres of the texel
/// grid (as rasterize_uv sees them); texel density per triangle is its uv area in texels
/// over its surface area.
struct UvCheck {
    std::string mesh_name;
    size_t triangles = 0;
    size_t vertices = 0;
    bool has_uvs = false;
    int uv_set = 0;        ///< the set checked (--uv-set)
    int uv_set_count = 0;  ///< the sets the file has
    int width = 0;
    int height = 0;
    int supersampling = 0;

    /// Connected sets of triangles joined through shared uv edges: edges whose two ends
    /// are the same uv-vertices (one vertex, or vertices with equal position and uv, so
    /// split normals do not cut an island). Corners alone do not join islands.
    size_t islands = 0;

    size_t covered_sub_samples = 0;      ///< sub-sample centres inside a triangle
    size_t overlapping_sub_samples = 0;  ///< ... inside two or more triangles
    size_t overlapping_triangle_pairs = 0;
    size_t overlapping_islands = 0;  ///< islands holding a triangle of an overlapping pair

    /// Texels per square metre of surface (mean = all texels over all area; min and max
    /// over triangles), degenerate triangles left out.
    double texel_density_mean = 0.0;
    double texel_density_min = 0.0;
    double texel_density_max = 0.0;
    /// The area-weighted RMS of log2(density / mean) over triangles: 0 when every triangle
    /// gets the same texels per square metre, 1 when they typically differ by a factor of 2.
    double stretch_rms_log2 = 0.0;

    std::vector<int> udims;              ///< tiles used, ascending
    size_t vertices_outside_udims = 0;   ///< uv outside 0 <= u < 10, 0 <= v < 100
    size_t triangles_outside_udims = 0;  ///< uv centroid outside: not baked
    size_t zero_uv_area = 0;             ///< degenerate triangles, not baked
    size_t zero_surface_area = 0;
    size_t wrapped_triangles = 0;        ///< folded into tile 1001 by --uv-wrap (the caller's)
    bool uv_wrap = false;                ///< the bakers were asked to fold (--uv-wrap)
    /// Triangles whose uvs run clockwise while the surface runs counter-clockwise (mirrored
    /// uv islands): tangent-space normal maps flip there.
    size_t mirrored_uv_triangles = 0;
    MeshTopology topology;

    /// Why the bakers would refuse this mesh (no uvs, triangles outside the UDIM tiles, no
    /// triangle of non-zero area); empty when they bake it.
    std::string refusal() const;

    bool overlaps() const { return overlapping_sub_samples > 0; }
    /// Overlapping over covered sub-samples: the share of the covered uv area that more
    /// than one triangle claims.
    double overlap_fraction() const
    {
        return covered_sub_samples ? double(overlapping_sub_samples) / covered_sub_samples : 0.0;
    }
};

/// Analyse `mesh`. A mesh without uvs is not an error (has_uvs is false); throws
/// std::runtime_error for bad options and non-finite positions or uvs, naming the vertex.
UvCheck check_uvs(const TriangleMesh& mesh, const UvCheckOptions& options);

/// The report uv-check prints, one finding per line.
std::string format_uv_check(const UvCheck& check);

/// Side of a square texel, in millimetres, at a density in texels per square metre.
double texel_size_mm(double texels_per_m2);

}  // namespace patina::texgen
