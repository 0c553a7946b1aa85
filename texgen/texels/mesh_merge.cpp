#include "texgen/texels/mesh_merge.h"

#include <fmt/format.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <stdexcept>

namespace patina::texgen {

TriangleMesh merge_meshes(const std::vector<TriangleMesh>& meshes,
                          const std::filesystem::path& file)
{
    if (meshes.empty())
        throw std::runtime_error(fmt::format("mesh file '{}' contains no meshes", file.string()));
    const TriangleMesh* with_uvs = nullptr;
    const TriangleMesh* without_uvs = nullptr;
    bool any_normals = false;
    size_t vertex_count = 0, index_count = 0;
    for (const TriangleMesh& m : meshes) {
        (m.has_uvs() ? with_uvs : without_uvs) = &m;
        any_normals = any_normals || m.has_normals();
        vertex_count += m.positions.size();
        index_count += m.indices.size();
    }
    if (with_uvs && without_uvs)
        throw std::runtime_error(fmt::format(
            "mesh file '{}': mesh '{}' has uvs but mesh '{}' has none; give every mesh uvs, or "
            "bake per vertex with --per-vertex out.ply",
            file.string(), with_uvs->name, without_uvs->name));
    if (vertex_count > std::numeric_limits<uint32_t>::max())
        throw std::runtime_error(fmt::format("mesh file '{}': {} vertices are more than 32-bit "
                                             "indices can address", file.string(), vertex_count));

    TriangleMesh merged;
    merged.name = meshes.size() == 1 ? meshes.front().name : file.stem().string();
    merged.material_name = meshes.front().material_name;
    merged.uv_set = meshes.front().uv_set;
    merged.uv_set_count = meshes.front().uv_set_count;
    for (const TriangleMesh& m : meshes)
        merged.uv_set_count = std::min(merged.uv_set_count, m.uv_set_count);
    merged.positions.reserve(vertex_count);
    merged.indices.reserve(index_count);
    if (any_normals)
        merged.normals.reserve(vertex_count);
    if (with_uvs)
        merged.uvs.reserve(vertex_count);
    // The artist's own uv set travels along when every mesh has it (--uv-set > 0).
    const bool sources = std::all_of(meshes.begin(), meshes.end(),
                                     [](const TriangleMesh& m) { return !m.source_uvs.empty(); });
    merged.triangle_material.reserve(index_count / 3);
    merged.base_colour = meshes.front().base_colour;
    merged.base_colour_texture = meshes.front().base_colour_texture;
    const auto material_index = [&](const std::string& name, const Imath::V4f& colour,
                                    const MaterialTexture& texture) {
        auto it = std::find(merged.materials.begin(), merged.materials.end(), name);
        if (it != merged.materials.end())
            return static_cast<uint16_t>(it - merged.materials.begin());
        if (merged.materials.size() > UINT16_MAX)
            throw std::runtime_error(fmt::format("mesh file '{}': more than {} materials",
                                                 file.string(), UINT16_MAX + 1));
        merged.materials.push_back(name);
        merged.material_base_colours.push_back(colour);
        merged.material_base_textures.push_back(texture);
        return static_cast<uint16_t>(merged.materials.size() - 1);
    };
    for (const TriangleMesh& m : meshes) {
        if (m.triangle_material.empty()) {
            merged.triangle_material.insert(
                merged.triangle_material.end(), m.triangle_count(),
                material_index(m.material_name, m.base_colour, m.base_colour_texture));
        } else {
            for (const uint16_t k : m.triangle_material)
                merged.triangle_material.push_back(material_index(
                    m.materials[k], m.material_base_colours[k], m.material_base_textures[k]));
        }
        const uint32_t base = static_cast<uint32_t>(merged.positions.size());
        merged.positions.insert(merged.positions.end(), m.positions.begin(), m.positions.end());
        merged.uvs.insert(merged.uvs.end(), m.uvs.begin(), m.uvs.end());
        if (sources)
            merged.source_uvs.insert(merged.source_uvs.end(), m.source_uvs.begin(),
                                     m.source_uvs.end());
        if (any_normals) {
            if (m.has_normals()) {
                merged.normals.insert(merged.normals.end(), m.normals.begin(), m.normals.end());
            } else {
                TriangleMesh smooth = m;
                compute_vertex_normals(smooth);
                merged.normals.insert(merged.normals.end(), smooth.normals.begin(),
                                      smooth.normals.end());
            }
        }
        for (uint32_t i : m.indices)
            merged.indices.push_back(base + i);
    }
    validate_mesh(merged, fmt::format("mesh file '{}'", file.string()));
    return merged;
}

TriangleMesh load_merged_mesh(const std::filesystem::path& file,
                              const MeshConventionOptions& convention, MeshConvention* applied)
{
    return merge_meshes(load_meshes(file, convention, applied), file);
}

}  // namespace patina::texgen
