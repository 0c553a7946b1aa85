// write_flattened (flatten_stack.h): the flattened maps as EXR textures and their manifest.
#include "texgen/flatten/flatten_stack.h"

#include "core/output_transaction.h"
#include "core/cancel.h"
#include "core/image_io.h"
#include "texgen/stack/manifest.h"
#include "formats/texture_stack/texture_stack.h"
#include "formats/toml_location.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cmath>
#include <sstream>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

    constexpr const char* kBaker = "flatten";

    /// Path of `file` relative to `dir` when it lies inside it ("stack.toml" when flattening
    /// into the stack's folder), else absolute.
    std::string relative_text(const fs::path& file, const fs::path& dir)
    {
        std::error_code ec;
        const fs::path rel = fs::relative(file, dir, ec);
        if (!ec && !rel.empty() && *rel.begin() != "..")
            return rel.generic_string();
        const fs::path abs = fs::absolute(file, ec);
        return (ec ? file : abs.lexically_normal()).generic_string();
    }

    toml::table read_or_new_manifest(const fs::path& path)
    {
        toml::table root = read_manifest_for_update(path);  // checked as every writer does
        if (root.empty())
            root.insert_or_assign("stack", toml::table{{"format", kStackFormatVersion},
                                                       {"generator", "patina-texgen flatten"}});
        return root;
    }

}  // namespace

std::vector<fs::path> write_flattened(const fs::path& out_dir, const FlattenedStack& flat,
                                      const PatinaStackFiles& stack,
                                      const FlattenOptions& options, const ColorManager& colors)
{
    const std::string colorspace = flatten_colorspace(options.color_space);
    // Check every value before the first file is written: a NaN never becomes a map.
    check_finite_maps(flat, stack.manifest, "flatten");

    // An earlier flatten into this folder: its entries go, and its files where not rewritten.
    for (const std::string& file : forget_maps_of(out_dir, kBaker, "flatten"))
        remove_output(out_dir / file);

    const std::string source = relative_text(stack.manifest, out_dir);
    const bool lone = flat.udims.size() == 1 && flat.udims[0] == 1001;
    std::vector<fs::path> written;
    toml::table root = read_or_new_manifest(manifest_path(out_dir));
    if (!root["maps"].as_table())
        root.insert_or_assign("maps", toml::table{});
    toml::table& maps = *root["maps"].as_table();

    for (const FlatMap& map : flat.maps) {
        const std::string space = map.is_color ? colorspace : std::string("raw");
        TextureOptions texture;
        texture.format = options.half ? OIIO::TypeDesc::HALF : OIIO::TypeDesc::FLOAT;
        texture.wrap = "clamp";
        std::vector<fs::path> files;
        for (size_t tile = 0; tile < flat.udims.size(); ++tile) {
            throw_if_cancelled();
            std::vector<float> pixels = map.tiles[tile];
            if (map.is_color)
                colors.convert("lin_rec709", colorspace, pixels.data(), pixels.size() / 3);
            texture.metadata = {{"patina:map", map.name},
                                {"patina:baker", std::string(kBaker)},
                                {"patina:units", map.units},
                                {"patina:description", map.description},
                                {"patina:udim", flat.udims[tile]},
                                {"patina:colorspace", space},
                                {"oiio:ColorSpace", space},
                                {"patina:stack", source},
                                {"patina:time_years", static_cast<float>(stack.time_years)}};
            const fs::path path = out_dir / map_file_name(map.name, flat.udims[tile], lone);
            make_texture_atomic(path, pixels.data(), flat.width, flat.height,
                                static_cast<int>(map.channels.size()), map.channels, texture);
            files.push_back(path);
            written.push_back(path);
        }
        // The entry, as every writer of stack.toml makes it (formats/texture_stack/texture_stack.h).
        formats::StackMap entry;
        entry.name = map.name;
        if (lone) {
            entry.file = files[0].filename().string();
        } else {
            entry.pattern = map_file_pattern(map.name);
            entry.tiles = flat.udims;
        }
        entry.channels = map.channels;
        entry.units = map.units;
        entry.colorspace = space;
        entry.baker = kBaker;
        entry.description = map.description;
        entry.width = flat.width;
        entry.height = flat.height;
        entry.parameters = toml::table{{"stack", source},
                                       {"time_years", stack.time_years},
                                       {"color_space", options.color_space}};
        maps.insert_or_assign(map.name, formats::to_toml(entry));
    }

    // What the maps are, for a person or a pipeline reading the folder.
    formats::FlattenTable info;
    info.stack = source;
    info.color_space = colorspace;
    info.texel_size_m = flat.texel_size_m;
    info.normal_scale = options.normal_scale;
    info.gltf_target = gltf_target_name(options.target);
    for (const FlatMap& map : flat.maps)
        if (map.name.rfind("interface", 0) == 0 && map.name.ends_with("_specular")) {
            const std::string stem = map.name.substr(0, map.name.size() - 9);
            info.interfaces.push_back({map.name, stem + "_roughness"});
        }
    root.insert_or_assign("flatten", formats::to_toml(info));

    write_manifest(manifest_path(out_dir), root);
    written.push_back(manifest_path(out_dir));
    return written;
}

}  // namespace patina::texgen
