// The geometry of an exported asset: a strip as a plane of its real size, or the mesh a
// stack was grown on split into one primitive per UDIM tile (glTF has no UDIM: each tile's
// triangles get the tile's material, their uvs moved into the unit square).
#pragma once

#include "core/mesh.h"
#include "texgen/export/gltf_document.h"

#include <nlohmann/json.hpp>

#include <string>
#include <vector>

namespace patina::texgen {

/// One primitive: its attributes and index accessor, and the tile (index into the stack's
/// udims) whose material it takes.
struct TilePrimitive {
    size_t tile = 0;
    size_t material = 0;  ///< the mesh's source material (index into its `materials`), or 0
    nlohmann::json attributes;
    int indices = -1;
};

/// A strip of `width_m` x `height_m` as a plane facing +Z (glTF's front), uv (0, 0) at
/// the top-left corner of the maps (glTF's uv origin is the image's first row), with
/// tangents along +X.
TilePrimitive add_strip_plane(gltf::Document& doc, double width_m, double height_m);

/// The vertices and triangles of one UDIM tile of a mesh, as glTF stores them.
struct TileGeometry {
    size_t tile = 0;  ///< index into the stack's udims
    size_t material = 0;  ///< the source material of its triangles (index into `materials`)
    std::vector<Imath::V3f> positions, normals;
    std::vector<Imath::V4f> tangents;  ///< xyz, w = ±1 (glTF's bitangent = cross(N, T) w)
    std::vector<Imath::V2f> uvs;       ///< glTF's: (0, 0) at the image's top-left
    /// The mesh's source_uvs (the artist's first set) in glTF's convention, or empty.
    std::vector<Imath::V2f> source_uvs;
    std::vector<uint32_t> indices;
};

/// `mesh` (with uvs) split into the tiles of `udims` that hold triangles, and within a tile
/// by source material (a mesh of several keeps them apart): a triangle belongs to the tile
/// of its uv centroid, and its uvs become glTF's, (u − u0, v0 + 1 − v)
/// (Patina's uvs have v up, glTF's first image row at v = 0). Normals are the mesh's
/// (area-weighted vertex normals when it has none, the face normal where those vanish);
/// tangents follow the uv gradients (a normal map's green up the image, as flatten makes
/// it). Throws std::runtime_error starting with `context` for a mesh without uvs or a
/// triangle on a tile the stack does not have.
std::vector<TileGeometry> split_by_tile(const TriangleMesh& mesh, const std::vector<int>& udims,
                                        const std::string& context);

/// The texCoord index of the maps' uvs: 1 when the mesh keeps the artist's first set
/// (source_uvs, TEXCOORD_0) beside the set the maps were baked into, else 0.
inline int weathering_tex_coord(const TriangleMesh& mesh) { return mesh.source_uvs.empty() ? 0 : 1; }

/// split_by_tile's tiles as primitives of `doc`, one per tile: the maps' uvs are
/// TEXCOORD_<weathering_tex_coord(mesh)>.
std::vector<TilePrimitive> add_mesh_primitives(gltf::Document& doc, const TriangleMesh& mesh,
                                               const std::vector<int>& udims,
                                               const std::string& context);

/// The mean edge of a texel on `mesh`, in metres, for maps of `width` texels per tile side:
/// sqrt(surface area / uv area) / width (the uv area in tiles). It turns a height map's
/// texel differences into slopes for the normal map. Throws starting with `context` for a
/// mesh whose uvs cover no area.
double mean_texel_size_m(const TriangleMesh& mesh, int width, const std::string& context);

}  // namespace patina::texgen
