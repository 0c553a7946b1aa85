#include "texgen/texels/uv_wrap.h"

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <utility>

namespace patina::texgen {

namespace {

    /// Inside the UDIM range rasterize_uv accepts: u in [0, 10), v in [0, 100).
    bool inside_udims(const Imath::V2f& c)
    {
        return c.x >= 0.0f && c.x < 10.0f && c.y >= 0.0f && c.y < 100.0f;
    }

} // namespace

size_t wrap_uvs_outside_udims(TriangleMesh& mesh)
{
    if (!mesh.has_uvs())
        return 0;
    size_t moved = 0;
    // A vertex and the whole-unit shift of its triangle: the copy that triangle uses.
    std::map<std::pair<uint32_t, std::pair<int64_t, int64_t>>, uint32_t> copies;
    const size_t triangles = mesh.triangle_count();
    for (size_t t = 0; t < triangles; ++t) {
        uint32_t* v = &mesh.indices[3 * t];
        const Imath::V2f c = (mesh.uvs[v[0]] + mesh.uvs[v[1]] + mesh.uvs[v[2]]) / 3.0f;
        if (inside_udims(c) || !std::isfinite(c.x) || !std::isfinite(c.y))
            continue;
        const double su = std::floor(static_cast<double>(c.x));
        const double sv = std::floor(static_cast<double>(c.y));
        if (std::abs(su) > 1e9 || std::abs(sv) > 1e9)
            throw std::runtime_error(
                "--uv-wrap: a triangle's uvs are more than 1e9 tiles away from the unit tile");
        const std::pair<int64_t, int64_t> shift{static_cast<int64_t>(su), static_cast<int64_t>(sv)};
        for (int k = 0; k < 3; ++k) {
            const auto [it, added] = copies.try_emplace({v[k], shift}, 0u);
            if (added) {
                if (mesh.positions.size() >= std::numeric_limits<uint32_t>::max())
                    throw std::runtime_error("--uv-wrap: too many vertices for 32-bit indices");
                it->second = static_cast<uint32_t>(mesh.positions.size());
                mesh.positions.push_back(mesh.positions[v[k]]);
                if (mesh.has_normals())
                    mesh.normals.push_back(mesh.normals[v[k]]);
                if (!mesh.source_uvs.empty())
                    mesh.source_uvs.push_back(mesh.source_uvs[v[k]]);
                const Imath::V2f uv = mesh.uvs[v[k]];
                mesh.uvs.emplace_back(static_cast<float>(uv.x - su), static_cast<float>(uv.y - sv));
            }
            v[k] = it->second;
        }
        ++moved;
    }
    return moved;
}

} // namespace patina::texgen
