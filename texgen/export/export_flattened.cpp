#include "texgen/export/export_flattened.h"

#include "formats/texture_stack/texture_stack.h"
#include "texgen/export/export_asset.h"
#include "texgen/flatten/patina_stack_files.h"
#include "texgen/texels/mesh_merge.h"

#include "core/image_io.h"

#include "texgen/meshes/mesh_input.h"
#include "texgen/texels/uv_wrap.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

}  // namespace

bool is_flattened_stack(const fs::path& input)
{
    const fs::path manifest = stack_manifest_of(input);
    std::error_code ec;
    if (!fs::is_regular_file(manifest, ec))
        return false;
    try {
        const toml::table root = toml::parse_file(manifest.string());
        return root["flatten"].is_table() && !root["patina"];
    } catch (const toml::parse_error&) {
        return false;  // the stack reader reports it, with its line
    }
}

ExportResult export_flattened(const fs::path& input, const fs::path& output,
                              const ExportOptions& given, const ColorManager& colors)
{
    ExportOptions options = given;
    check_export_options(options, output);
    if (options.resolution > 0)
        throw std::runtime_error("--resolution: flattened maps export at their own resolution "
                                 "(flatten again with --resolution)");
    const formats::TextureStack stack = formats::read_texture_stack(input);
    // The [flatten] table, as the stack's reader checked it (a flattened stack has one).
    const formats::FlattenTable info = stack.flatten.value_or(formats::FlattenTable{});
    // The glTF maps are fitted for one renderer when they are made: refuse another.
    if (info.gltf_target.empty())
        throw std::runtime_error(fmt::format(
            "export of '{}': its glTF maps come from an older flatten, fitted for no renderer; "
            "flatten the stack again (--target {})",
            stack.manifest.string(), options.target));
    if (info.gltf_target != options.target)
        throw std::runtime_error(fmt::format(
            "export of '{}': its glTF maps are fitted for --target {}; flatten again with "
            "--target {}, or export with --target {}",
            stack.manifest.string(), info.gltf_target, options.target, info.gltf_target));

    ExportStep step;
    step.manifest = stack.manifest;
    step.label = stack.folder().filename().string();
    if (step.label.empty())
        step.label = "flat";
    FlattenedStack& flat = step.flat;
    double time_years = 0.0;
    for (const char* name : formats::kGltfExportMaps) {
        const formats::StackMap& entry = stack.map(name);  // throws naming the manifest
        if (flat.udims.empty()) {
            flat.udims = entry.udims();
            flat.width = entry.width;
            flat.height = entry.height;
            time_years = entry.parameters["time_years"].value_or(0.0);
        }
        FlatMap map;
        map.name = name;
        map.channels = entry.channels;
        map.is_color = std::string(name) == formats::kGltfBaseColorMap;
        for (const fs::path& file : entry.files(stack.folder())) {
            const ImageData image = read_image(file);
            if (image.width != flat.width || image.height != flat.height ||
                image.channels < static_cast<int>(entry.channels.size()) ||
                entry.udims() != flat.udims)
                throw std::runtime_error(fmt::format(
                    "export of '{}': map '{}' ('{}') is {}x{} texels of {} channels on {} "
                    "tile(s); the maps are {}x{} on {}",
                    stack.manifest.string(), name, file.string(), image.width, image.height,
                    image.channels, entry.udims().size(), flat.width, flat.height,
                    flat.udims.size()));
            // The map's own channels, in the order the manifest lists them.
            const size_t texels = static_cast<size_t>(image.width) * image.height;
            std::vector<float> tile(texels * entry.channels.size());
            for (size_t c = 0; c < entry.channels.size(); ++c) {
                const int at = image.channel(entry.channels[c]);
                if (at < 0)
                    throw std::runtime_error(fmt::format("{}: no channel '{}' (the manifest "
                                                         "lists it)",
                                                         file.string(), entry.channels[c]));
                for (size_t t = 0; t < texels; ++t)
                    tile[t * entry.channels.size() + c] = image.pixels[t * image.channels + at];
            }
            if (map.is_color && entry.colorspace != "lin_rec709")
                colors.convert(entry.colorspace, "lin_rec709", tile.data(), texels);
            map.tiles.push_back(std::move(tile));
        }
        flat.maps.push_back(std::move(map));
    }
    flat.texel_size_m = info.texel_size_m;
    step.variant = age_name(time_years);
    step.extras = {{"time_years", time_years},
                   {"stack", relative_to(stack.manifest, output.parent_path())}};
    encode_step(step, options, colors);

    // The geometry of the stack the maps came from: its strip, or its mesh.
    ExportGeometry geometry;
    PatinaStackFiles source;
    const std::string& source_text = info.stack;
    const fs::path source_path = source_text.empty() ? fs::path()
                                                     : stack.folder() / fs::path(source_text);
    std::error_code ec;
    const bool have_source = !source_path.empty() && fs::exists(source_path, ec);
    if (have_source)
        source = read_patina_stack(source_path);
    const fs::path mesh_file = options.mesh.empty() ? source.mesh : options.mesh;
    if (!mesh_file.empty()) {
        if (!fs::is_regular_file(mesh_file, ec))
            throw std::runtime_error(fmt::format("export of '{}': the mesh '{}' does not exist",
                                                 stack.manifest.string(), mesh_file.string()));
        geometry.mesh = load_merged_mesh(
            mesh_file, convention_for_stack(options.convention, source.mesh_convention,
                                            "the stack of " + stack.manifest.string()));
        if (source.uv_wrap)
            wrap_uvs_outside_udims(geometry.mesh);
    } else if (have_source ? source.strip_size_m > 0.0 : flat.texel_size_m > 0.0) {
        // A strip of its stack's size; without the stack, a plane of the maps' own size.
        geometry.width_m = have_source ? source.strip_size_m : flat.texel_size_m * flat.width;
        geometry.height_m = geometry.width_m * flat.height / std::max(1, flat.width);
    } else {
        throw std::runtime_error(fmt::format(
            "export of '{}': the maps' stack ('{}') was grown on a mesh it does not name; "
            "pass --mesh", stack.manifest.string(), source_text));
    }
    std::vector<ExportStep> steps;
    steps.push_back(std::move(step));
    return write_export(steps, geometry, input, output, options, colors);
}

}  // namespace patina::texgen
