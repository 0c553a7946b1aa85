#include "texgen/stack/map_output.h"

#include "texgen/stack/manifest.h"
#include "texgen/stack/padding.h"
#include "texgen/stack/ply_writer.h"

#include "core/cancel.h"

#include <fmt/format.h>

#include <cmath>
#include <set>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

    /// Header attributes every map carries; a bake parameter may not reuse these names.
    const std::set<std::string> kReservedKeys = {"map",     "baker",      "units",
                                                 "description", "udim", "padding",
                                                 "colorspace", "coverage"};

    std::string parameter_key(const std::string& key)
    {
        return key.rfind("patina:", 0) == 0 ? key.substr(7) : key;
    }

    void check_description(const MapDescription& map, const char* what)
    {
        if (map.name.empty() || map.name == "." || map.name == ".." ||
            map.name.find_first_of("/\\") != std::string::npos)
            throw std::runtime_error(fmt::format(
                "cannot write {} '{}': the map name must be a plain file name", what, map.name));
        if (map.channels.empty())
            throw std::runtime_error(
                fmt::format("cannot write {} '{}': the map has no channels", what, map.name));
        std::set<std::string> seen = {std::string(kCoverageChannel)};
        for (const std::string& c : map.channels)
            if (c.empty() || !seen.insert(c).second)
                throw std::runtime_error(fmt::format(
                    "cannot write {} '{}': channel names must be non-empty, distinct and not "
                    "the coverage channel '{}' ('{}')",
                    what, map.name, kCoverageChannel, c));
        for (const auto& [key, value] : map.parameters)
            if (kReservedKeys.count(parameter_key(key)))
                throw std::runtime_error(fmt::format("cannot write {} '{}': parameter '{}' clashes "
                                                     "with the header attribute patina:{}",
                                                     what, map.name, key, parameter_key(key)));
    }

    const char* nonfinite_word(float v)
    {
        return std::isnan(v) ? "NaN" : "infinite";
    }

    std::string value_text(const MetadataValue& value)
    {
        return std::visit([](const auto& v) { return fmt::format("{}", v); }, value);
    }

}  // namespace

std::vector<fs::path> write_texel_map(const fs::path& out_dir, const MapDescription& map,
                                      const std::vector<TexelGrid>& tiles,
                                      const std::vector<std::vector<float>>& values,
                                      const MapOutputOptions& options)
{
    check_description(map, "map");
    if (tiles.empty())
        throw std::runtime_error(fmt::format("cannot write map '{}': no UDIM tiles", map.name));
    if (values.size() != tiles.size())
        throw std::runtime_error(
            fmt::format("cannot write map '{}': values for {} tiles, but {} tiles", map.name,
                        values.size(), tiles.size()));
    if (options.padding < -1)
        throw std::runtime_error(
            fmt::format("cannot write map '{}': padding {} must be -1 (fill all) or >= 0", map.name,
                        options.padding));
    const size_t nc = map.channels.size();

    // Check every tile before the first file is written: a bad value never leaves a
    // partial set of tiles behind.
    for (size_t i = 0; i < tiles.size(); ++i) {
        const TexelGrid& tile = tiles[i];
        if (tile.width <= 0 || tile.height <= 0 || tile.group_of_texel.size() != tile.texel_count())
            throw std::runtime_error(fmt::format(
                "cannot write map '{}': tile {} is {}x{} with {} texel entries", map.name,
                tile.udim, tile.width, tile.height, tile.group_of_texel.size()));
        const size_t groups = tile.groups.group_count();
        if (values[i].size() != groups * nc)
            throw std::runtime_error(fmt::format(
                "cannot write map '{}': tile {} has {} values for {} texel groups x {} channels",
                map.name, tile.udim, values[i].size(), groups, nc));
        for (size_t t = 0; t < tile.texel_count(); ++t) {
            const int32_t g = tile.group_of_texel[t];
            if (g < -1 || g >= static_cast<int64_t>(groups))
                throw std::runtime_error(
                    fmt::format("cannot write map '{}': tile {} texel {} names group {} of {}",
                                map.name, tile.udim, t, g, groups));
            if (g < 0)
                continue;
            for (size_t c = 0; c < nc; ++c) {
                const float v = values[i][static_cast<size_t>(g) * nc + c];
                if (!std::isfinite(v))
                    throw std::runtime_error(
                        fmt::format("cannot write map '{}': the baker gave texel ({}, {}) of tile "
                                    "{} channel '{}' a {} value (group {})",
                                    map.name, t % static_cast<size_t>(tile.width),
                                    t / static_cast<size_t>(tile.width), tile.udim, map.channels[c],
                                    nonfinite_word(v), g));
            }
        }
    }


    TextureOptions texture;
    texture.format = options.format;
    texture.tile_size = options.tile_size;
    // A UDIM tile's neighbour is another file: a lookup at its edge must not wrap around.
    texture.wrap = "clamp";
    const bool lone = tiles.size() == 1 && tiles[0].udim == 1001;
    std::vector<fs::path> files;
    for (size_t i = 0; i < tiles.size(); ++i) {
        const TexelGrid& tile = tiles[i];
        // A Ctrl-C between tiles stops before the next file; each file is whole or absent.
        throw_if_cancelled();
        // Scatter the groups' values into the texels they came from.
        std::vector<float> pixels(tile.texel_count() * nc, 0.0f);
        std::vector<uint8_t> covered(tile.texel_count(), 0);
        for (size_t t = 0; t < tile.texel_count(); ++t) {
            const int32_t g = tile.group_of_texel[t];
            if (g < 0)
                continue;
            covered[t] = 1;
            for (size_t c = 0; c < nc; ++c)
                pixels[t * nc + c] = values[i][static_cast<size_t>(g) * nc + c];
        }
        pad_texels(pixels, tile.width, tile.height, static_cast<int>(nc), covered, options.padding);
        // The coverage channel after the padded ones: the texel's covered fraction (1 inside
        // an island, less at its borders, 0 where nothing is baked), never padded, so a
        // consumer can tell a baked 0 from an empty texel.
        const size_t nw = nc + 1;
        std::vector<float> written(tile.texel_count() * nw);
        for (size_t t = 0; t < tile.texel_count(); ++t) {
            std::copy_n(&pixels[t * nc], nc, &written[t * nw]);
            written[t * nw + nc] = tile.group_of_texel[t] >= 0 && t < tile.coverage.size()
                                       ? tile.coverage[t]
                                       : 0.0f;
        }

        texture.metadata = {{"patina:map", map.name},
                            {"patina:baker", map.baker},
                            {"patina:units", map.units},
                            {"patina:description", map.description},
                            {"patina:udim", tile.udim},
                            {"patina:padding", options.padding},
                            {"patina:coverage", std::string(kCoverageChannel)},
                            // OpenEXR has no colour-space attribute and OIIO 2.4's EXR
                            // writer drops oiio:ColorSpace (readers then assume "Linear"):
                            // patina:colorspace is what survives. Maps are data, never colour.
                            {"patina:colorspace", std::string("raw")},
                            {"oiio:ColorSpace", std::string("raw")}};
        for (const auto& [key, value] : map.parameters)
            texture.metadata.emplace_back("patina:" + parameter_key(key), value);

        const fs::path path = out_dir / map_file_name(map.name, tile.udim, lone);
        std::vector<std::string> channels = map.channels;
        channels.emplace_back(kCoverageChannel);
        make_texture_atomic(path, written.data(), tile.width, tile.height, static_cast<int>(nw),
                            channels, texture);
        files.push_back(path);
    }
    return files;
}

void write_vertex_map(const fs::path& ply_path, const TriangleMesh& mesh, const MapDescription& map,
                      const std::vector<float>& values)
{
    check_description(map, "per-vertex map");
    const size_t nc = map.channels.size();
    if (values.size() != mesh.positions.size() * nc)
        throw std::runtime_error(fmt::format(
            "cannot write per-vertex map '{}' to '{}': {} values for {} vertices x {} channels",
            map.name, ply_path.string(), values.size(), mesh.positions.size(), nc));
    for (size_t i = 0; i < values.size(); ++i)
        if (!std::isfinite(values[i]))
            throw std::runtime_error(fmt::format("cannot write per-vertex map '{}' to '{}': the "
                                                 "baker gave vertex {} channel '{}' a {} value",
                                                 map.name, ply_path.string(), i / nc,
                                                 map.channels[i % nc], nonfinite_word(values[i])));

    std::vector<std::string> names;
    for (const std::string& c : map.channels)
        names.push_back(sanitize_ply_name(c));
    std::vector<std::string> comments = {
        "patina:map " + map.name, "patina:baker " + map.baker, "patina:units " + map.units,
        "patina:description " + map.description, "patina:colorspace raw"};
    for (const auto& [key, value] : map.parameters)
        comments.push_back(fmt::format("patina:{} {}", parameter_key(key), value_text(value)));
    throw_if_cancelled();
    write_ply_with_vertex_values(ply_path, mesh, names, values, comments);
}

}  // namespace patina::texgen
