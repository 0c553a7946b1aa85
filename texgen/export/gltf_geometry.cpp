#include "texgen/export/gltf_geometry.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <unordered_map>

namespace patina::texgen {

using nlohmann::json;

namespace {

    /// The attributes and indices of one primitive, as accessors of `doc`; POSITION with
    /// its bounds (glTF 2.0 §5.1.1 requires them).
    TilePrimitive add_primitive(gltf::Document& doc, size_t tile,
                                const std::vector<Imath::V3f>& positions,
                                const std::vector<Imath::V3f>& normals,
                                const std::vector<Imath::V4f>& tangents,
                                const std::vector<Imath::V2f>& uvs,
                                const std::vector<uint32_t>& indices,
                                const std::vector<Imath::V2f>& source_uvs = {})
    {
        constexpr float inf = std::numeric_limits<float>::infinity();
        std::vector<float> lo(3, inf), hi(3, -inf);
        for (const Imath::V3f& p : positions)
            for (int a = 0; a < 3; ++a) {
                lo[a] = std::min(lo[a], p[a]);
                hi[a] = std::max(hi[a], p[a]);
            }
        auto view = [&](const auto& values, int target) {
            return doc.add_view(values.data(), values.size() * sizeof(values[0]), target);
        };
        TilePrimitive out;
        out.tile = tile;
        out.attributes["POSITION"] = doc.add_accessor(view(positions, gltf::kArrayBuffer),
                                                      gltf::kFloat, positions.size(), "VEC3",
                                                      lo, hi);
        out.attributes["NORMAL"] = doc.add_accessor(view(normals, gltf::kArrayBuffer),
                                                    gltf::kFloat, normals.size(), "VEC3");
        if (!tangents.empty())
            out.attributes["TANGENT"] = doc.add_accessor(view(tangents, gltf::kArrayBuffer),
                                                         gltf::kFloat, tangents.size(), "VEC4");
        // The artist's own uvs, when the maps are on another set, stay TEXCOORD_0 for their
        // textures; the maps' set is TEXCOORD_1 (weathering_tex_coord).
        const std::string maps_set = source_uvs.empty() ? "TEXCOORD_0" : "TEXCOORD_1";
        if (!source_uvs.empty())
            out.attributes["TEXCOORD_0"] = doc.add_accessor(view(source_uvs, gltf::kArrayBuffer),
                                                            gltf::kFloat, source_uvs.size(),
                                                            "VEC2");
        out.attributes[maps_set] = doc.add_accessor(view(uvs, gltf::kArrayBuffer), gltf::kFloat,
                                                    uvs.size(), "VEC2");
        out.indices = doc.add_accessor(view(indices, gltf::kElementArrayBuffer),
                                       gltf::kUnsignedInt, indices.size(), "SCALAR");
        return out;
    }

    Imath::V3d face_normal(const TriangleMesh& mesh, size_t t)
    {
        const Imath::V3d a(mesh.positions[mesh.indices[3 * t]]),
            b(mesh.positions[mesh.indices[3 * t + 1]]), c(mesh.positions[mesh.indices[3 * t + 2]]);
        return (b - a).cross(c - a);
    }

    /// Per-vertex tangents for a normal map whose green channel points along +v of
    /// Patina's uvs (up the image): the uv gradients of position summed over the triangles
    /// around each vertex (Lengyel 2001, "Computing Tangent Space Basis Vectors"),
    /// orthogonalised against the normal; w = ±1 makes glTF's bitangent cross(N, T) w point
    /// up the image, i.e. along −v of glTF's uvs (glTF 2.0 §3.7.2.1).
    std::vector<Imath::V4f> vertex_tangents(const std::vector<Imath::V3f>& positions,
                                            const std::vector<Imath::V3f>& normals,
                                            const std::vector<Imath::V2f>& uvs,
                                            const std::vector<uint32_t>& indices)
    {
        std::vector<Imath::V3d> tangent(positions.size(), Imath::V3d(0.0)),
            up(positions.size(), Imath::V3d(0.0));
        for (size_t t = 0; t + 2 < indices.size(); t += 3) {
            const uint32_t a = indices[t], b = indices[t + 1], c = indices[t + 2];
            const Imath::V3d e1 = Imath::V3d(positions[b]) - Imath::V3d(positions[a]),
                             e2 = Imath::V3d(positions[c]) - Imath::V3d(positions[a]);
            const double du1 = double(uvs[b].x) - uvs[a].x, du2 = double(uvs[c].x) - uvs[a].x;
            // Up the image: glTF's v runs down it.
            const double dv1 = -(double(uvs[b].y) - uvs[a].y), dv2 = -(double(uvs[c].y) - uvs[a].y);
            const double det = du1 * dv2 - du2 * dv1;
            if (det == 0.0)
                continue;
            const Imath::V3d dp_du = (e1 * dv2 - e2 * dv1) / det, dp_dv = (e2 * du1 - e1 * du2) / det;
            for (uint32_t v : {a, b, c}) {
                tangent[v] += dp_du;
                up[v] += dp_dv;
            }
        }
        std::vector<Imath::V4f> out(positions.size());
        for (size_t v = 0; v < positions.size(); ++v) {
            const Imath::V3d n(normals[v]);
            Imath::V3d t = tangent[v] - n * n.dot(tangent[v]);
            if (!(t.length2() > 1e-20)) {
                // No uv gradient here: any direction across the normal.
                t = std::abs(n.x) < 0.9 ? Imath::V3d(1, 0, 0) : Imath::V3d(0, 1, 0);
                t -= n * n.dot(t);
            }
            t.normalize();
            const float w = n.cross(t).dot(up[v]) < 0.0 ? -1.0f : 1.0f;
            out[v] = Imath::V4f(static_cast<float>(t.x), static_cast<float>(t.y),
                                static_cast<float>(t.z), w);
        }
        return out;
    }

}  // namespace

TilePrimitive add_strip_plane(gltf::Document& doc, double width_m, double height_m)
{
    const float x = static_cast<float>(0.5 * width_m), y = static_cast<float>(0.5 * height_m);
    return add_primitive(doc, 0, {{-x, y, 0}, {x, y, 0}, {x, -y, 0}, {-x, -y, 0}},
                         std::vector<Imath::V3f>(4, Imath::V3f(0, 0, 1)),
                         std::vector<Imath::V4f>(4, Imath::V4f(1, 0, 0, 1)),
                         {{0, 0}, {1, 0}, {1, 1}, {0, 1}}, {0, 3, 2, 0, 2, 1});
}

std::vector<TileGeometry> split_by_tile(const TriangleMesh& given, const std::vector<int>& udims,
                                        const std::string& context)
{
    if (!given.has_uvs())
        throw std::runtime_error(fmt::format("{}: the mesh has no uvs", context));
    TriangleMesh normals_source;
    const TriangleMesh* mesh = &given;
    if (!given.has_normals()) {
        normals_source = given;
        compute_vertex_normals(normals_source);
        mesh = &normals_source;
    }

    // One part per tile and source material: part k * materials + m.
    const size_t materials = std::max<size_t>(1, mesh->materials.size());
    std::vector<TileGeometry> tiles(udims.size() * materials);
    // Per part: the mesh's vertex -> the part's.
    std::vector<std::unordered_map<uint32_t, uint32_t>> vertex_of(tiles.size());
    const size_t count = mesh->triangle_count();
    for (size_t t = 0; t < count; ++t) {
        const uint32_t* v = &mesh->indices[3 * t];
        const Imath::V2f a = mesh->uvs[v[0]], b = mesh->uvs[v[1]], c = mesh->uvs[v[2]];
        const double cu = (double(a.x) + b.x + c.x) / 3.0, cv = (double(a.y) + b.y + c.y) / 3.0;
        const double u0 = std::floor(cu), v0 = std::floor(cv);
        const double uv_area = std::abs(double(b.x - a.x) * (c.y - a.y) -
                                        double(b.y - a.y) * (c.x - a.x));
        const int udim = u0 >= 0 && u0 < 10 && v0 >= 0 && v0 < 100
                             ? 1001 + static_cast<int>(u0) + 10 * static_cast<int>(v0)
                             : -1;
        const auto found = std::find(udims.begin(), udims.end(), udim);
        if (found == udims.end()) {
            if (uv_area == 0.0)
                continue;  // no texels: the bakers skipped it too
            throw std::runtime_error(fmt::format(
                "{}: triangle {} has its uv centroid at ({}, {}), {} the stack's UDIM tiles "
                "({}): is this the mesh the stack was grown on?",
                context, t, cu, cv, udim < 0 ? "outside" : fmt::format("on tile {}, not one of", udim),
                fmt::join(udims, ", ")));
        }
        const size_t material = mesh->triangle_material.empty() ? 0 : mesh->triangle_material[t];
        const size_t k = static_cast<size_t>(found - udims.begin()) * materials + material;
        TileGeometry& tile = tiles[k];
        for (int i = 0; i < 3; ++i) {
            const auto [at, added] =
                vertex_of[k].emplace(v[i], static_cast<uint32_t>(tile.positions.size()));
            if (added) {
                tile.positions.push_back(mesh->positions[v[i]]);
                const Imath::V2d uv(mesh->uvs[v[i]]);
                tile.uvs.emplace_back(static_cast<float>(uv.x - u0),
                                      static_cast<float>(v0 + 1.0 - uv.y));
                if (!mesh->source_uvs.empty())  // glTF's v down, as they are, not moved
                    tile.source_uvs.emplace_back(mesh->source_uvs[v[i]].x,
                                                 1.0f - mesh->source_uvs[v[i]].y);
                Imath::V3d n(mesh->normals[v[i]]);
                if (!(n.length2() > 1e-24))
                    n = face_normal(*mesh, t);
                n = n.length2() > 0.0 ? n.normalized() : Imath::V3d(0, 1, 0);
                tile.normals.emplace_back(static_cast<float>(n.x), static_cast<float>(n.y),
                                          static_cast<float>(n.z));
            }
            tile.indices.push_back(at->second);
        }
    }
    std::vector<TileGeometry> out;
    for (size_t k = 0; k < tiles.size(); ++k) {
        TileGeometry& tile = tiles[k];
        if (tile.indices.empty())
            continue;
        tile.tile = k / materials;
        tile.material = k % materials;
        tile.tangents = vertex_tangents(tile.positions, tile.normals, tile.uvs, tile.indices);
        out.push_back(std::move(tile));
    }
    if (out.empty())
        throw std::runtime_error(fmt::format("{}: the mesh has no triangle with uvs", context));
    return out;
}

std::vector<TilePrimitive> add_mesh_primitives(gltf::Document& doc, const TriangleMesh& mesh,
                                               const std::vector<int>& udims,
                                               const std::string& context)
{
    std::vector<TilePrimitive> out;
    for (const TileGeometry& tile : split_by_tile(mesh, udims, context)) {
        out.push_back(add_primitive(doc, tile.tile, tile.positions, tile.normals, tile.tangents,
                                    tile.uvs, tile.indices, tile.source_uvs));
        out.back().material = tile.material;
    }
    return out;
}

double mean_texel_size_m(const TriangleMesh& mesh, int width, const std::string& context)
{
    double uv_area = 0.0;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const Imath::V2d a(mesh.uvs[mesh.indices[3 * t]]), b(mesh.uvs[mesh.indices[3 * t + 1]]),
            c(mesh.uvs[mesh.indices[3 * t + 2]]);
        uv_area += 0.5 * std::abs((b.x - a.x) * (c.y - a.y) - (b.y - a.y) * (c.x - a.x));
    }
    if (!(uv_area > 0.0) || width <= 0)
        throw std::runtime_error(fmt::format("{}: the mesh's uvs cover no area", context));
    return std::sqrt(surface_area(mesh) / uv_area) / width;
}

}  // namespace patina::texgen
