#include "stack_file.h"

#include "formats/stack_format.h"
#include "formats/toml_location.h"

#include <toml++/toml.h>

#include <cmath>
#include <stdexcept>
#include <string>

namespace patina::layered {

namespace fs = std::filesystem;

namespace {

    using formats::toml_fail;

    std::string string_of(const fs::path& file, const toml::table& t, const char* key,
                          const std::string& context)
    {
        const toml::node* n = t.get(key);
        if (!n)
            toml_fail(file, &t, context + " has no '" + key + "'");
        const auto s = n->value<std::string>();
        if (!s || s->empty())
            toml_fail(file, n, context + ": '" + key + "' must be a non-empty string");
        return *s;
    }

    /// An array of finite numbers of the given size (any size when `size` is 0).
    std::vector<float> numbers_of(const fs::path& file, const toml::table& t, const char* key,
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
        std::vector<float> out;
        for (const toml::node& v : *a) {
            const auto x = v.value<double>();
            if (!x || !std::isfinite(*x) || *x < 0.0)
                toml_fail(file, &v, context + ": '" + key + "' must hold finite numbers >= 0");
            out.push_back(static_cast<float>(*x));
        }
        return out;
    }

    MaterialOptics material_of(const fs::path& file, const std::string& name,
                               const toml::table& t)
    {
        const std::string context = "material '" + name + "'";
        MaterialOptics m;
        m.name = name;
        if (const toml::node* metal = t.get("metal")) {
            const auto b = metal->value<bool>();
            if (!b)
                toml_fail(file, &*metal, context + ": 'metal' must be true or false");
            m.metal = *b;
        }
        m.lambda_nm = numbers_of(file, t, "wavelengths_nm", context, 0, true);
        for (size_t i = 1; i < m.lambda_nm.size(); ++i)
            if (!(m.lambda_nm[i] > m.lambda_nm[i - 1]))
                toml_fail(file, &*t.get("wavelengths_nm"),
                     context + ": 'wavelengths_nm' must increase strictly");
        const size_t count = m.lambda_nm.size();
        if (m.metal) {
            m.n = numbers_of(file, t, "n", context, count, true);
            m.k = numbers_of(file, t, "k", context, count, true);
            for (size_t i = 0; i < count; ++i)
                if (m.n[i] == 0.0f && m.k[i] == 0.0f)
                    toml_fail(file, &*t.get("n"), context + ": n + ik vanishes at " +
                                                std::to_string(m.lambda_nm[i]) + " nm");
        } else {
            m.absorption_per_um = numbers_of(file, t, "absorption_per_um", context, count, true);
            m.scattering_per_um = numbers_of(file, t, "scattering_per_um", context, count, true);
        }
        m.specular = numbers_of(file, t, "specular", context, count, !m.metal);
        for (float s : m.specular)
            if (s > 1.0f)
                toml_fail(file, &*t.get("specular"), context + ": 'specular' must lie in [0, 1]");
        const toml::node* r = t.get("roughness");
        if (!r)
            toml_fail(file, &t, context + " has no 'roughness'");
        const auto rv = r->value<double>();
        if (!rv || !(*rv >= 0.0 && *rv <= 1.0))
            toml_fail(file, &*r, context + ": 'roughness' must be a number in [0, 1]");
        m.roughness = static_cast<float>(*rv);
        return m;
    }

    /// A layer's `channel`: an index >= 0 or a name from its map's `channels` list.
    int channel_of(const fs::path& file, const toml::node& c, const toml::table& map,
                   const std::string& context)
    {
        if (const auto index = c.value<int64_t>()) {
            if (*index < 0 || *index > 1023)
                toml_fail(file, &c, context + ": 'channel' must be an index in [0, 1023]");
            return static_cast<int>(*index);
        }
        const auto name = c.value<std::string>();
        if (!name)
            toml_fail(file, &c, context + ": 'channel' must be an index or a channel name");
        if (const toml::array* names = map["channels"].as_array())
            for (size_t i = 0; i < names->size(); ++i)
                if (names->get(i)->value<std::string>() == *name)
                    return static_cast<int>(i);
        toml_fail(file, &c, context + ": channel '" + *name + "' is not in its map's 'channels'");
    }

}  // namespace

StackFile read_stack_file(const fs::path& path)
{
    StackFile stack;
    stack.path = path;
    const toml::table root = formats::parse_toml_file(path);
    formats::check_stack_format(path, root);
    const toml::table* patina = root["patina"].as_table();
    if (!patina)
        throw std::runtime_error(path.string() +
                                 ": no [patina] table (not a stack written by patina-texgen "
                                 "patina)");
    stack.base = string_of(path, *patina, "base", "[patina]");
    const toml::table* materials = (*patina)["materials"].as_table();
    if (!materials)
        toml_fail(path, patina,
             "[patina] has no [patina.materials] table (written by patina-texgen 0.2 and "
             "later: run the patina script again)");
    const toml::table* maps = root["maps"].as_table();

    auto need_material = [&](const std::string& name, const toml::node& at) {
        if (stack.materials.count(name))
            return;
        const toml::table* m = (*materials)[name].as_table();
        if (!m)
            toml_fail(path, &at, "material '" + name + "' has no [patina.materials.\"" + name +
                               "\"] table");
        stack.materials.emplace(name, material_of(path, name, *m));
    };
    need_material(stack.base, *patina->get("base"));
    if (!stack.materials.at(stack.base).metal &&
        stack.materials.at(stack.base).absorption_per_um.empty())
        toml_fail(path, &*patina->get("base"), "the base has no optical description");

    if (const toml::node* layers_node = patina->get("layers")) {
        const toml::array* layers = layers_node->as_array();
        if (!layers)
            toml_fail(path, &*layers_node, "[patina] 'layers' must be an array of tables");
        for (size_t i = 0; i < layers->size(); ++i) {
            const toml::table* l = layers->get(i)->as_table();
            const std::string context = "layer " + std::to_string(i + 1);
            if (!l)
                toml_fail(path, &*layers->get(i), context + " must be a table");
            StackLayer layer;
            layer.material = string_of(path, *l, "material", context);
            need_material(layer.material, *l->get("material"));
            if (stack.materials.at(layer.material).metal)
                toml_fail(path, &*l->get("material"),
                     context + ": the metal '" + layer.material + "' cannot be a layer");
            const std::string map = string_of(path, *l, "map", context);
            const toml::table* entry = maps ? (*maps)[map].as_table() : nullptr;
            if (!entry)
                toml_fail(path, &*l->get("map"), context + ": map '" + map + "' has no [maps." +
                                               map + "] entry");
            const char* key = entry->contains("file") ? "file" : "pattern";
            const fs::path file = string_of(path, *entry, key, "[maps." + map + "]");
            layer.map_file = (path.parent_path() / file).lexically_normal();
            if (const toml::node* c = l->get("channel"))
                layer.channel = channel_of(path, *c, *entry, context);
            stack.layers.push_back(std::move(layer));
        }
    }
    return stack;
}

}  // namespace patina::layered
