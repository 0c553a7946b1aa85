#include "formats/texture_stack/texture_stack.h"

#include "formats/texture_stack/stack_format.h"
#include "formats/toml_location.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <sstream>
#include <stdexcept>
#include <tuple>

namespace patina::formats {

std::string name_part(std::string_view name)
{
    std::string s;
    for (char c : name)
        s += std::isalnum(static_cast<unsigned char>(c)) ? c : '_';
    return s;
}

namespace fs = std::filesystem;

namespace {

    constexpr std::string_view kUdimToken = "<UDIM>";

    // ---- typed reads with the value's location in every message ----

    std::string string_of(const fs::path& file, const toml::table& t, const char* key,
                          const std::string& context)
    {
        const toml::node* n = t.get(key);
        if (!n)
            toml_fail(file, &t, context + " has no '" + key + "'");
        const auto s = n->value<std::string>();
        if (!s || s->empty() || !n->is_string())
            toml_fail(file, n, context + ": '" + key + "' must be a non-empty string");
        return *s;
    }

    std::string optional_string(const fs::path& file, const toml::table& t, const char* key,
                                const std::string& context)
    {
        const toml::node* n = t.get(key);
        if (!n)
            return {};
        if (!n->is_string())
            toml_fail(file, n, context + ": '" + key + "' must be a string");
        return n->value<std::string>().value_or("");
    }

    double optional_number(const fs::path& file, const toml::table& t, const char* key,
                           const std::string& context, double fallback)
    {
        const toml::node* n = t.get(key);
        if (!n)
            return fallback;
        const auto v = n->value<double>();
        if (!v || !std::isfinite(*v))
            toml_fail(file, n, context + ": '" + key + "' must be a finite number");
        return *v;
    }

    /// An array of finite numbers >= 0 of the given size (any size when `size` is 0).
    std::vector<double> numbers_of(const fs::path& file, const toml::table& t, const char* key,
                                   const std::string& context, size_t size, bool required)
    {
        const toml::node* n = t.get(key);
        if (!n) {
            if (required)
                toml_fail(file, &t, context + " has no '" + key + "'");
            return {};
        }
        const toml::array* a = n->as_array();
        if (!a || a->empty())
            toml_fail(file, n, context + ": '" + key + "' must be an array of numbers");
        if (size && a->size() != size)
            toml_fail(file, n, context + ": '" + key + "' has " + std::to_string(a->size()) +
                                   " values for " + std::to_string(size) + " wavelengths");
        std::vector<double> out;
        out.reserve(a->size());
        for (const toml::node& v : *a) {
            const auto x = v.value<double>();
            if (!x || !std::isfinite(*x) || *x < 0.0)
                toml_fail(file, &v, context + ": '" + key + "' must hold finite numbers >= 0");
            out.push_back(*x);
        }
        return out;
    }

    std::vector<std::string> strings_of(const fs::path& file, const toml::table& t,
                                        const char* key, const std::string& context)
    {
        const toml::node* n = t.get(key);
        if (!n)
            return {};
        const toml::array* a = n->as_array();
        if (!a)
            toml_fail(file, n, context + ": '" + key + "' must be an array of strings");
        std::vector<std::string> out;
        for (const toml::node& v : *a) {
            const auto s = v.value<std::string>();
            if (!s || !v.is_string() || s->empty())
                toml_fail(file, &v, context + ": '" + key + "' must hold non-empty strings");
            out.push_back(*s);
        }
        return out;
    }

    StackMap map_from_toml(const fs::path& file, const std::string& name, const toml::node& node)
    {
        const std::string context = "[maps." + name + "]";
        const toml::table* t = node.as_table();
        if (!t)
            toml_fail(file, &node, context + " must be a table");
        StackMap m;
        m.name = name;
        m.domain = optional_string(file, *t, "domain", context);
        if (m.domain.empty())
            m.domain = "texel";
        if (m.domain != "texel" && m.domain != "vertex")
            toml_fail(file, t->get("domain"), context + ": 'domain' must be \"texel\" or \"vertex\"");
        if (t->contains("file")) {
            m.file = string_of(file, *t, "file", context);
        } else if (t->contains("pattern")) {
            m.pattern = string_of(file, *t, "pattern", context);
            if (m.pattern.find(kUdimToken) == std::string::npos)
                toml_fail(file, t->get("pattern"), context + ": 'pattern' has no <UDIM>");
            const toml::array* tiles = (*t)["tiles"].as_array();
            if (!tiles || tiles->empty())
                toml_fail(file, t->contains("tiles") ? t->get("tiles") : t,
                          context + ": a 'pattern' needs 'tiles', an array of UDIM numbers");
            for (const toml::node& v : *tiles) {
                const auto udim = v.value<int64_t>();
                if (!udim || !v.is_integer() || *udim < 1001 || *udim > 9999)
                    toml_fail(file, &v, context + ": 'tiles' must hold UDIM numbers 1001-9999");
                m.tiles.push_back(static_cast<int>(*udim));
            }
        } else {
            toml_fail(file, t, context + " has neither 'file' nor 'pattern'");
        }
        m.channels = strings_of(file, *t, "channels", context);
        m.coverage = optional_string(file, *t, "coverage", context);
        if (!m.coverage.empty() && m.channel_index(m.coverage) < 0)
            toml_fail(file, t->get("coverage"),
                      context + ": coverage channel '" + m.coverage + "' is not in 'channels'");
        m.units = optional_string(file, *t, "units", context);
        if (t->contains("colorspace"))
            m.colorspace = optional_string(file, *t, "colorspace", context);
        m.baker = optional_string(file, *t, "baker", context);
        m.description = optional_string(file, *t, "description", context);
        if (const toml::node* r = t->get("resolution")) {
            const toml::array* a = r->as_array();
            const auto w = a && a->size() == 2 ? a->get(0)->value<int64_t>() : std::nullopt;
            const auto h = a && a->size() == 2 ? a->get(1)->value<int64_t>() : std::nullopt;
            if (!w || !h || *w < 1 || *h < 1 || *w > (1 << 20) || *h > (1 << 20))
                toml_fail(file, r, context + ": 'resolution' must be [width, height] in texels");
            m.width = static_cast<int>(*w);
            m.height = static_cast<int>(*h);
        }
        if (const toml::node* p = t->get("parameters")) {
            if (!p->is_table())
                toml_fail(file, p, context + ": 'parameters' must be a table");
            m.parameters = *p->as_table();
        }
        return m;
    }

    /// A layer's `channel`: an index into its map's `channels` or one of their names.
    void channel_of(const fs::path& file, const toml::node* c, const StackMap& map,
                    const std::string& context, PatinaLayer& layer)
    {
        if (!c) {
            layer.channel_index = 0;
            layer.channel = map.channels.empty() ? "thickness" : map.channels.front();
            return;
        }
        if (const auto index = c->value<int64_t>(); index && c->is_integer()) {
            const int64_t count = static_cast<int64_t>(map.channels.size());
            if (*index < 0 || (count ? *index >= count : *index > 0))
                toml_fail(file, c,
                          context + ": 'channel' " + std::to_string(*index) +
                              " is not an index into map '" + map.name + "''s " +
                              std::to_string(count) + " channels");
            layer.channel_index = static_cast<int>(*index);
            layer.channel = count ? map.channels[static_cast<size_t>(*index)] : "thickness";
            return;
        }
        const auto name = c->value<std::string>();
        if (!name || !c->is_string())
            toml_fail(file, c, context + ": 'channel' must be an index or a channel name");
        const int index = map.channel_index(*name);
        if (index < 0)
            toml_fail(file, c, context + ": channel '" + *name + "' is not in map '" + map.name +
                                   "''s 'channels'");
        layer.channel_index = index;
        layer.channel = *name;
    }

    void require_files(const fs::path& manifest, const toml::node* at, const StackMap& map,
                       const std::string& context)
    {
        for (const fs::path& f : map.files(manifest.parent_path()))
            if (std::error_code ec; !fs::is_regular_file(f, ec))
                toml_fail(manifest, at,
                          context + ": map '" + map.name + "': file '" + f.string() +
                              "' does not exist");
    }

    PatinaTable patina_from_toml(const fs::path& file, const toml::table& patina,
                                 const std::map<std::string, StackMap>& maps)
    {
        PatinaTable p;
        p.script = optional_string(file, patina, "script", "[patina]");
        p.time_years = optional_number(file, patina, "time_years", "[patina]", 0.0);
        p.base = string_of(file, patina, "base", "[patina]");
        if (patina.contains("thickness_units"))
            p.thickness_units = optional_string(file, patina, "thickness_units", "[patina]");
        if (p.thickness_units != "um")
            toml_fail(file, patina.get("thickness_units"),
                      "[patina] thickness_units must be \"um\"");
        if (patina.contains("total_thickness"))
            p.total_thickness = string_of(file, patina, "total_thickness", "[patina]");
        p.preview = optional_string(file, patina, "preview", "[patina]");

        const toml::table* materials = patina["materials"].as_table();
        if (!materials)
            toml_fail(file, &patina,
                      "[patina] has no [patina.materials] table (written by patina-texgen 0.2 "
                      "and later: run the patina script again)");
        auto need_material = [&](const std::string& name, const toml::node* at) {
            if (p.materials.count(name))
                return;
            const toml::table* m = (*materials)[name].as_table();
            if (!m)
                toml_fail(file, at,
                          "material '" + name + "' has no [patina.materials.\"" + name +
                              "\"] table");
            p.materials.emplace(name, material_from_toml(file, name, *m));
        };
        need_material(p.base, patina.get("base"));

        if (const toml::node* layers_node = patina.get("layers")) {
            const toml::array* layers = layers_node->as_array();
            if (!layers)
                toml_fail(file, layers_node, "[patina] 'layers' must be an array of tables");
            for (size_t i = 0; i < layers->size(); ++i) {
                const std::string context = "layer " + std::to_string(i + 1);
                const toml::table* l = layers->get(i)->as_table();
                if (!l)
                    toml_fail(file, layers->get(i), context + " must be a table");
                PatinaLayer layer;
                layer.material = string_of(file, *l, "material", context);
                need_material(layer.material, l->get("material"));
                if (p.materials.at(layer.material).metal)
                    toml_fail(file, l->get("material"),
                              context + ": the metal '" + layer.material + "' cannot be a layer");
                layer.map = string_of(file, *l, "map", context);
                const auto map = maps.find(layer.map);
                if (map == maps.end())
                    toml_fail(file, l->get("map"),
                              context + ": map '" + layer.map + "' has no [maps." + layer.map +
                                  "] entry");
                if (map->second.domain != "texel")
                    toml_fail(file, l->get("map"),
                              context + ": map '" + layer.map + "' is not a texel map");
                channel_of(file, l->get("channel"), map->second, context, layer);
                require_files(file, l->get("map"), map->second, context);
                layer.layer_map = optional_string(file, *l, "layer_map", context);
                if (!layer.layer_map.empty()) {
                    const auto single = maps.find(layer.layer_map);
                    if (single == maps.end())
                        toml_fail(file, l->get("layer_map"),
                                  context + ": map '" + layer.layer_map + "' has no [maps." +
                                      layer.layer_map + "] entry");
                    require_files(file, l->get("layer_map"), single->second, context);
                }
                layer.made_by = optional_string(file, *l, "made_by", context);
                layer.mean_um = optional_number(file, *l, "mean_um", context, 0.0);
                layer.max_um = optional_number(file, *l, "max_um", context, 0.0);
                layer.coverage = optional_number(file, *l, "coverage", context, 0.0);
                if (!p.layers.empty() &&
                    maps.at(p.layers.front().map).udims() != map->second.udims())
                    toml_fail(file, l->get("map"),
                              context + ": map '" + layer.map + "' is on other UDIM tiles than '" +
                                  p.layers.front().map + "'");
                p.layers.push_back(std::move(layer));
            }
        }
        return p;
    }

    toml::array array_of(const std::vector<double>& v)
    {
        toml::array a;
        for (double x : v)
            a.push_back(x);
        return a;
    }

    std::string shortest(double x)
    {
        std::ostringstream s;
        s << x;
        return s.str();
    }

}  // namespace

std::vector<int> StackMap::udims() const
{
    return pattern.empty() ? std::vector<int>{1001} : tiles;
}

std::vector<fs::path> StackMap::files(const fs::path& dir) const
{
    if (pattern.empty())
        return {(dir / file).lexically_normal()};
    const size_t at = pattern.find(kUdimToken);
    std::vector<fs::path> out;
    for (int udim : tiles)
        out.push_back((dir / (pattern.substr(0, at) + std::to_string(udim) +
                              pattern.substr(at + kUdimToken.size())))
                          .lexically_normal());
    return out;
}

int StackMap::channel_index(std::string_view channel) const
{
    for (size_t i = 0; i < channels.size(); ++i)
        if (channels[i] == channel)
            return static_cast<int>(i);
    return -1;
}

const StackMap& TextureStack::map(const std::string& name) const
{
    const auto it = maps.find(name);
    if (it == maps.end())
        throw std::runtime_error(manifest.string() + ": map '" + name + "' is not listed in [maps]");
    return it->second;
}

namespace {

    constexpr const char* kNormalConvention =
        "tangent space, OpenGL (+Y = +v, green up), encoded n * 0.5 + 0.5";
    constexpr const char* kTwoLobe = "glTF 2.0 metallic-roughness + KHR_materials_clearcoat";

    FlattenTable flatten_from_toml(const fs::path& file, const toml::table& t)
    {
        toml_check_keys(file, t, "flatten.",
                        {"stack", "color_space", "diffuse", "height", "normal",
                         "normal_convention", "texel_size_m", "normal_scale", "two_lobe",
                         "gltf_target", "base_color", "metallic_roughness", "clearcoat",
                         "interfaces"});
        // The typed reads every table of the manifest uses (top of this file).
        FlattenTable f;
        f.stack = optional_string(file, t, "stack", "[flatten]");
        f.color_space = optional_string(file, t, "color_space", "[flatten]");
        f.texel_size_m = optional_number(file, t, "texel_size_m", "[flatten]", 0.0);
        f.normal_scale = optional_number(file, t, "normal_scale", "[flatten]", 1.0);
        f.gltf_target = optional_string(file, t, "gltf_target", "[flatten]");
        if (const toml::node* n = t.get("interfaces")) {
            const toml::array* a = n->as_array();
            if (!a)
                toml_fail(file, n, "[flatten] 'interfaces' must be an array of tables");
            for (size_t k = 0; k < a->size(); ++k) {
                const std::string context = "[flatten] interface " + std::to_string(k + 1);
                const toml::table* i = a->get(k)->as_table();
                if (!i)
                    toml_fail(file, a->get(k), context + " must be a table");
                f.interfaces.push_back({string_of(file, *i, "specular", context),
                                        string_of(file, *i, "roughness", context)});
            }
        }
        return f;
    }

}  // namespace

TextureStack read_texture_stack(const fs::path& path)
{
    std::error_code ec;
    fs::path manifest = path;
    if (fs::is_directory(path, ec)) {
        manifest = path / kStackManifest;
        if (!fs::exists(manifest, ec) && fs::exists(path / "series.toml", ec))
            throw std::runtime_error(path.string() +
                                     ": a time series (series.toml), not one stack: name a step "
                                     "folder (e.g. t30) or its stack.toml");
    }
    if (!fs::is_regular_file(manifest, ec))
        throw std::runtime_error(manifest.string() +
                                 ": no such file (expected a stack folder or its stack.toml)");

    const toml::table root = parse_toml_file(manifest);
    check_stack_format(manifest, root);
    TextureStack stack;
    stack.manifest = manifest;
    stack.format = static_cast<int>(root["stack"]["format"].value<int64_t>().value_or(1));
    stack.generator = root["stack"]["generator"].value<std::string>().value_or("");
    if (const toml::node* maps = root.get("maps")) {
        if (!maps->is_table())
            toml_fail(manifest, maps, "'maps' must be a table of maps");
        for (const auto& [name, entry] : *maps->as_table())
            stack.maps.emplace(std::string(name.str()),
                               map_from_toml(manifest, std::string(name.str()), entry));
    }
    if (const toml::node* patina = root.get("patina")) {
        if (!patina->is_table())
            toml_fail(manifest, patina, "'patina' must be a table");
        stack.patina = patina_from_toml(manifest, *patina->as_table(), stack.maps);
    }
    if (const toml::node* flatten = root.get("flatten")) {
        if (!flatten->is_table())
            toml_fail(manifest, flatten, "'flatten' must be a table");
        stack.flatten = flatten_from_toml(manifest, *flatten->as_table());
    }
    return stack;
}

toml::table to_toml(const FlattenTable& f)
{
    toml::array interfaces;
    for (const FlattenInterface& i : f.interfaces)
        interfaces.push_back(toml::table{{"specular", i.specular}, {"roughness", i.roughness}});
    return toml::table{
        {"stack", f.stack},
        {"color_space", f.color_space},
        {"diffuse", kDiffuseAlbedoMap},
        {"height", kHeightMap},
        {"normal", kNormalMap},
        {"normal_convention", kNormalConvention},
        {"texel_size_m", f.texel_size_m},
        {"normal_scale", f.normal_scale},
        {"two_lobe", kTwoLobe},
        {"gltf_target", f.gltf_target},
        {"base_color", kGltfBaseColorMap},
        {"metallic_roughness", kGltfMetallicRoughnessMap},
        {"clearcoat", kGltfClearcoatMap},
        {"interfaces", std::move(interfaces)}};
}

StackSeries read_stack_series(const fs::path& path)
{
    std::error_code ec;
    const fs::path manifest = fs::is_directory(path, ec) ? path / kSeriesManifest : path;
    if (!fs::is_regular_file(manifest, ec))
        throw std::runtime_error(manifest.string() + ": no such file (expected a time series "
                                                     "folder written by patina-texgen patina "
                                                     "--times, or its series.toml)");
    const toml::table root = parse_toml_file(manifest);
    const toml::table* series = root["series"].as_table();
    if (!series)
        toml_fail(manifest, &root, "no [series] table");
    StackSeries out;
    out.manifest = manifest;
    out.script = optional_string(manifest, *series, "script", "[series]");
    const toml::array* steps = (*series)["steps"].as_array();
    if (!steps || steps->empty())
        toml_fail(manifest, series->contains("steps") ? series->get("steps") : series,
                  "[series] 'steps' must be a non-empty array of { time_years, folder }");
    for (size_t i = 0; i < steps->size(); ++i) {
        const std::string context = "step " + std::to_string(i + 1);
        const toml::table* t = steps->get(i)->as_table();
        if (!t)
            toml_fail(manifest, steps->get(i), context + " must be a table");
        SeriesStep step;
        step.time_years = optional_number(manifest, *t, "time_years", context, -1.0);
        step.folder = string_of(manifest, *t, "folder", context);
        if (!(step.time_years >= 0.0))
            toml_fail(manifest, t, context + " needs 'time_years' >= 0");
        if (!out.steps.empty() && !(step.time_years > out.steps.back().time_years))
            toml_fail(manifest, t->get("time_years"), context + ": times must ascend");
        if (!fs::is_directory(manifest.parent_path() / step.folder, ec))
            toml_fail(manifest, t->get("folder"),
                      context + ": folder '" + step.folder + "' does not exist");
        out.steps.push_back(std::move(step));
    }
    return out;
}

std::string series_step_folder(double time_years, double last_years)
{
    const int digits = static_cast<int>(std::to_string(static_cast<long long>(last_years)).size());
    char name[64];
    if (time_years == std::floor(time_years))
        std::snprintf(name, sizeof name, "t%0*lld", digits, static_cast<long long>(time_years));
    else
        std::snprintf(name, sizeof name, "t%0*.3f", digits + 4, time_years);
    return name;
}

std::string stack_series_text(const StackSeries& series)
{
    toml::array steps;
    for (const SeriesStep& s : series.steps)
        steps.push_back(toml::table{{"time_years", s.time_years}, {"folder", s.folder}});
    const toml::table root{
        {"series", toml::table{{"script", series.script}, {"steps", std::move(steps)}}}};
    std::ostringstream text;
    text << "# The time series written by patina-texgen patina: one stack per step.\n"
         << root << "\n";
    return text.str();
}

const PatinaTable& patina_of(const TextureStack& stack)
{
    if (!stack.patina)
        throw std::runtime_error(stack.manifest.string() +
                                 ": no [patina] table (not a stack written by patina-texgen "
                                 "patina)");
    return *stack.patina;
}

MaterialOptics material_from_toml(const fs::path& file, const std::string& name,
                                  const toml::table& t)
{
    const std::string context = "material '" + name + "'";
    MaterialOptics m;
    m.name = name;
    m.description = optional_string(file, t, "description", context);
    if (const toml::node* metal = t.get("metal")) {
        const auto b = metal->value<bool>();
        if (!b)
            toml_fail(file, metal, context + ": 'metal' must be true or false");
        m.metal = *b;
    }
    m.lambda_nm = numbers_of(file, t, "wavelengths_nm", context, 0, true);
    for (size_t i = 1; i < m.lambda_nm.size(); ++i)
        if (!(m.lambda_nm[i] > m.lambda_nm[i - 1]))
            toml_fail(file, t.get("wavelengths_nm"),
                      context + ": 'wavelengths_nm' must increase strictly");
    const size_t count = m.lambda_nm.size();
    if (m.metal) {
        m.n = numbers_of(file, t, "n", context, count, true);
        m.k = numbers_of(file, t, "k", context, count, true);
        for (size_t i = 0; i < count; ++i)
            if (m.n[i] == 0.0 && m.k[i] == 0.0)
                toml_fail(file, t.get("n"),
                          context + ": n + ik vanishes at " + shortest(m.lambda_nm[i]) + " nm");
    } else {
        m.absorption_per_um = numbers_of(file, t, "absorption_per_um", context, count, true);
        m.scattering_per_um = numbers_of(file, t, "scattering_per_um", context, count, true);
    }
    m.specular = numbers_of(file, t, "specular", context, count, !m.metal);
    for (double s : m.specular)
        if (s > 1.0)
            toml_fail(file, t.get("specular"), context + ": 'specular' must lie in [0, 1]");
    const toml::node* r = t.get("roughness");
    if (!r)
        toml_fail(file, &t, context + " has no 'roughness'");
    const auto rv = r->value<double>();
    if (!rv || !(*rv >= 0.0 && *rv <= 1.0))
        toml_fail(file, r, context + ": 'roughness' must be a number in [0, 1]");
    m.roughness = *rv;
    return m;
}

toml::table to_toml(const StackMap& map)
{
    toml::table t;
    if (map.pattern.empty()) {
        t.insert_or_assign("file", map.file);
    } else {
        t.insert_or_assign("pattern", map.pattern);
        toml::array tiles;
        for (int udim : map.tiles)
            tiles.push_back(static_cast<int64_t>(udim));
        t.insert_or_assign("tiles", std::move(tiles));
    }
    t.insert_or_assign("domain", map.domain);
    toml::array channels;
    for (const std::string& c : map.channels)
        channels.push_back(c);
    t.insert_or_assign("channels", std::move(channels));
    if (!map.coverage.empty())
        t.insert_or_assign("coverage", map.coverage);
    t.insert_or_assign("units", map.units);
    t.insert_or_assign("colorspace", map.colorspace);
    t.insert_or_assign("baker", map.baker);
    t.insert_or_assign("description", map.description);
    if (map.width > 0 && map.height > 0)
        t.insert_or_assign("resolution", toml::array{static_cast<int64_t>(map.width),
                                                     static_cast<int64_t>(map.height)});
    t.insert_or_assign("parameters", map.parameters);
    return t;
}

toml::table to_toml(const MaterialOptics& m)
{
    toml::table t;
    if (!m.description.empty())
        t.insert_or_assign("description", m.description);
    t.insert_or_assign("metal", m.metal);
    t.insert_or_assign("roughness", m.roughness);
    t.insert_or_assign("wavelengths_nm", array_of(m.lambda_nm));
    if (m.metal) {
        t.insert_or_assign("n", array_of(m.n));
        t.insert_or_assign("k", array_of(m.k));
    } else {
        t.insert_or_assign("absorption_per_um", array_of(m.absorption_per_um));
        t.insert_or_assign("scattering_per_um", array_of(m.scattering_per_um));
    }
    if (!m.specular.empty())
        t.insert_or_assign("specular", array_of(m.specular));
    return t;
}

toml::table to_toml(const PatinaTable& p)
{
    toml::table t;
    t.insert_or_assign("script", p.script);
    t.insert_or_assign("time_years", p.time_years);
    t.insert_or_assign("base", p.base);
    t.insert_or_assign("thickness_units", p.thickness_units);
    t.insert_or_assign("total_thickness", p.total_thickness);
    if (!p.preview.empty())
        t.insert_or_assign("preview", p.preview);
    toml::array layers;
    for (const PatinaLayer& l : p.layers) {
        toml::table entry;
        entry.insert_or_assign("material", l.material);
        entry.insert_or_assign("map", l.map);
        entry.insert_or_assign("channel", l.channel);
        if (!l.layer_map.empty())
            entry.insert_or_assign("layer_map", l.layer_map);
        entry.insert_or_assign("made_by", l.made_by);
        entry.insert_or_assign("mean_um", l.mean_um);
        entry.insert_or_assign("max_um", l.max_um);
        entry.insert_or_assign("coverage", l.coverage);
        layers.push_back(std::move(entry));
    }
    t.insert_or_assign("layers", std::move(layers));
    toml::table materials;
    for (const auto& [name, m] : p.materials)
        materials.insert_or_assign(name, to_toml(m));
    t.insert_or_assign("materials", std::move(materials));
    return t;
}

std::string optics_difference(const MaterialOptics& a, const MaterialOptics& b, double relative)
{
    auto differ = [&](double x, double y) {
        return std::abs(x - y) > relative * std::max({std::abs(x), std::abs(y), 1e-12});
    };
    if (a.metal != b.metal)
        return a.metal ? "a metal against a layer material" : "a layer material against a metal";
    if (differ(a.roughness, b.roughness))
        return "roughness " + shortest(a.roughness) + " against " + shortest(b.roughness);
    if (a.lambda_nm.size() != b.lambda_nm.size())
        return std::to_string(a.lambda_nm.size()) + " wavelengths against " +
               std::to_string(b.lambda_nm.size());
    auto compare = [&](const char* key, const std::vector<double>& x,
                       const std::vector<double>& y) -> std::string {
        if (x.size() != y.size())
            return std::string(key) + ": " + std::to_string(x.size()) + " values against " +
                   std::to_string(y.size());
        for (size_t i = 0; i < x.size(); ++i)
            if (differ(x[i], y[i]))
                return std::string(key) + " at " + shortest(a.lambda_nm[i]) + " nm: " +
                       shortest(x[i]) + " against " + shortest(y[i]);
        return {};
    };
    for (const auto& [key, x, y] :
         {std::tuple{"wavelengths_nm", &a.lambda_nm, &b.lambda_nm},
          std::tuple{"absorption_per_um", &a.absorption_per_um, &b.absorption_per_um},
          std::tuple{"scattering_per_um", &a.scattering_per_um, &b.scattering_per_um},
          std::tuple{"specular", &a.specular, &b.specular}, std::tuple{"n", &a.n, &b.n},
          std::tuple{"k", &a.k, &b.k}})
        if (std::string d = compare(key, *x, *y); !d.empty())
            return d;
    return {};
}

}  // namespace patina::formats
