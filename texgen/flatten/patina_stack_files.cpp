#include "texgen/flatten/patina_stack_files.h"

#include "texgen/stack/manifest.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <optional>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

    [[noreturn]] void fail(const fs::path& file, const std::string& what)
    {
        throw std::runtime_error(fmt::format("patina stack '{}': {}", file.string(), what));
    }

    /// The tiles and files of map `name` from its `[maps.<name>]` entry.
    void map_files(const fs::path& manifest, const toml::table& root, const std::string& name,
                   std::vector<int>& udims, std::vector<fs::path>& files, int& width,
                   int& height, double& strip_size_m)
    {
        const toml::table* entry = root["maps"][name].as_table();
        if (!entry)
            fail(manifest, fmt::format("map '{}' is not listed in [maps]", name));
        const fs::path dir = manifest.parent_path();
        udims.clear();
        files.clear();
        if (const auto file = (*entry)["file"].value<std::string>()) {
            udims.push_back(1001);
            files.push_back(dir / *file);
        } else if (const auto pattern = (*entry)["pattern"].value<std::string>()) {
            const toml::array* tiles = (*entry)["tiles"].as_array();
            const size_t at = pattern->find("<UDIM>");
            if (!tiles || tiles->empty() || at == std::string::npos)
                fail(manifest, fmt::format("map '{}' has a pattern but no tiles", name));
            for (const toml::node& t : *tiles) {
                const auto udim = t.value<int64_t>();
                if (!udim)
                    fail(manifest, fmt::format("map '{}': tiles must be integers", name));
                udims.push_back(static_cast<int>(*udim));
                files.push_back(dir / (pattern->substr(0, at) + std::to_string(*udim) +
                                       pattern->substr(at + 6)));
            }
        } else {
            fail(manifest, fmt::format("map '{}' has neither file nor pattern", name));
        }
        for (const fs::path& f : files)
            if (std::error_code ec; !fs::is_regular_file(f, ec))
                fail(manifest, fmt::format("map '{}': file '{}' does not exist", name,
                                           f.string()));
        if (const toml::array* res = (*entry)["resolution"].as_array(); res && res->size() == 2) {
            width = static_cast<int>(res->get(0)->value<int64_t>().value_or(0));
            height = static_cast<int>(res->get(1)->value<int64_t>().value_or(0));
        }
        if (const auto s = (*entry)["parameters"]["strip_size_m"].value<double>())
            strip_size_m = *s;
    }

}  // namespace

PatinaStackFiles read_patina_stack(const fs::path& stack)
{
    std::error_code ec;
    fs::path manifest = stack;
    if (fs::is_directory(stack, ec)) {
        manifest = manifest_path(stack);
        if (!fs::exists(manifest, ec) && fs::exists(stack / "series.toml", ec))
            fail(stack, "a time series (series.toml), not one stack: name a step folder "
                        "(e.g. t30) or its stack.toml");
    }
    if (!fs::is_regular_file(manifest, ec))
        fail(manifest, "no such file (expected a patina stack folder or its stack.toml)");

    toml::table root;
    try {
        root = toml::parse_file(manifest.string());
    } catch (const toml::parse_error& e) {
        fail(manifest, fmt::format("line {}: {}", e.source().begin.line, e.description()));
    }
    formats::check_stack_format(manifest, root);
    const toml::table* patina = root["patina"].as_table();
    if (!patina)
        fail(manifest, "no [patina] table: not a stack written by `patina-texgen patina`");

    PatinaStackFiles out;
    out.manifest = manifest;
    const auto base = (*patina)["base"].value<std::string>();
    if (!base || base->empty())
        fail(manifest, "[patina] has no base material");
    out.base = *base;
    out.time_years = (*patina)["time_years"].value<double>().value_or(0.0);

    std::vector<int> udims;
    if (const toml::array* layers = (*patina)["layers"].as_array()) {
        for (size_t i = 0; i < layers->size(); ++i) {
            const toml::table* layer = layers->get(i)->as_table();
            const auto material = layer ? (*layer)["material"].value<std::string>() : std::nullopt;
            const auto map = layer ? (*layer)["map"].value<std::string>() : std::nullopt;
            if (!material || !map)
                fail(manifest, fmt::format("[[patina.layers]] entry {} needs material and map",
                                           i + 1));
            StackLayerFiles files{*material, *map, {}, "thickness"};
            // One rule with plugins/layered: a layer that names no channel reads its map's
            // first channel, the first of the map's `channels` ("thickness" when the map
            // lists none).
            if (const auto first = root["maps"][*map]["channels"][0].value<std::string>())
                files.channel = *first;
            // A layer reading a channel of a multi-channel map: by name, or by index into the
            // map's `channels` (as plugins/layered reads it).
            if (const toml::node* c = layer->get("channel")) {
                const toml::node* name = c;
                if (const auto index = c->value<int64_t>())
                    name = *index >= 0
                               ? root["maps"][*map]["channels"][static_cast<size_t>(*index)].node()
                               : nullptr;
                const auto channel = name ? name->value<std::string>() : std::nullopt;
                if (!channel || channel->empty())
                    fail(manifest, fmt::format("[[patina.layers]] entry {}: 'channel' must name a "
                                               "channel of map '{}' or index its 'channels'",
                                               i + 1, *map));
                files.channel = *channel;
            }
            map_files(manifest, root, *map, udims, files.files, out.width, out.height,
                      out.strip_size_m);
            // The layer's single-channel copy (stack_writer writes both) must be there too:
            // a stack with a listed file missing is broken, whichever file we read.
            if (const auto single = (*layer)["layer_map"].value<std::string>()) {
                std::vector<int> single_udims;
                std::vector<fs::path> single_files;
                int w = 0, h = 0;
                double size = 0.0;
                map_files(manifest, root, *single, single_udims, single_files, w, h, size);
            }
            if (i == 0)
                out.udims = udims;
            else if (udims != out.udims)
                fail(manifest, fmt::format("layer map '{}' is on other UDIM tiles than '{}'",
                                           *map, out.layers.front().map));
            out.layers.push_back(std::move(files));
        }
    }
    // A stack without layers (bare base) still has its total thickness map: its tiles.
    const std::string total = (*patina)["total_thickness"].value<std::string>().value_or(
        "total_thickness");
    std::vector<fs::path> total_files;
    map_files(manifest, root, total, udims, total_files, out.width, out.height,
              out.strip_size_m);
    if (out.layers.empty())
        out.udims = udims;
    else if (udims != out.udims)
        fail(manifest, fmt::format("map '{}' is on other UDIM tiles than the layers", total));
    return out;
}

}  // namespace patina::texgen
