#include "texgen/export/export_asset.h"

#include "formats/texture_stack/texture_stack.h"

#include "texgen/export/gltf_document.h"
#include "texgen/export/gltf_geometry.h"
#include "texgen/export/png_encode.h"
#include "texgen/export/source_material.h"
#include "core/one_line.h"
#include "texgen/export/presets.h"
#include "texgen/flatten/gltf_albedo.h"

#include "core/cancel.h"
#include "core/image_io.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <set>
#include <stdexcept>

namespace patina::texgen {

FlattenedStack rough_dielectric(int width, int height, std::vector<float> base,
                                const std::string& description)
{
    FlattenedStack flat;
    flat.width = width;
    flat.height = height;
    flat.udims = {1001};
    const size_t texels = static_cast<size_t>(width) * height;
    auto constant = [&](std::initializer_list<float> value) {
        std::vector<float> v(value.size() * texels);
        for (size_t i = 0; i < texels; ++i)
            std::copy(value.begin(), value.end(), v.begin() + i * value.size());
        return std::vector<std::vector<float>>{std::move(v)};
    };
    flat.maps = {
        {formats::kGltfBaseColorMap, {"R", "G", "B"}, "1", description, true, {std::move(base)}},
        // R occlusion 1, G roughness 1, B metallic 0
        {formats::kGltfMetallicRoughnessMap, {"R", "G", "B"}, "1", "", false, constant({1, 1, 0})},
        {formats::kGltfClearcoatMap, {"R", "G", "B"}, "1", "", false, constant({0, 0, 0})},
        {formats::kNormalMap, {"R", "G", "B"}, "1", "", false, constant({0.5f, 0.5f, 1})},
        {formats::kHeightMap, {"height"}, "um", "", false, constant({0})}};
    return flat;
}


namespace fs = std::filesystem;
using nlohmann::json;

namespace {

    /// The largest UDIM tile a glTF export takes: the ten columns of the first 10 rows.
    constexpr int kMaxUdim = 1099;

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
            pattern.append(".").append(std::to_string(udim));
        return pattern + ".png";
    }

    /// Refuses a --name-template that could name a file outside the output folder or no file:
    /// an absolute path, a `..` part, a control character, a `$key` other than $mesh,
    /// $material, $map and $udim, or one without $map (every map would get one name).
    void check_name_template(const std::string& t)
    {
        auto refuse = [&](const std::string& why) {
            return std::runtime_error(fmt::format("--name-template '{}': {}", one_line(t), why));
        };
        if (t.empty() || t.front() == '/')
            throw refuse("names a file inside the output folder: not empty, not absolute");
        for (const char c : t)
            if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f)
                throw refuse("a control character");
        for (const fs::path& part : fs::path(t))
            if (part == "..")
                throw refuse("'..' would leave the output folder");
        for (size_t at = t.find('$'); at != std::string::npos; at = t.find('$', at + 1)) {
            bool known = false;
            for (const char* key : {"$mesh", "$material", "$map", "$udim"})
                known |= t.compare(at, std::strlen(key), key) == 0;
            if (!known)
                throw refuse("unknown key at '" + one_line(t.substr(at, 12)) +
                             "' (known: $mesh, $material, $map, $udim)");
        }
        if (t.find("$map") == std::string::npos)
            throw refuse("has no $map: every map would get the same name");
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
    double height_range_um(const std::vector<ExportStep>& steps)
    {
        double top = 0.0;
        for (const ExportStep& step : steps)
            for (const FlatMap& map : step.flat.maps)
                if (map.name == formats::kHeightMap)
                    for (const std::vector<float>& tile : map.tiles)
                        for (float h : tile)
                            top = std::max(top, static_cast<double>(h));
        return top;
    }

    /// The texture presets: every map of every step as a file of `dir`.
    std::vector<fs::path> write_textures(const fs::path& dir, const std::vector<ExportStep>& steps,
                                         const ExportOptions& options, const ColorManager& colors)
    {
        const double range = height_range_um(steps);
        std::vector<fs::path> written;
        const std::string mesh = dir.filename().string();
        std::set<std::string> names;  // two maps of one name would overwrite each other
        for (const ExportStep& step : steps) {
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
                    if (!names.insert(name).second)
                        throw std::runtime_error(fmt::format(
                            "--name-template '{}': two maps would be written as '{}' (give each "
                            "step its $material)", options.name_template, name));
                    const int channels = static_cast<int>(map.channels.size());
                    if (exr) {
                        name.replace(name.size() - 4, 4, ".exr");
                        const Metadata meta = {
                            {"patina:map", map.name},
                            {"patina:preset", options.preset},
                            {"patina:age", step.variant},
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

fs::path stack_manifest_of(const fs::path& input)
{
    std::error_code ec;
    return fs::is_directory(input, ec) ? input / formats::kStackManifest : input;
}

std::string relative_to(const fs::path& file, const fs::path& dir)
{
    std::error_code ec;
    const fs::path rel = fs::relative(file, dir.empty() ? fs::path(".") : dir, ec);
    return (ec || rel.empty() ? file : rel).generic_string();
}


void check_export_options(ExportOptions& options, const fs::path& output)
{
    if (options.bits == 0)
        options.bits = options.preset == "exr" ? 32 : 8;
    check_preset(options.preset);
    gltf_target(options.target);  // throws naming --target
    check_name_template(options.name_template);
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

}

std::vector<ExportStep> make_steps(size_t count,
                                   const std::function<void(size_t, ExportStep&)>& make)
{
    std::vector<ExportStep> steps(count);
    std::vector<std::exception_ptr> failures(count);
    tbb::parallel_for(size_t(0), count, [&](size_t k) {
        try {
            throw_if_cancelled();
            make(k, steps[k]);
        } catch (...) {
            failures[k] = std::current_exception();
        }
    });
    for (const std::exception_ptr& failure : failures)
        if (failure)
            std::rethrow_exception(failure);
    return steps;
}

void encode_step(ExportStep& step, const ExportOptions& options, const ColorManager& colors)
{
    check_finite_maps(step.flat, step.manifest, "export");
    for (int udim : step.flat.udims)
        if (udim > kMaxUdim)
            throw std::runtime_error(fmt::format(
                "export of '{}': UDIM tile {} is beyond {}; glTF has no UDIM, and export makes "
                "one material per tile of the first ten rows",
                step.manifest.string(), udim, kMaxUdim));
    if (preset_writes_textures(options.preset))
        return;
    step.pngs.resize(step.flat.udims.size());
    for (size_t tile = 0; tile < step.flat.udims.size(); ++tile) {
        const std::vector<PresetMap> maps = preset_maps("gltf", step.flat, tile, 0.0, colors);
        std::vector<std::vector<unsigned char>> pngs =
            encode_all(maps, step.flat.width, step.flat.height, 8);
        for (size_t m = 0; m < maps.size(); ++m)
            step.pngs[tile].emplace_back(maps[m].name, std::move(pngs[m]));
    }
    step.flat.maps.clear();  // encoded: the memory goes back
}

ExportResult write_export(std::vector<ExportStep>& steps, const ExportGeometry& geometry,
                          const fs::path& input, const fs::path& output,
                          const ExportOptions& options, const ColorManager& colors)
{
    for (const ExportStep& step : steps) {
        const ExportStep& first = steps.front();
        if (step.flat.width != first.flat.width || step.flat.height != first.flat.height ||
            step.flat.udims != first.flat.udims)
            throw std::runtime_error(fmt::format(
                "export of '{}': the steps disagree: {} is {}x{} texels on {} tile(s), {} is "
                "{}x{} on {}",
                input.string(), first.label, first.flat.width, first.flat.height,
                first.flat.udims.size(), step.label, step.flat.width, step.flat.height,
                step.flat.udims.size()));
    }
    const int width = steps.front().flat.width, height = steps.front().flat.height;
    const std::vector<int>& udims = steps.front().flat.udims;

    ExportResult result;
    result.steps = steps.size();
    result.width = width;
    result.height = height;
    if (preset_writes_textures(options.preset)) {
        result.files = write_textures(output, steps, options, colors);
        result.textures = result.files.size();
        return result;
    }

    gltf::Document doc;
    const std::string mesh_name = output.stem().string();
    const int sampler = doc.add_sampler(gltf::kClampToEdge);

    // One texture per map and step, identical ones shared.
    std::map<std::string, int> textures_by_bytes;  // the PNG's bytes -> its texture
    std::set<std::string> file_names;              // --separate: each map a file of its own
    size_t texture_count = 0;
    auto texture = [&](const ExportStep& step, size_t tile, const std::string& map,
                       std::vector<unsigned char> png) {
        std::string key(png.begin(), png.end());
        const auto found = textures_by_bytes.find(key);
        if (found != textures_by_bytes.end())
            return found->second;
        const std::string name = udims.size() > 1
                                     ? fmt::format("{} {} {}", step.label, map, udims[tile])
                                     : fmt::format("{} {}", step.label, map);
        const std::string file = expand(options.name_template, mesh_name, step.label, map,
                                        udims[tile], udims.size() > 1);
        if (options.separate && !file_names.insert(file).second)
            throw std::runtime_error(fmt::format(
                "--name-template '{}': two maps would be written as '{}' (give each step its "
                "$material)", options.name_template, file));
        const int image = doc.add_png(name, file, png);
        const int t = doc.add_texture(image, sampler);
        textures_by_bytes.emplace(std::move(key), t);
        ++texture_count;
        return t;
    };

    // A material per step, tile and source material: materials[step][tile * sources + s].
    // Its textures read the uv set the maps were baked into. A mesh of one source material
    // keeps the names without it. Kept-off source materials get one plain material each.
    const bool tiled = udims.size() > 1;
    const TriangleMesh& source = geometry.mesh;
    const size_t sources = std::max<size_t>(1, source.materials.size());
    const bool by_source = source.materials.size() > 1 || !geometry.keep_off.empty();
    std::vector<int> kept(sources, -1);
    for (size_t s = 0; s < source.materials.size(); ++s)
        if (std::find(geometry.keep_off.begin(), geometry.keep_off.end(), source.materials[s]) !=
            geometry.keep_off.end())
            kept[s] = add_source_material(doc, fmt::format("{} {}", mesh_name, source.materials[s]),
                                          source.material_base_colours[s],
                                          source.material_base_textures[s]);
    const int tex_coord = weathering_tex_coord(geometry.mesh);
    const auto info = [tex_coord](int texture) {
        json i = {{"index", texture}};
        if (tex_coord != 0)
            i["texCoord"] = tex_coord;
        return i;
    };
    std::vector<std::vector<int>> materials(steps.size());
    for (size_t k = 0; k < steps.size(); ++k) {
        const ExportStep& step = steps[k];
        throw_if_cancelled();
        for (size_t tile = 0; tile < udims.size(); ++tile) {
            // The gltf preset: base colour sRGB-encoded, as glTF's baseColorTexture is; the
            // data maps linear.
            std::map<std::string, int> tex;
            for (const auto& [map, png] : step.pngs[tile])
                tex[map] = texture(step, tile, map, png);
            const int base_tex = tex.at("base_color"), mr_tex = tex.at("metallic_roughness"),
                      normal_tex = tex.at("normal");
            const auto coat_tex = tex.find(kGltfPresetCoat);  // none: no coat here
            json patina = step.extras;
            if (tiled)
                patina["udim"] = udims[tile];
            for (size_t s = 0; s < sources; ++s) {
                if (kept[s] >= 0) {
                    materials[k].push_back(kept[s]);
                    continue;
                }
                const std::string name =
                    by_source ? fmt::format("{} {}", mesh_name, source.materials[s]) : mesh_name;
                json material = {
                    {"name", tiled ? fmt::format("{} {} {}", name, step.variant, udims[tile])
                                   : fmt::format("{} {}", name, step.variant)},
                    {"pbrMetallicRoughness",
                     {{"baseColorTexture", info(base_tex)},
                      {"metallicRoughnessTexture", info(mr_tex)}}},
                    {"normalTexture", info(normal_tex)},
                    {"extras", {{"patina", patina}}}};
                if (coat_tex != tex.end()) {
                    doc.use_extension("KHR_materials_clearcoat");
                    material["extensions"]["KHR_materials_clearcoat"] = {
                        {"clearcoatFactor", 1.0},
                        {"clearcoatTexture", info(coat_tex->second)},
                        {"clearcoatRoughnessFactor", 1.0},
                        {"clearcoatRoughnessTexture", info(coat_tex->second)}};
                }
                materials[k].push_back(doc.add("materials", std::move(material)));
            }
        }
    }

    // The strip as a plane of its size, or the mesh split by tile.
    const std::vector<TilePrimitive> parts =
        geometry.mesh.positions.empty()
            ? std::vector<TilePrimitive>{add_strip_plane(doc, geometry.width_m, geometry.height_m)}
            : add_mesh_primitives(doc, geometry.mesh, udims,
                                  fmt::format("export of '{}'", input.string()));
    json primitives = json::array();
    for (const TilePrimitive& part : parts) {
        // The default material is the last step (the age the script describes).
        json primitive = {{"attributes", part.attributes}, {"indices", part.indices},
                          {"material", materials.back()[part.tile * sources + part.material]}};
        if (steps.size() > 1) {
            json mappings = json::array();
            for (size_t k = 0; k < steps.size(); ++k)
                mappings.push_back({{"material", materials[k][part.tile * sources + part.material]},
                                    {"variants", {k}}});
            primitive["extensions"]["KHR_materials_variants"] = {{"mappings", mappings}};
        }
        primitives.push_back(std::move(primitive));
    }
    if (steps.size() > 1) {
        doc.use_extension("KHR_materials_variants");
        json variants = json::array();
        for (const ExportStep& step : steps)
            variants.push_back({{"name", step.variant}});
        doc.root()["extensions"]["KHR_materials_variants"] = {{"variants", variants}};
    }
    const int gltf_mesh = doc.add("meshes", {{"name", mesh_name}, {"primitives", primitives}});
    const int node = doc.add("nodes", {{"name", mesh_name}, {"mesh", gltf_mesh}});
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
