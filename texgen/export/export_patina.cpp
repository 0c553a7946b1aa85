#include "texgen/export/export_patina.h"

#include "formats/texture_stack.h"
#include "texgen/export/gltf_document.h"
#include "texgen/export/png_encode.h"
#include "texgen/flatten/flatten_stack.h"
#include "texgen/flatten/patina_stack_files.h"

#include "core/cancel.h"
#include "core/output_transaction.h"

#include <fmt/format.h>

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
        FlattenedStack flat;
    };

    const FlatMap& map_of(const FlattenedStack& flat, const std::string& name)
    {
        for (const FlatMap& m : flat.maps)
            if (m.name == name)
                return m;
        throw std::logic_error("flatten made no map '" + name + "'");
    }

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

    /// The texels of one map and tile, NaN refused with the stack and texel named.
    std::vector<float> checked(const FlatMap& map, size_t tile, const Step& step, int width)
    {
        const std::vector<float>& v = map.tiles[tile];
        for (size_t i = 0; i < v.size(); ++i)
            if (!std::isfinite(v[i])) {
                const size_t texel = i / map.channels.size();
                throw std::runtime_error(fmt::format(
                    "export of '{}': map '{}' texel ({}, {}) is not finite; nothing was written",
                    step.stack.manifest.string(), map.name, texel % width, texel / width));
            }
        return v;
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
                           const ExportOptions& options, const MaterialLibrary& library,
                           const ColorManager& colors)
{
    if (options.preset != "gltf")
        throw std::runtime_error(fmt::format("--preset '{}': expected gltf", options.preset));
    const std::string extension = output.extension().string();
    if (extension != (options.separate ? ".gltf" : ".glb"))
        throw std::runtime_error(fmt::format(
            "-o '{}': a {} file (the extension is {})", output.string(),
            options.separate ? "glTF (--separate)" : "binary glTF", options.separate ? ".gltf" : ".glb"));

    // Every step read and flattened before anything is written.
    std::vector<Step> steps = read_steps(input);
    FlattenOptions flatten;
    flatten.resolution = options.resolution;
    flatten.normal_scale = options.normal_scale;
    for (Step& step : steps) {
        throw_if_cancelled();
        if (!(step.stack.strip_size_m > 0.0))
            throw std::runtime_error(fmt::format(
                "export of '{}': the stack was made on a mesh; export takes strips (flatten "
                "the stack and wire its maps to the mesh)", step.stack.manifest.string()));
        step.flat = flatten_stack(step.stack, resolve_stack_materials(step.stack, library, colors),
                                  flatten);
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

    gltf::Document doc;
    doc.use_extension("KHR_materials_clearcoat");
    const std::string mesh_name = output.stem().string();
    const int sampler = doc.add_sampler(gltf::kClampToEdge);

    // One texture per map and step, identical ones shared (a clearcoat of zeros).
    std::map<std::string, int> textures_by_bytes;  // the PNG's bytes -> its texture
    size_t texture_count = 0;
    auto texture = [&](const Step& step, const std::string& map, std::vector<float> pixels,
                       int channels, int bits) {
        std::vector<unsigned char> png = encode_png(pixels.data(), width, height, channels, bits);
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
        const FlattenedStack& flat = step.flat;
        // Base colour: linear Rec.709 to sRGB-encoded, as glTF's baseColorTexture is.
        std::vector<float> base = checked(map_of(flat, "gltf_base_color"), 0, step, width);
        colors.convert("lin_rec709", "srgb_texture", base.data(), base.size() / 3);
        const int base_tex = texture(step, "base_color", std::move(base), 3, 8);
        const int mr_tex = texture(step, "metallic_roughness",
                                   checked(map_of(flat, "gltf_metallic_roughness"), 0, step, width),
                                   3, 8);
        const int normal_tex =
            texture(step, "normal", checked(map_of(flat, "normal"), 0, step, width), 3, 8);
        const int coat_tex = texture(step, "clearcoat",
                                     checked(map_of(flat, "gltf_clearcoat"), 0, step, width), 3, 8);
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

    ExportResult result;
    result.steps = steps.size();
    result.textures = texture_count;
    result.width = width;
    result.height = height;
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
