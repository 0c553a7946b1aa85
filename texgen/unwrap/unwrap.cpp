#include "texgen/unwrap/unwrap.h"

#include "core/data_files.h"
#include "core/mesh.h"
#include "core/image_io.h"
#include "core/output_transaction.h"
#include "core/progress.h"
#include "texgen/export/gltf_document.h"
#include "texgen/export/source_material.h"
#include "texgen/texels/mesh_merge.h"
#include "texgen/texels/mesh_topology.h"
#include "texgen/texels/uv_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cstdint>
#include <cstring>
#include <tuple>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>
#include <vector>

#include <sys/wait.h>
#include <unistd.h>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

    /// A private folder under the system's temporary directory, removed with the object.
    class TemporaryFolder {
    public:
        TemporaryFolder()
        {
            std::string name = (fs::temp_directory_path() / "patina-unwrap-XXXXXX").string();
            if (!::mkdtemp(name.data()))
                throw std::runtime_error("unwrap: cannot make a temporary folder in " +
                                         fs::temp_directory_path().string());
            path_ = name;
        }
        ~TemporaryFolder()
        {
            std::error_code ec;
            fs::remove_all(path_, ec);
        }
        TemporaryFolder(const TemporaryFolder&) = delete;
        TemporaryFolder& operator=(const TemporaryFolder&) = delete;
        const fs::path& path() const { return path_; }

    private:
        fs::path path_;
    };

    std::string shell_quoted(const std::string& text)
    {
        std::string out(1, '\'');
        for (char c : text) {
            if (c == '\'')
                out += "'\\''";
            else
                out += c;
        }
        out += '\'';
        return out;
    }

    /// The meshes as a .glb: +Y up metres (glTF's own), one material per name with its base
    /// colour and base colour texture (source_material.h), the artist's uvs (source_uvs) as TEXCOORD_0 and the new set (uvs) after them; the new set
    /// alone as TEXCOORD_0 for meshes that had none. glTF's v runs down the image.
    std::string meshes_as_glb(const std::vector<TriangleMesh>& meshes)
    {
        gltf::Document doc;
        doc.root()["asset"]["generator"] = "patina-texgen unwrap";
        std::map<std::string, int> materials;
        nlohmann::json nodes = nlohmann::json::array();
        for (const TriangleMesh& m : meshes) {
            constexpr float inf = std::numeric_limits<float>::infinity();
            std::vector<float> lo(3, inf), hi(3, -inf);
            for (const Imath::V3f& p : m.positions)
                for (int a = 0; a < 3; ++a) {
                    lo[a] = std::min(lo[a], p[a]);
                    hi[a] = std::max(hi[a], p[a]);
                }
            const auto accessor = [&](const auto& values, int target, int component,
                                      const char* type, const std::vector<float>& min = {},
                                      const std::vector<float>& max = {}) {
                const int view =
                    doc.add_view(values.data(), values.size() * sizeof(values[0]), target);
                return doc.add_accessor(view, component, values.size(), type, min, max);
            };
            const auto gltf_uvs = [&](std::vector<Imath::V2f> uvs) {
                for (Imath::V2f& uv : uvs)
                    uv.y = 1.0f - uv.y;
                return accessor(uvs, gltf::kArrayBuffer, gltf::kFloat, "VEC2");
            };
            nlohmann::json attributes = {{"POSITION", accessor(m.positions, gltf::kArrayBuffer,
                                                               gltf::kFloat, "VEC3", lo, hi)}};
            // Normals as the file has them; none where it has none (a glTF reader then makes
            // flat ones, glTF 2.0 §3.7.2.1).
            if (m.has_normals())
                attributes["NORMAL"] =
                    accessor(m.normals, gltf::kArrayBuffer, gltf::kFloat, "VEC3");
            if (m.source_uvs.empty()) {
                attributes["TEXCOORD_0"] = gltf_uvs(m.uvs);
            } else {
                attributes["TEXCOORD_0"] = gltf_uvs(m.source_uvs);
                attributes["TEXCOORD_1"] = gltf_uvs(m.uvs);
            }
            const std::string material_name = m.material_name.empty() ? "default" : m.material_name;
            auto [found, added] = materials.try_emplace(material_name, 0);
            if (added)
                found->second = add_source_material(doc, material_name, m.base_colour,
                                                    m.base_colour_texture);
            const nlohmann::json primitive = {
                {"attributes", attributes},
                {"indices",
                 accessor(m.indices, gltf::kElementArrayBuffer, gltf::kUnsignedInt, "SCALAR")},
                {"material", found->second}};
            const int mesh = doc.add("meshes", {{"name", m.name}, {"primitives", {primitive}}});
            nodes.push_back(doc.add("nodes", {{"name", m.name}, {"mesh", mesh}}));
        }
        doc.add("scenes", {{"nodes", nodes}});
        return doc.glb();
    }

    template <typename T> void write_raw(const fs::path& file, const std::vector<T>& values)
    {
        std::ofstream out(file, std::ios::binary);
        out.write(reinterpret_cast<const char*>(values.data()),
                  static_cast<std::streamsize>(values.size() * sizeof(T)));
        if (!out)
            throw std::runtime_error("unwrap: cannot write " + file.string());
    }

    /// `mesh` with `corner_uvs` (one per triangle corner) as its uvs, its own uvs kept as
    /// source_uvs: a vertex whose corners got different new uvs (an island's seam) is split.
    TriangleMesh with_new_uvs(const TriangleMesh& mesh, const Imath::V2f* corner_uvs)
    {
        struct Corner {
            uint32_t vertex, u, v, corner;
        };
        std::vector<Corner> corners(mesh.indices.size());
        for (size_t c = 0; c < corners.size(); ++c) {
            uint32_t u = 0, v = 0;
            std::memcpy(&u, &corner_uvs[c].x, 4);
            std::memcpy(&v, &corner_uvs[c].y, 4);
            corners[c] = {mesh.indices[c], u, v, static_cast<uint32_t>(c)};
        }
        std::sort(corners.begin(), corners.end(), [](const Corner& a, const Corner& b) {
            return std::tie(a.vertex, a.u, a.v, a.corner) < std::tie(b.vertex, b.u, b.v, b.corner);
        });
        TriangleMesh out;
        out.name = mesh.name;
        out.material_name = mesh.material_name;
        out.base_colour = mesh.base_colour;
        out.base_colour_texture = mesh.base_colour_texture;
        out.indices.resize(mesh.indices.size());
        for (size_t i = 0; i < corners.size(); ++i) {
            const Corner& c = corners[i];
            if (i == 0 || c.vertex != corners[i - 1].vertex || c.u != corners[i - 1].u ||
                c.v != corners[i - 1].v) {
                out.positions.push_back(mesh.positions[c.vertex]);
                if (mesh.has_normals())
                    out.normals.push_back(mesh.normals[c.vertex]);
                if (mesh.has_uvs())
                    out.source_uvs.push_back(mesh.uvs[c.vertex]);
                out.uvs.push_back(corner_uvs[c.corner]);
            }
            out.indices[c.corner] = static_cast<uint32_t>(out.positions.size() - 1);
        }
        return out;
    }

    /// The last `count` lines of `text`.
    std::string last_lines(const std::string& text, size_t count)
    {
        size_t at = text.size();
        for (size_t n = 0; n <= count && at > 0; ++n)
            at = text.rfind('\n', at - 1);
        return text.substr(at == std::string::npos ? 0 : at + 1);
    }

} // namespace

UnwrapReport unwrap_mesh(const fs::path& input, const MeshConventionOptions& convention,
                         const fs::path& output, const UnwrapOptions& options)
{
    if (options.method != "smart" && options.method != "lightmap")
        throw std::runtime_error(
            fmt::format("unwrap: --method '{}' is not smart or lightmap", options.method));
    if (output.extension() != ".glb")
        throw std::runtime_error(fmt::format("unwrap: the output '{}' must be a .glb (glTF "
                                             "keeps every uv set)",
                                             output.string()));
    const fs::path script = find_data_file("blender/unwrap.py");
    reserve_output(output);

    MeshConventionOptions read_with = convention;
    read_with.uv_set = 0;
    MeshConvention applied;
    const std::vector<TriangleMesh> meshes = load_meshes(input, read_with, &applied);
    for (const std::string& warning : applied.warnings)
        print_warning("patina-texgen", fmt::format("mesh file '{}': {}", input.string(), warning));
    if (const std::string size = implausible_size_warning(bounds_of(meshes), applied);
        !size.empty())
        print_warning("patina-texgen", fmt::format("mesh file '{}': {}", input.string(), size));
    const bool some_uvs = std::any_of(meshes.begin(), meshes.end(),
                                      [](const TriangleMesh& m) { return m.has_uvs(); });
    const bool all_uvs = std::all_of(meshes.begin(), meshes.end(),
                                     [](const TriangleMesh& m) { return m.has_uvs(); });
    if (some_uvs && !all_uvs)
        throw std::runtime_error(fmt::format("unwrap: mesh file '{}': some meshes have uvs and "
                                             "others none (one new uv set cannot follow both)",
                                             input.string()));

    // One surface for Blender: every mesh of the file, welded by position (the artist's uv
    // and normal seams are no edges of the new layout), without triangles that collapse to
    // a line or a point there (Blender would drop them and shift the rest).
    const TriangleMesh all = merge_meshes(meshes, input);
    const std::vector<uint32_t> welded = welded_vertices(all);
    std::vector<uint32_t> compact(all.positions.size(), UINT32_MAX);
    std::vector<float> positions;
    for (size_t v = 0; v < all.positions.size(); ++v)
        if (welded[v] == v) {
            compact[v] = static_cast<uint32_t>(positions.size() / 3);
            positions.insert(positions.end(),
                             {all.positions[v].x, all.positions[v].y, all.positions[v].z});
        }
    std::vector<uint32_t> triangles, sent;
    for (size_t t = 0; t < all.triangle_count(); ++t) {
        const uint32_t a = compact[welded[all.indices[3 * t]]],
                       b = compact[welded[all.indices[3 * t + 1]]],
                       c = compact[welded[all.indices[3 * t + 2]]];
        if (a == b || b == c || a == c)
            continue;
        triangles.insert(triangles.end(), {a, b, c});
        sent.push_back(static_cast<uint32_t>(t));
    }
    if (sent.empty())
        throw std::runtime_error(fmt::format("unwrap: mesh file '{}' has no triangle of three "
                                             "distinct vertices",
                                             input.string()));

    const TemporaryFolder temporary;
    write_raw(temporary.path() / "positions.f32", positions);
    write_raw(temporary.path() / "triangles.u32", triangles);
    const fs::path log = temporary.path() / "blender.log";
    const std::string command = fmt::format(
        "{} -b --factory-startup --python-exit-code 1 --python {} -- {} {} {} {} > {} 2>&1",
        shell_quoted(options.blender), shell_quoted(script.string()),
        shell_quoted(temporary.path().string()), options.method, options.margin,
        options.angle_limit_deg, shell_quoted(log.string()));
    const auto start = std::chrono::steady_clock::now();
    const int status = std::system(command.c_str());
    UnwrapReport report;
    report.blender_seconds =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::stringstream text;
    text << std::ifstream(log).rdbuf();
    const std::string printed = text.str();
    const int code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    if (code == 127)
        throw std::runtime_error(fmt::format("unwrap: Blender ('{}') was not found: install "
                                             "Debian's blender and python3-numpy (apt-get "
                                             "install blender python3-numpy)",
                                             options.blender));
    const fs::path uv_file = temporary.path() / "uvs.f32";
    std::error_code ec;
    if (code != 0 || printed.find("patina-unwrap: done") == std::string::npos ||
        fs::file_size(uv_file, ec) != 6 * sizeof(float) * sent.size())
        throw std::runtime_error(fmt::format("unwrap: Blender failed on '{}' (exit {}): {}",
                                             input.string(), code, last_lines(printed, 4)));
    std::vector<Imath::V2f> sent_uvs(3 * sent.size());
    std::ifstream(uv_file, std::ios::binary)
        .read(reinterpret_cast<char*>(sent_uvs.data()),
              static_cast<std::streamsize>(sent_uvs.size() * sizeof(Imath::V2f)));

    // Back on the file's own vertices: a new uv per triangle corner (a collapsed triangle's
    // corners take (0, 0): it has no area to bake), then each
    // mesh with its vertices split where the new layout has a seam.
    std::vector<Imath::V2f> corner_uvs(all.indices.size(), Imath::V2f(0.0f));
    for (size_t k = 0; k < sent.size(); ++k)
        for (int i = 0; i < 3; ++i)
            corner_uvs[3 * size_t{sent[k]} + i] = sent_uvs[3 * k + i];
    std::vector<TriangleMesh> unwrapped;
    size_t first_corner = 0;
    for (const TriangleMesh& m : meshes) {
        unwrapped.push_back(with_new_uvs(m, corner_uvs.data() + first_corner));
        first_corner += m.indices.size();
    }
    write_file_atomic(output, {meshes_as_glb(unwrapped)}, "glTF binary");
    report.uv_set = all.has_uvs() ? 1 : 0;

    // Measured on the new set as the bakers will see it.
    const TriangleMesh mesh = merge_meshes(unwrapped, output);
    const UvCheck check = check_uvs(mesh, {options.resolution, options.resolution, 2});
    report.triangles = check.triangles;
    report.islands = check.islands;
    const double sub_samples = 4.0 * options.resolution * options.resolution *
                               static_cast<double>(std::max<size_t>(1, check.udims.size()));
    report.utilisation = static_cast<double>(check.covered_sub_samples) / sub_samples;
    report.overlap_fraction = check.overlap_fraction();
    report.density_min_over_mean = check.texel_density_min / check.texel_density_mean;
    report.density_max_over_mean = check.texel_density_max / check.texel_density_mean;
    report.stretch_rms_log2 = check.stretch_rms_log2;
    return report;
}

std::string format_unwrap_report(const UnwrapReport& r)
{
    return fmt::format(
        "uv set           {} (bake with --uv-set {})\n"
        "triangles        {}\n"
        "uv islands       {}\n"
        "utilisation      {:.1f}% of the tile covered\n"
        "overlapping uvs  {:.3g}% of the covered area\n"
        "texel density    min {:.2f}, max {:.2f} of the mean; stretch {:.3f} (RMS of log2 of "
        "density over the mean, area-weighted; 0 = even)\n"
        "blender          {:.2f} s\n",
        r.uv_set, r.uv_set, r.triangles, r.islands, 100.0 * r.utilisation,
        100.0 * r.overlap_fraction, r.density_min_over_mean, r.density_max_over_mean,
        r.stretch_rms_log2, r.blender_seconds);
}

} // namespace patina::texgen
