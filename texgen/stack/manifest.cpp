#include "texgen/stack/manifest.h"

#include "core/output_transaction.h"
#include "texgen/stack/map_output.h"
#include "formats/texture_stack/texture_stack.h"
#include "formats/toml_location.h"

#include "core/cancel.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cstdlib>
#include <fstream>
#include <sstream>
#include <stdexcept>

// The library is built without the project version when texgen/CMakeLists.txt does not
// pass it; the manifest then says so rather than guessing.
#ifndef PATINA_VERSION_STRING
#define PATINA_VERSION_STRING "(unknown version)"
#endif

namespace patina::texgen {

namespace fs = std::filesystem;

fs::path manifest_path(const fs::path& out_dir)
{
    return out_dir / "stack.toml";
}

std::string map_file_name(const std::string& name, int udim, bool lone_1001_tile)
{
    if (lone_1001_tile)
        return name + ".exr";
    return fmt::format("{}.{}.exr", name, udim);
}

std::string map_file_pattern(const std::string& name)
{
    return name + ".<UDIM>.exr";
}

namespace {

    /// `file` relative to the folder of the manifest, with '/' separators.
    fs::path relative_to(const fs::path& file, const fs::path& out_dir)
    {
        std::error_code ec;
        fs::path rel = fs::relative(file, out_dir, ec);
        if (ec || rel.empty())
            return file;
        return rel;
    }

    /// A float parameter as the double that prints like the float (0.1f -> 0.1, not
    /// 0.10000000149011612): fmt prints the shortest text that reads back as the same float.
    double as_shortest_double(float v)
    {
        return std::strtod(fmt::format("{}", v).c_str(), nullptr);
    }

    toml::table parameters_table(const MapDescription& map)
    {
        toml::table params;
        for (const auto& [key, value] : map.parameters) {
            const std::string k = key.rfind("patina:", 0) == 0 ? key.substr(7) : key;
            std::visit(
                [&, &k = k](const auto& v) {
                    using T = std::decay_t<decltype(v)>;
                    if constexpr (std::is_same_v<T, int>)
                        params.insert_or_assign(k, static_cast<int64_t>(v));
                    else if constexpr (std::is_same_v<T, float>)
                        params.insert_or_assign(k, as_shortest_double(v));
                    else
                        params.insert_or_assign(k, v);
                },
                value);
        }
        return params;
    }

}  // namespace

toml::table read_manifest_for_update(const fs::path& path)
{
    // This run's own version when it wrote one already (two maps recorded in one run).
    const fs::path file = output_to_read(path);
    std::error_code ec;
    if (!fs::exists(file, ec))
        return {};
    if (!fs::is_regular_file(file, ec))
        throw std::runtime_error(fmt::format("manifest '{}' is not a file", path.string()));
    toml::table root;
    try {
        root = toml::parse_file(file.string());
    } catch (const toml::parse_error& e) {
        throw std::runtime_error(fmt::format("cannot update manifest {}: {} (fix or "
                                             "remove the file; it was left unchanged)",
                                             formats::toml_where(path, e.source().begin),
                                             e.description()));
    }
    auto fail = [&](const toml::node* node, const std::string& what) {
        throw std::runtime_error(fmt::format("cannot update manifest {}: {} (fix or "
                                             "remove the file; it was left unchanged)",
                                             formats::toml_where(path, node), what));
    };
    try {
        formats::check_stack_format(path, root);
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(fmt::format("cannot update manifest {} (fix or remove the "
                                             "file; it was left unchanged)",
                                             e.what()));
    }
    if (const toml::node* maps = root.get("maps"); maps && !maps->is_table())
        fail(maps, "'maps' must be a table of maps");
    return root;
}

void record_in_manifest(const fs::path& out_dir, const MapDescription& map,
                        const std::vector<fs::path>& files, const std::vector<TexelGrid>& tiles)
{
    const fs::path path = manifest_path(out_dir);
    if (map.name.empty())
        throw std::runtime_error(fmt::format("manifest '{}': a map needs a name", path.string()));
    if (files.empty())
        throw std::runtime_error(
            fmt::format("manifest '{}': map '{}' has no files", path.string(), map.name));

    formats::StackMap entry;
    entry.name = map.name;
    if (tiles.empty()) {
        // The per-vertex mode: one PLY, no texels.
        if (files.size() != 1)
            throw std::runtime_error(
                fmt::format("manifest '{}': per-vertex map '{}' must be one file, not {}",
                            path.string(), map.name, files.size()));
        entry.file = relative_to(files[0], out_dir).generic_string();
        entry.domain = "vertex";
    } else {
        if (files.size() != tiles.size())
            throw std::runtime_error(
                fmt::format("manifest '{}': map '{}' has {} files for {} tiles", path.string(),
                            map.name, files.size(), tiles.size()));
        const bool lone = tiles.size() == 1 && tiles[0].udim == 1001;
        if (lone) {
            entry.file = relative_to(files[0], out_dir).generic_string();
        } else {
            // The pattern must describe every file, or a renderer would look for other names.
            const fs::path folder = relative_to(files[0], out_dir).parent_path();
            for (size_t i = 0; i < tiles.size(); ++i) {
                const fs::path expected = folder / map_file_name(map.name, tiles[i].udim, false);
                if (relative_to(files[i], out_dir) != expected)
                    throw std::runtime_error(fmt::format(
                        "manifest '{}': file '{}' of map '{}' should be '{}' for tile {}",
                        path.string(), files[i].string(), map.name, expected.generic_string(),
                        tiles[i].udim));
                entry.tiles.push_back(tiles[i].udim);
            }
            entry.pattern = (folder / map_file_pattern(map.name)).generic_string();
        }
        entry.domain = "texel";
    }
    entry.channels = map.channels;
    if (!tiles.empty()) {
        // Texel maps carry the coverage channel after their own (write_texel_map).
        entry.channels.push_back(kCoverageChannel);
        entry.coverage = kCoverageChannel;
    }
    entry.units = map.units;
    entry.colorspace = "raw";
    entry.baker = map.baker;
    entry.description = map.description;
    if (!tiles.empty()) {
        for (const TexelGrid& t : tiles)
            if (t.width != tiles[0].width || t.height != tiles[0].height)
                throw std::runtime_error(fmt::format(
                    "manifest '{}': tiles of map '{}' differ in size ({}: {}x{}, {}: {}x{})",
                    path.string(), map.name, tiles[0].udim, tiles[0].width, tiles[0].height, t.udim,
                    t.width, t.height));
        entry.width = tiles[0].width;
        entry.height = tiles[0].height;
    }
    entry.parameters = parameters_table(map);

    // Read (and check) the manifest before anything is written, then replace this map only.
    toml::table root = read_manifest_for_update(path);
    if (!root.contains("stack"))
        root.insert_or_assign("stack", toml::table{});
    toml::table& stack = *root["stack"].as_table();
    stack.insert_or_assign("format", static_cast<int64_t>(kStackFormatVersion));
    stack.insert_or_assign("generator", std::string("patina-texgen ") + PATINA_VERSION_STRING);
    if (!root.contains("maps"))
        root.insert_or_assign("maps", toml::table{});
    root["maps"].as_table()->insert_or_assign(map.name, formats::to_toml(entry));

    throw_if_cancelled();
    write_manifest(path, root);
}

void write_manifest(const fs::path& path, const toml::table& root)
{
    std::ostringstream text;
    text << "# Texture stack written by patina-texgen (docs/file-formats.md): every map of this\n"
            "# folder, its channels, units and colour space; maps are data (colour space raw),\n"
            "# never colour. [patina] lists a grown stack's layers bottom to top (the base,\n"
            "# infinitely thick, first; thicknesses in micrometres) and [patina.materials] the\n"
            "# optics of every material it uses per wavelength (nm): KM absorption K and\n"
            "# scattering S per micrometre, the specular colour and roughness of its top\n"
            "# surface, a metal's n and k. [flatten] says what flattened maps are.\n";
    // [stack] first for the reader (toml++ sorts keys). Only when every other top-level entry
    // is a table: a bare key printed after [stack] would move into it.
    toml::table rest = root;
    rest.erase("stack");
    bool only_tables = root["stack"].is_table();
    for (const auto& [key, node] : rest)
        only_tables = only_tables && node.is_table();
    if (only_tables)
        text << toml::table{{"stack", *root["stack"].as_table()}} << "\n\n" << rest << "\n";
    else
        text << root << "\n";
    write_file_atomic(path, {text.str()}, "manifest");
}

void check_manifest_can_be_updated(const fs::path& out_dir)
{
    const fs::path path = manifest_path(out_dir);
    reserve_output(path);
    read_manifest_for_update(path);
}

std::vector<std::string> forget_maps_of(const fs::path& out_dir, const std::string& baker,
                                        const std::string& table)
{
    const fs::path path = manifest_path(out_dir);
    toml::table root = read_manifest_for_update(path);
    if (root.empty())
        return {};
    bool changed = !table.empty() && root.erase(table) > 0;
    std::vector<std::string> files;
    if (toml::table* maps = root["maps"].as_table()) {
        std::vector<std::string> stale;
        for (const auto& [name, entry] : *maps)
            if (const toml::table* t = entry.as_table();
                t && t->get("baker") && t->get("baker")->value<std::string>() == baker)
                stale.emplace_back(name.str());
        for (const std::string& name : stale) {
            if (const auto* file = (*maps)[name]["file"].as_string())
                files.push_back(file->get());
            maps->erase(name);
            changed = true;
        }
    }
    if (changed)
        write_manifest(path, root);
    return files;
}

}  // namespace patina::texgen
