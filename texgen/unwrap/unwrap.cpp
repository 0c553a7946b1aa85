#include "texgen/unwrap/unwrap.h"

#include "core/data_files.h"
#include "core/mesh.h"
#include "core/output_transaction.h"
#include "core/progress.h"
#include "texgen/export/gltf_document.h"
#include "texgen/texels/mesh_merge.h"
#include "texgen/texels/uv_check.h"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
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

    /// The meshes as a .glb Blender's importer reads as they are: +Y up metres (glTF's own),
    /// the artist's uvs as TEXCOORD_0 (glTF's v down), one material per name.
    std::string meshes_as_glb(std::vector<TriangleMesh> meshes)
    {
        gltf::Document doc;
        doc.root()["asset"]["generator"] = "patina-texgen unwrap";
        std::map<std::string, int> materials;
        nlohmann::json nodes = nlohmann::json::array();
        for (TriangleMesh& m : meshes) {
            // Normals as the file has them; none where it has none (a glTF reader then makes
            // flat ones, glTF 2.0 §3.7.2.1), not smoothed over the corners of a faceted shape.
            for (Imath::V3f& n : m.normals)
                if (!(n.length2() > 0.0f))
                    n = Imath::V3f(0, 1, 0);  // a vertex of degenerate triangles only
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
            nlohmann::json attributes = {
                {"POSITION", accessor(m.positions, gltf::kArrayBuffer, gltf::kFloat, "VEC3", lo, hi)}};
            if (m.has_normals())
                attributes["NORMAL"] = accessor(m.normals, gltf::kArrayBuffer, gltf::kFloat, "VEC3");
            if (m.has_uvs()) {
                std::vector<Imath::V2f> uvs = m.uvs;
                for (Imath::V2f& uv : uvs)
                    uv.y = 1.0f - uv.y;
                attributes["TEXCOORD_0"] = accessor(uvs, gltf::kArrayBuffer, gltf::kFloat, "VEC2");
            }
            const std::string material_name = m.material_name.empty() ? "default" : m.material_name;
            auto [found, added] = materials.try_emplace(material_name, 0);
            if (added)
                found->second = doc.add("materials", {{"name", material_name}});
            const nlohmann::json primitive = {
                {"attributes", attributes},
                {"indices", accessor(m.indices, gltf::kElementArrayBuffer, gltf::kUnsignedInt,
                                     "SCALAR")},
                {"material", found->second}};
            const int mesh = doc.add("meshes", {{"name", m.name}, {"primitives", {primitive}}});
            nodes.push_back(doc.add("nodes", {{"name", m.name}, {"mesh", mesh}}));
        }
        doc.add("scenes", {{"nodes", nodes}});
        return doc.glb();
    }

    /// The last `count` lines of `text`.
    std::string last_lines(const std::string& text, size_t count)
    {
        size_t at = text.size();
        for (size_t n = 0; n <= count && at > 0; ++n)
            at = text.rfind('\n', at - 1);
        return text.substr(at == std::string::npos ? 0 : at + 1);
    }

}  // namespace

UnwrapReport unwrap_mesh(const fs::path& input, const MeshConventionOptions& convention,
                         const fs::path& output, const UnwrapOptions& options)
{
    if (options.method != "smart" && options.method != "lightmap")
        throw std::runtime_error(fmt::format("unwrap: --method '{}' is not smart or lightmap",
                                             options.method));
    if (output.extension() != ".glb")
        throw std::runtime_error(fmt::format("unwrap: the output '{}' must be a .glb (glTF "
                                             "keeps every uv set)", output.string()));
    const fs::path script = find_data_file("blender/unwrap.py");
    reserve_output(output);

    MeshConventionOptions read_with = convention;
    read_with.uv_set = 0;
    MeshConvention applied;
    const std::vector<TriangleMesh> meshes = load_meshes(input, read_with, &applied);
    for (const std::string& warning : applied.warnings)
        print_warning("patina-texgen", fmt::format("mesh file '{}': {}", input.string(), warning));
    if (const std::string size = implausible_size_warning(bounds_of(meshes), applied); !size.empty())
        print_warning("patina-texgen", fmt::format("mesh file '{}': {}", input.string(), size));
    const bool some_uvs = std::any_of(meshes.begin(), meshes.end(),
                                      [](const TriangleMesh& m) { return m.has_uvs(); });
    const bool all_uvs = std::all_of(meshes.begin(), meshes.end(),
                                     [](const TriangleMesh& m) { return m.has_uvs(); });
    if (some_uvs && !all_uvs)
        throw std::runtime_error(fmt::format("unwrap: mesh file '{}': some meshes have uvs and "
                                             "others none (one new uv set cannot follow both)",
                                             input.string()));

    const TemporaryFolder temporary;
    const fs::path given = temporary.path() / "input.glb";
    std::ofstream(given, std::ios::binary) << meshes_as_glb(meshes);
    StagedOutput staged(output);
    const fs::path log = temporary.path() / "blender.log";
    const std::string command = fmt::format(
        "{} -b --factory-startup --python-exit-code 1 --python {} -- {} {} {} {} {} > {} 2>&1",
        shell_quoted(options.blender), shell_quoted(script.string()), shell_quoted(given.string()),
        shell_quoted(staged.path().string()), options.method, options.margin,
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
                                             "install blender python3-numpy)", options.blender));
    const size_t said = printed.rfind("patina-unwrap: uv set ");
    if (code != 0 || said == std::string::npos || !fs::is_regular_file(staged.path()))
        throw std::runtime_error(fmt::format("unwrap: Blender failed on '{}' (exit {}): {}",
                                             input.string(), code, last_lines(printed, 4)));
    report.uv_set = std::stoi(printed.substr(said + 22));

    // Measured on what Blender wrote, as the bakers will read it.
    MeshConventionOptions baked;
    baked.uv_set = report.uv_set;
    const TriangleMesh mesh = merge_meshes(load_meshes(staged.path(), baked), output);
    const UvCheck check = check_uvs(mesh, {options.resolution, options.resolution, 2});
    report.triangles = check.triangles;
    report.islands = check.islands;
    const double sub_samples = 4.0 * options.resolution * options.resolution *
                               std::max<size_t>(1, check.udims.size());
    report.utilisation = check.covered_sub_samples / sub_samples;
    report.overlap_fraction = check.overlap_fraction();
    report.density_min_over_mean = check.texel_density_min / check.texel_density_mean;
    report.density_max_over_mean = check.texel_density_max / check.texel_density_mean;
    double weighted = 0.0, area = 0.0;
    for (size_t t = 0; t < mesh.triangle_count(); ++t) {
        const uint32_t* v = &mesh.indices[3 * t];
        const Imath::V2d e1 = Imath::V2d(mesh.uvs[v[1]]) - Imath::V2d(mesh.uvs[v[0]]);
        const Imath::V2d e2 = Imath::V2d(mesh.uvs[v[2]]) - Imath::V2d(mesh.uvs[v[0]]);
        const double uv_area = 0.5 * std::abs(e1.x * e2.y - e1.y * e2.x);
        const Imath::V3d p0(mesh.positions[v[0]]);
        const double surface = 0.5 * (Imath::V3d(mesh.positions[v[1]]) - p0)
                                         .cross(Imath::V3d(mesh.positions[v[2]]) - p0)
                                         .length();
        if (!(uv_area > 0.0 && surface > 0.0))
            continue;
        const double density = uv_area * options.resolution * options.resolution / surface;
        const double l = std::log2(density / check.texel_density_mean);
        weighted += surface * l * l;
        area += surface;
    }
    report.stretch_rms_log2 = area > 0.0 ? std::sqrt(weighted / area) : 0.0;
    staged.done();
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

}  // namespace patina::texgen
