// Triangle meshes: loading any format Assimp reads (OBJ, PLY, glTF, FBX, ...) with node
// transforms applied, checks that turn bad input into errors naming the file, and the
// procedural shapes that samples and tests use.
#pragma once

#include "core/mesh_convention.h"

#include <Imath/ImathMatrix.h>
#include <Imath/ImathVec.h>

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace patina {

struct ImageData;

/// A source material's base colour texture: an image file beside the mesh, or an image
/// embedded in the mesh file (a .glb's buffer, an FBX's embedded media) as the file stores
/// it. Read with read_material_texture.
struct MaterialTexture {
    std::filesystem::path file;  ///< an image file; empty when embedded
    std::string name;            ///< the image's name as the mesh file gives it
    std::filesystem::path container;  ///< the mesh file an embedded image is in
    /// An embedded image's bytes as stored (PNG, JPEG, ...), `format` its extension ("png")...
    std::shared_ptr<const std::vector<unsigned char>> encoded;
    std::string format;
    /// ... or, for the uncompressed kind (Assimp's aiTexture with a height), its texels.
    std::shared_ptr<const ImageData> texels;

    bool empty() const { return file.empty() && !encoded && !texels; }
};

/// The texels of `texture`: read from its file, or decoded from the bytes embedded in the
/// mesh file. Errors name the image (and the mesh file that holds it).
ImageData read_material_texture(const MaterialTexture& texture);

/// An indexed triangle mesh in world space. `normals` and `uvs` are per vertex and either
/// empty or as long as `positions`. Triangles wind counter-clockwise seen from the side
/// the normals point to (the right-hand rule gives the outward geometric normal).
/// UVs follow the file: (0,0) at the bottom-left of the texture, v up (OpenGL convention).
struct TriangleMesh {
    std::string name;
    std::string material_name;
    /// The source material's base colour (glTF baseColorFactor, else the diffuse colour;
    /// linear RGBA as the file stores it) and its base colour texture, a file beside the
    /// mesh or embedded in it (empty when absent).
    Imath::V4f base_colour{0.8f, 0.8f, 0.8f, 1.0f};
    MaterialTexture base_colour_texture;
    std::vector<Imath::V3f> positions;
    std::vector<Imath::V3f> normals;
    std::vector<Imath::V2f> uvs;   ///< the uv set Patina bakes into (the file's first, or --uv-set)
    /// The file's first uv set (the artist's, for their own textures) when `uvs` holds
    /// another; empty otherwise. Export keeps it as TEXCOORD_0.
    std::vector<Imath::V2f> source_uvs;
    int uv_set = 0;        ///< which of the file's uv sets `uvs` holds
    int uv_set_count = 0;  ///< how many the file has for this mesh
    std::vector<uint32_t> indices; ///< 3 per triangle
    /// When meshes of several materials are merged (texgen's merge_meshes): the source
    /// material of each triangle, an index into `materials`. Empty: every triangle is
    /// `material_name`'s.
    std::vector<uint16_t> triangle_material;
    std::vector<std::string> materials;
    std::vector<Imath::V4f> material_base_colours;                ///< per entry of `materials`
    std::vector<MaterialTexture> material_base_textures;        ///< per entry of `materials`

    /// The source material of triangle `t`.
    const std::string& material_of(size_t t) const
    {
        return triangle_material.empty() ? material_name : materials[triangle_material[t]];
    }

    size_t triangle_count() const { return indices.size() / 3; }
    bool has_normals() const { return !normals.empty(); }
    bool has_uvs() const { return !uvs.empty(); }
};

/// Load every mesh of a scene file through Assimp, triangulated, in Patina's world (+Y up,
/// metres): each node's transform, then the file's axes and unit (what the file declares,
/// overridden by `convention`; mesh_convention.h), then `transform` (Imath row-vector
/// convention: p' = p * transform). `applied`, when given, receives the convention used and
/// its warnings (an option that contradicts the file). One TriangleMesh per mesh instance
/// in the node graph; points and lines are dropped. Missing normals stay missing (shading
/// uses the geometric normal; call compute_vertex_normals for smooth shading). Throws
/// std::runtime_error naming the file when it is missing or Assimp cannot parse it, when it
/// holds no triangles, or when a position is NaN/Inf or an index is out of range.
std::vector<TriangleMesh> load_meshes(const std::filesystem::path& path,
                                      const MeshConventionOptions& convention = {},
                                      MeshConvention* applied = nullptr,
                                      const Imath::M44f& transform = Imath::M44f());

/// The world bounds of `meshes`, or of one mesh.
Imath::Box3f bounds_of(const std::vector<TriangleMesh>& meshes);
Imath::Box3f bounds_of(const TriangleMesh& mesh);

/// Check the invariants above (sizes, index range, finite values); throws
/// std::runtime_error starting with `context` (e.g. the file name).
void validate_mesh(const TriangleMesh& mesh, const std::string& context);

/// Replace `mesh.normals` by area-weighted averages of the face normals around each vertex.
/// A vertex used only by degenerate triangles gets a zero normal (shading then falls back
/// to the geometric normal).
void compute_vertex_normals(TriangleMesh& mesh);

/// Sum of the triangle areas.
double surface_area(const TriangleMesh& mesh);

/// A UV sphere with poles on the y axis: `rings` >= 2 bands of latitude, `segments` >= 3
/// of longitude. u = longitude / 2 pi (from +z towards +x), v = 0 at the south pole, 1 at
/// the north; exact unit normals; a seam of duplicated vertices at u = 0/1.
TriangleMesh make_uv_sphere(const Imath::V3f& center, float radius, int rings, int segments);

/// A square of side `size` centred at `center`, facing `normal` (default +y, "up"),
/// divided into `subdivisions` x `subdivisions` cells; uv spans [0,1]^2 with dPdu along
/// +x for an up-facing plane and cross(dPdu, dPdv) along the normal.
TriangleMesh make_plane(const Imath::V3f& center, float size, int subdivisions = 1,
                        const Imath::V3f& normal = Imath::V3f(0, 1, 0));
/// make_plane with one cell (two triangles).
TriangleMesh make_quad(const Imath::V3f& center, float size,
                       const Imath::V3f& normal = Imath::V3f(0, 1, 0));

/// An axis-aligned box with edge lengths `size`: 6 faces of 4 vertices each, outward
/// normals, each face's uv spanning [0,1]^2.
TriangleMesh make_box(const Imath::V3f& center, const Imath::V3f& size);

}  // namespace patina
