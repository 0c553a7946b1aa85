#include "texgen/export/export_patina.h"

#include "formats/texture_stack.h"
#include "texgen/export/gltf_document.h"
#include "texgen/export/png_encode.h"
#include "texgen/export/presets.h"
#include "core/image_io.h"
#include "texgen/flatten/flatten_stack.h"
#include "texgen/flatten/patina_stack_files.h"

#include "core/cancel.h"
#include "core/output_transaction.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

    /// The largest UDIM tile a glTF export takes: the ten columns of the first 10 rows.
    constexpr int kMaxUdim = 1099;

    struct Step {
        double time_years = 0.0;
        std::string label;  ///< "t30": the step's folder, or "stack" for a lone stack
        PatinaStackFiles stack;
        FlattenedStack flat;  ///< for the gltf preset, its maps are dropped once encoded
        std::vector<std::pair<std::string, std::vector<unsigned char>>> pngs;  ///< gltf: $map, PNG
    };

    std::string expand(std::string pattern, const std::string& mesh, const std::string& material,
                       const std::string& map, int udim, bool tiled)
    {
        auto replace = [&](const std::string& key, const std::string& value) {
            for (size_t at; (at = pattern.find(key)) != std::string::npos;)
                pattern.replace(at, key.size(), value);
        };
        replace("$udim", std::to_string(udim));
        replace("$mesh", mesh);
        replace("$material", material);
        replace("$map", map);
        if (tiled && pattern.find(std::to_string(udim)) == std::string::npos)
            pattern += "." + std::to_string(udim);
        return pattern + ".png";
    }

    /// The steps of `input`: every step of a series, or the one stack.
    std::vector<Step> read_steps(const fs::path& input)
    {
        std::vector<Step> steps;
        std::error_code ec;
        if (fs::is_directory(input, ec) && !fs::exists(input / formats::kStackManifest, ec) &&
            fs::exists(input / formats::kSeriesManifest, ec)) {
            const formats::StackSeries series = formats::read_stack_series(input);
            for (const formats::SeriesStep& s : series.steps) {
                Step step;
                step.time_years = s.time_years;
                step.label = s.folder;
                step.stack = read_patina_stack(series.folder() / s.folder);
                steps.push_back(std::move(step));
            }
        } else {
            Step step;
            step.stack = read_patina_stack(input);
            step.time_years = step.stack.time_years;
            step.label = step.stack.manifest.parent_path().filename().string();
            if (step.label.empty())
                step.label = "stack";
            steps.push_back(std::move(step));
        }
        return steps;
    }

    /// The strip as a plane of its real size, facing +Z (glTF's front), uv (0, 0) at the
    /// top-left corner of the maps (glTF's uv origin is the image's first row).
    int strip_mesh_data(gltf::Document& doc, double width_m, double height_m, json* attributes)
    {
        const float x = static_cast<float>(0.5 * width_m), y = static_cast<float>(0.5 * height_m);
        const float positions[] = {-x, y, 0, x, y, 0, x, -y, 0, -x, -y, 0};
        const float normals[] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
        const float tangents[] = {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1};
        const float uvs[] = {0, 0, 1, 0, 1, 1, 0, 1};
        const uint32_t indices[] = {0, 3, 2, 0, 2, 1};
        const int p = doc.add_accessor(doc.add_view(positions, sizeof positions, gltf::kArrayBuffer),
                                       gltf::kFloat, 4, "VEC3", {-x, -y, 0}, {x, y, 0});
        const int n = doc.add_accessor(doc.add_view(normals, sizeof normals, gltf::kArrayBuffer),
                                       gltf::kFloat, 4, "VEC3");
        const int t = doc.add_accessor(doc.add_view(tangents, sizeof tangents, gltf::kArrayBuffer),
                                       gltf::kFloat, 4, "VEC4");
        const int uv = doc.add_accessor(doc.add_view(uvs, sizeof uvs, gltf::kArrayBuffer),
                                        gltf::kFloat, 4, "VEC2");
        *attributes = {{"POSITION", p}, {"NORMAL", n}, {"TANGENT", t}, {"TEXCOORD_0", uv}};
        return doc.add_accessor(doc.add_view(indices, sizeof indices, gltf::kElementArrayBuffer),
                                gltf::kUnsignedInt, 6, "SCALAR");
    }

    /// The PNG files of `maps`, encoded in parallel (each at max(bits, its min_bits)).
    std::vector<std::vector<unsigned char>> encode_all(const std::vector<PresetMap>& maps,
                                                       int width, int height, int bits)
    {
        std::vector<std::vector<unsigned char>> pngs(maps.size());
        tbb::parallel_for(size_t(0), maps.size(), [&](size_t i) {
            pngs[i] = encode_png(maps[i].texels.data(), width, height,
                                 static_cast<int>(maps[i].channels.size()),
                                 std::max(bits, maps[i].min_bits));
        });
        return pngs;
    }

    /// The largest height of every step (µm): the range of the height maps.
    double height_range_um(const std::vector<Step>& steps)
    {
        double top = 0.0;
        for (const Step& step : steps)
            for (const FlatMap& map : step.flat.maps)
                if (map.name == "height")
                    for (const std::vector<float>& tile : map.tiles)
                        for (float h : tile)
                            top = std::max(top, static_cast<double>(h));
        return top;
    }

    /// The texture presets: every map of every step as a file of `dir`.
    std::vector<fs::path> write_textures(const fs::path& dir, const std::vector<Step>& steps,
                                         const ExportOptions& options, const ColorManager& colors)
    {
        const double range = height_range_um(steps);
        std::vector<fs::path> written;
        const std::string mesh = dir.filename().string();
        for (const Step& step : steps) {
            const FlattenedStack& flat = step.flat;
            for (size_t tile = 0; tile < flat.udims.size(); ++tile) {
                throw_if_cancelled();
                const std::vector<PresetMap> maps =
                    preset_maps(options.preset, flat, tile, range, colors);
                const bool exr = options.bits == 32 || options.preset == "exr";
                const std::vector<std::vector<unsigned char>> pngs =
                    exr ? std::vector<std::vector<unsigned char>>()
                        : encode_all(maps, flat.width, flat.height, options.bits);
                for (size_t m = 0; m < maps.size(); ++m) {
                    const PresetMap& map = maps[m];
                    std::string name = expand(options.name_template, mesh, step.label, map.name,
                                              flat.udims[tile], flat.udims.size() > 1);
                    const int channels = static_cast<int>(map.channels.size());
                    if (exr) {
                        name.replace(name.size() - 4, 4, ".exr");
                        const Metadata meta = {
                            {"patina:map", map.name},
                            {"patina:preset", options.preset},
                            {"patina:time_years", static_cast<float>(step.time_years)},
                            {"oiio:ColorSpace",
                             std::string(map.name == "base_color" ? "lin_rec709" : "raw")}};
                        write_image_atomic(dir / name, map.texels.data(), flat.width,
                                           flat.height, channels, map.channels,
                                           options.bits == 16 ? OIIO::TypeDesc::HALF
                                                              : OIIO::TypeDesc::FLOAT,
                                           meta);
                    } else {
                        write_file_atomic(dir / name,
                                          {std::string_view(reinterpret_cast<const char*>(pngs[m].data()),
                                                            pngs[m].size())},
                                          "texture");
                    }
                    written.push_back(dir / name);
                }
            }
        }
        return written;
    }

}  // namespace

std::string relative_to(const fs::path& file, const fs::path& dir)
{
    std::error_code ec;
    const fs::path rel = fs::relative(file, dir.empty() ? fs::path(".") : dir, ec);
    return (ec || rel.empty() ? file : rel).generic_string();
}

std::string age_name(double years)
{
    return fmt::format("{} y", years);
}

ExportResult export_patina(const fs::path& input, const fs::path& output,
                           const ExportOptions& given, const MaterialLibrary& library,
                           const ColorManager& colors)
{
    ExportOptions options = given;
    if (options.bits == 0)
        options.bits = options.preset == "exr" ? 32 : 8;
    check_preset(options.preset);
    const bool textures = preset_writes_textures(options.preset);
    if (textures ? !(options.bits == 8 || options.bits == 16 || options.bits == 32)
                 : options.bits != 8)
        throw std::runtime_error(fmt::format(
            "--bits {}: the {} preset takes {}", options.bits, options.preset,
            textures ? "8 or 16 (PNG) or 32 (float EXR)" : "8 (glTF's PNG maps)"));
    if (options.preset == "exr" && options.bits == 8)
        throw std::runtime_error("--bits 8: the exr preset writes 16 (half) or 32 (float) EXRs");
    const std::string extension = output.extension().string();
    if (!textures && extension != (options.separate ? ".gltf" : ".glb"))
        throw std::runtime_error(fmt::format(
            "-o '{}': a {} file (the extension is {})", output.string(),
            options.separate ? "glTF (--separate)" : "binary glTF", options.separate ? ".gltf" : ".glb"));
    if (textures && (extension == ".glb" || extension == ".gltf"))
        throw std::runtime_error(fmt::format(
            "-o '{}': the {} preset writes a folder of textures, not a glTF file",
            output.string(), options.preset));

    // Every step read and flattened before anything is written.
    std::vector<Step> steps = read_steps(input);
    FlattenOptions flatten;
    flatten.resolution = options.resolution;
    flatten.normal_scale = options.normal_scale;
    flatten.only = {"gltf_base_color", "gltf_metallic_roughness", "gltf_clearcoat", "normal",
                    "height"};
    // Each step flattened (and, for glTF, encoded) in parallel with the others; the first
    // failure in step order is reported, whatever the threads' order.
    std::vector<std::exception_ptr> failures(steps.size());
    tbb::parallel_for(size_t(0), steps.size(), [&](size_t k) {
        Step& step = steps[k];
        try {
            throw_if_cancelled();
            if (!(step.stack.strip_size_m > 0.0))
                throw std::runtime_error(fmt::format(
                    "export of '{}': the stack was made on a mesh; export takes strips "
                    "(flatten the stack and wire its maps to the mesh)",
                    step.stack.manifest.string()));
            step.flat = flatten_stack(
                step.stack, resolve_stack_materials(step.stack, library, colors), flatten);
            check_finite_maps(step.flat, step.stack.manifest, "export");
            if (!textures && step.flat.udims.size() == 1) {
                const std::vector<PresetMap> maps = preset_maps("gltf", step.flat, 0, 0.0, colors);
                std::vector<std::vector<unsigned char>> pngs =
                    encode_all(maps, step.flat.width, step.flat.height, 8);
                for (size_t m = 0; m < maps.size(); ++m)
                    step.pngs.emplace_back(maps[m].name, std::move(pngs[m]));
                step.flat.maps.clear();  // encoded: the memory goes back
            }
        } catch (...) {
            failures[k] = std::current_exception();
        }
    });
    for (const std::exception_ptr& failure : failures)
        if (failure)
            std::rethrow_exception(failure);
    for (Step& step : steps) {
        const Step& first = steps.front();
        if (step.flat.width != first.flat.width || step.flat.height != first.flat.height ||
            step.flat.udims != first.flat.udims || step.stack.strip_size_m != first.stack.strip_size_m)
            throw std::runtime_error(fmt::format(
                "export of '{}': the steps disagree: {} is {}x{} texels on {} tile(s) of {} m, "
                "{} is {}x{} on {} of {} m",
                input.string(), first.label, first.flat.width, first.flat.height,
                first.flat.udims.size(), first.stack.strip_size_m, step.label, step.flat.width,
                step.flat.height, step.flat.udims.size(), step.stack.strip_size_m));
        for (int udim : step.flat.udims)
            if (udim > kMaxUdim)
                throw std::runtime_error(fmt::format(
                    "export of '{}': UDIM tile {} is beyond {}; glTF has no UDIM, and export "
                    "makes one material per tile of the first ten rows",
                    step.stack.manifest.string(), udim, kMaxUdim));
    }
    const int width = steps.front().flat.width, height = steps.front().flat.height;
    const std::vector<int>& udims = steps.front().flat.udims;
    if (udims.size() != 1)
        throw std::runtime_error(fmt::format("export of '{}': a strip has one tile, not {}",
                                             input.string(), udims.size()));

    ExportResult result;
    result.steps = steps.size();
    result.width = width;
    result.height = height;
    if (textures) {
        result.files = write_textures(output, steps, options, colors);
        result.textures = result.files.size();
        return result;
    }

    gltf::Document doc;
    doc.use_extension("KHR_materials_clearcoat");
    const std::string mesh_name = output.stem().string();
    const int sampler = doc.add_sampler(gltf::kClampToEdge);

    // One texture per map and step, identical ones shared (a clearcoat of zeros).
    std::map<std::string, int> textures_by_bytes;  // the PNG's bytes -> its texture
    size_t texture_count = 0;
    auto texture = [&](const Step& step, const std::string& map, std::vector<unsigned char> png) {
        std::string key(png.begin(), png.end());
        const auto found = textures_by_bytes.find(key);
        if (found != textures_by_bytes.end())
            return found->second;
        const std::string name = fmt::format("{} {}", step.label, map);
        const std::string file =
            expand(options.name_template, mesh_name, step.label, map, udims[0], false);
        const int image = doc.add_png(name, file, png);
        const int t = doc.add_texture(image, sampler);
        textures_by_bytes.emplace(std::move(key), t);
        ++texture_count;
        return t;
    };

    std::vector<int> materials;
    for (const Step& step : steps) {
        throw_if_cancelled();
        // The gltf preset: base colour sRGB-encoded, as glTF's baseColorTexture is; the
        // data maps linear.
        std::map<std::string, int> tex;
        for (const auto& [map, png] : step.pngs)
            tex[map] = texture(step, map, png);
        const int base_tex = tex.at("base_color"), mr_tex = tex.at("metallic_roughness"),
                  normal_tex = tex.at("normal"), coat_tex = tex.at("clearcoat");
        json material = {
            {"name", fmt::format("{} {}", mesh_name, age_name(step.time_years))},
            {"pbrMetallicRoughness",
             {{"baseColorTexture", {{"index", base_tex}}},
              {"metallicRoughnessTexture", {{"index", mr_tex}}}}},
            {"normalTexture", {{"index", normal_tex}}},
            {"extensions",
             {{"KHR_materials_clearcoat",
               {{"clearcoatFactor", 1.0},
                {"clearcoatTexture", {{"index", coat_tex}}},
                {"clearcoatRoughnessFactor", 1.0},
                {"clearcoatRoughnessTexture", {{"index", coat_tex}}}}}}},
            {"extras",
             {{"patina",
               {{"time_years", step.time_years},
                {"stack", relative_to(step.stack.manifest, output.parent_path())}}}}}};
        materials.push_back(doc.add("materials", std::move(material)));
    }

    json attributes;
    const int indices = strip_mesh_data(doc, steps.front().stack.strip_size_m,
                                        steps.front().stack.strip_size_m * height / width,
                                        &attributes);
    // The default material is the last step (the age the script describes).
    json primitive = {{"attributes", attributes}, {"indices", indices},
                      {"material", materials.back()}};
    if (steps.size() > 1) {
        doc.use_extension("KHR_materials_variants");
        json variants = json::array(), mappings = json::array();
        for (size_t k = 0; k < steps.size(); ++k) {
            variants.push_back({{"name", age_name(steps[k].time_years)}});
            mappings.push_back({{"material", materials[k]}, {"variants", {k}}});
        }
        doc.root()["extensions"]["KHR_materials_variants"] = {{"variants", variants}};
        primitive["extensions"]["KHR_materials_variants"] = {{"mappings", mappings}};
    }
    const int mesh = doc.add("meshes", {{"name", mesh_name}, {"primitives", {primitive}}});
    const int node = doc.add("nodes", {{"name", mesh_name}, {"mesh", mesh}});
    doc.add("scenes", {{"nodes", {node}}});

    result.textures = texture_count;
    throw_if_cancelled();
    if (options.separate)
        result.files = doc.write_gltf(output);
    else {
        doc.write_glb(output);
        result.files = {output};
    }
    return result;
}

}  // namespace patina::texgen
