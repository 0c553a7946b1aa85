#include "texgen/stack/ply_writer.h"

#include "core/image_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <bit>
#include <climits>
#include <cstring>
#include <fstream>
#include <set>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;

std::string sanitize_ply_name(std::string_view name)
{
    std::string out(name);
    for (char& c : out) {
        const bool ok =
            (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_';
        if (!ok)
            c = '_';
    }
    return out.empty() ? std::string("_") : out;
}

namespace {

    /// Little-endian bytes whatever the host's byte order.
    template <class T> void append_le(std::string& out, T value)
    {
        static_assert(sizeof(T) == 1 || sizeof(T) == 4);
        char bytes[sizeof(T)];
        std::memcpy(bytes, &value, sizeof(T));
        if constexpr (std::endian::native == std::endian::big)
            std::reverse(bytes, bytes + sizeof(T));
        out.append(bytes, sizeof(T));
    }

    std::string one_line(std::string text)
    {
        std::replace(text.begin(), text.end(), '\n', ' ');
        std::replace(text.begin(), text.end(), '\r', ' ');
        return text;
    }

}  // namespace

void write_ply_with_vertex_values(const fs::path& path, const TriangleMesh& mesh,
                                  const std::vector<std::string>& property_names,
                                  const std::vector<float>& values,
                                  const std::vector<std::string>& comments)
{
    validate_mesh(mesh, fmt::format("cannot write PLY '{}'", path.string()));
    const size_t nv = mesh.positions.size();
    const size_t np = property_names.size();
    if (values.size() != nv * np)
        throw std::runtime_error(
            fmt::format("cannot write PLY '{}': {} values for {} vertices x {} properties",
                        path.string(), values.size(), nv, np));
    if (nv > static_cast<size_t>(INT_MAX))
        throw std::runtime_error(fmt::format(
            "cannot write PLY '{}': {} vertices do not fit int indices", path.string(), nv));

    // The names PLY readers give a meaning to come first; ours must not shadow them.
    std::vector<std::string> fixed = {"x", "y", "z"};
    if (mesh.has_normals())
        fixed.insert(fixed.end(), {"nx", "ny", "nz"});
    if (mesh.has_uvs())
        fixed.insert(fixed.end(), {"u", "v"});
    std::set<std::string> used(fixed.begin(), fixed.end());
    for (const std::string& name : property_names) {
        if (name.empty() || sanitize_ply_name(name) != name)
            throw std::runtime_error(fmt::format(
                "cannot write PLY '{}': vertex property name '{}' must be made of A-Z a-z 0-9 _",
                path.string(), name));
        if (!used.insert(name).second)
            throw std::runtime_error(fmt::format(
                "cannot write PLY '{}': vertex property '{}' appears twice", path.string(), name));
    }

    std::string header = "ply\nformat binary_little_endian 1.0\n";
    for (const std::string& c : comments)
        header += "comment " + one_line(c) + "\n";
    header += fmt::format("element vertex {}\n", nv);
    for (const std::string& name : fixed)
        header += "property float " + name + "\n";
    for (const std::string& name : property_names)
        header += "property float " + name + "\n";
    header += fmt::format("element face {}\n", mesh.triangle_count());
    header += "property list uchar int vertex_indices\nend_header\n";

    std::string body;
    body.reserve(nv * (fixed.size() + np) * 4 + mesh.triangle_count() * 13);
    for (size_t v = 0; v < nv; ++v) {
        const Imath::V3f& p = mesh.positions[v];
        append_le(body, p.x);
        append_le(body, p.y);
        append_le(body, p.z);
        if (mesh.has_normals()) {
            const Imath::V3f& n = mesh.normals[v];
            append_le(body, n.x);
            append_le(body, n.y);
            append_le(body, n.z);
        }
        if (mesh.has_uvs()) {
            append_le(body, mesh.uvs[v].x);
            append_le(body, mesh.uvs[v].y);
        }
        for (size_t k = 0; k < np; ++k)
            append_le(body, values[v * np + k]);
    }
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        append_le(body, static_cast<uint8_t>(3));
        for (int k = 0; k < 3; ++k)
            append_le(body, static_cast<int32_t>(mesh.indices[3 * t + static_cast<size_t>(k)]));
    }

    // Temporary name + rename: an interrupted write never leaves half a PLY.
    write_file_atomic(path, {header, body}, "PLY");
}

}  // namespace patina::texgen
