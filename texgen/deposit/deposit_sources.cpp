#include "texgen/deposit/deposit_sources.h"

#include "formats/toml_location.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <utility>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

    // One key=value of a source as read from either syntax, with where it was written.
    struct Field {
        std::string key;
        std::vector<double> numbers;
        std::string where; ///< "--source '...'" or "file:line:col"
    };

    struct KeySpec {
        const char* key;
        int count; ///< 1: a number, 3: a vector
        bool required;
    };

    const std::vector<KeySpec>& keys_of(DepositSource::Kind kind)
    {
        using K = DepositSource::Kind;
        static const std::vector<KeySpec> sphere = {
            {"center", 3, true}, {"radius", 1, true}, {"strength", 1, false}};
        static const std::vector<KeySpec> disc = {
            {"center", 3, true}, {"normal", 3, true}, {"radius", 1, true}, {"strength", 1, false}};
        static const std::vector<KeySpec> rectangle = {
            {"corner", 3, true}, {"edge1", 3, true}, {"edge2", 3, true}, {"strength", 1, false}};
        static const std::vector<KeySpec> directional = {
            {"direction", 3, true}, {"spread_deg", 1, false}, {"strength", 1, false}};
        switch (kind) {
        case K::Sphere:
            return sphere;
        case K::Disc:
            return disc;
        case K::Rectangle:
            return rectangle;
        case K::Directional:
            return directional;
        }
        return sphere;
    }

    const char* name_of(DepositSource::Kind kind)
    {
        using K = DepositSource::Kind;
        switch (kind) {
        case K::Sphere:
            return "sphere";
        case K::Disc:
            return "disc";
        case K::Rectangle:
            return "rectangle";
        case K::Directional:
            return "directional";
        }
        return "?";
    }

    DepositSource::Kind kind_of(const std::string& type, const std::string& where)
    {
        using K = DepositSource::Kind;
        for (K k : {K::Sphere, K::Disc, K::Rectangle, K::Directional})
            if (type == name_of(k))
                return k;
        throw std::runtime_error(fmt::format(
            "{}: unknown source type '{}' (known: sphere, disc, rectangle, directional)", where,
            type));
    }

    std::string key_list(const std::vector<KeySpec>& specs)
    {
        std::string s;
        for (const KeySpec& k : specs)
            s += (s.empty() ? "" : ", ") + std::string(k.key);
        return s;
    }

    // Check the fields against the type's keys and turn them into a source. `where` names the
    // source as a whole (for a missing key).
    DepositSource build_source(DepositSource::Kind kind, const std::vector<Field>& fields,
                               const std::string& where)
    {
        const std::vector<KeySpec>& specs = keys_of(kind);
        const char* type = name_of(kind);
        DepositSource s;
        s.kind = kind;
        std::vector<const Field*> found(specs.size(), nullptr);
        for (const Field& f : fields) {
            const auto spec = std::find_if(specs.begin(), specs.end(),
                                           [&](const KeySpec& k) { return f.key == k.key; });
            if (spec == specs.end())
                throw std::runtime_error(
                    fmt::format("{}: unknown key '{}' for a {} source (allowed: "
                                "{})",
                                f.where, f.key, type, key_list(specs)));
            const size_t i = static_cast<size_t>(spec - specs.begin());
            if (found[i])
                throw std::runtime_error(fmt::format("{}: key '{}' given twice", f.where, f.key));
            if (static_cast<int>(f.numbers.size()) != spec->count)
                throw std::runtime_error(fmt::format("{}: '{}' must be {}", f.where, f.key,
                                                     spec->count == 1
                                                         ? std::string("a number")
                                                         : std::string("3 numbers (x, y, z)")));
            for (double v : f.numbers)
                if (!std::isfinite(v))
                    throw std::runtime_error(fmt::format("{}: '{}' is not finite", f.where, f.key));
            found[i] = &f;
        }
        for (size_t i = 0; i < specs.size(); ++i)
            if (specs[i].required && !found[i])
                throw std::runtime_error(fmt::format("{}: a {} source needs '{}' (keys: {})", where,
                                                     type, specs[i].key, key_list(specs)));

        const auto field = [&](const char* key) -> const Field* {
            for (size_t i = 0; i < specs.size(); ++i)
                if (std::string(specs[i].key) == key)
                    return found[i];
            return nullptr;
        };
        const auto vec = [&](const char* key) {
            const Field* f = field(key);
            return Imath::V3f(static_cast<float>(f->numbers[0]), static_cast<float>(f->numbers[1]),
                              static_cast<float>(f->numbers[2]));
        };
        const auto number = [&](const char* key, float fallback) {
            const Field* f = field(key);
            return f ? static_cast<float>(f->numbers[0]) : fallback;
        };
        const auto require = [&](bool ok, const char* key, const std::string& what) {
            if (!ok)
                throw std::runtime_error(fmt::format("{}: '{}' {}", field(key)->where, key, what));
        };
        using K = DepositSource::Kind;
        s.strength = number("strength", 1.0f);
        if (field("strength"))
            require(s.strength >= 0.0f, "strength", "must be >= 0");
        if (kind == K::Sphere || kind == K::Disc) {
            s.center = vec("center");
            s.radius = number("radius", 0.0f);
            require(s.radius > 0.0f, "radius", "must be > 0");
        }
        if (kind == K::Disc) {
            const Imath::V3f n = vec("normal");
            require(n.length() > 0.0f, "normal", "must not be zero");
            s.normal = n.normalized();
        }
        if (kind == K::Rectangle) {
            s.corner = vec("corner");
            s.edge1 = vec("edge1");
            s.edge2 = vec("edge2");
            require(s.edge1.cross(s.edge2).length() > 0.0f, "edge2",
                    "must not be zero or parallel to edge1 (the rectangle has no area)");
        }
        if (kind == K::Directional) {
            const Imath::V3f d = vec("direction");
            require(d.length() > 0.0f, "direction", "must not be zero");
            s.direction = d.normalized();
            s.spread_deg = number("spread_deg", 0.0f);
            if (field("spread_deg"))
                require(s.spread_deg >= 0.0f && s.spread_deg < 90.0f, "spread_deg",
                        "must be in [0, 90)");
        }
        return s;
    }

    std::string vec_text(const Imath::V3f& v)
    {
        return fmt::format("{},{},{}", v.x, v.y, v.z);
    }

} // namespace

std::string DepositSource::describe() const
{
    std::string s = name_of(kind);
    switch (kind) {
    case Kind::Sphere:
        s += fmt::format(" center={} radius={}", vec_text(center), radius);
        break;
    case Kind::Disc:
        s += fmt::format(" center={} normal={} radius={}", vec_text(center), vec_text(normal),
                         radius);
        break;
    case Kind::Rectangle:
        s += fmt::format(" corner={} edge1={} edge2={}", vec_text(corner), vec_text(edge1),
                         vec_text(edge2));
        break;
    case Kind::Directional:
        s += fmt::format(" direction={} spread_deg={}", vec_text(direction), spread_deg);
        break;
    }
    return s + fmt::format(" strength={}", strength);
}

DepositSource parse_source_option(const std::string& text)
{
    const std::string where = fmt::format("--source '{}'", text);
    std::istringstream words(text);
    std::string type;
    if (!(words >> type))
        throw std::runtime_error(where + ": empty (expected e.g. 'sphere center=0,5,0 radius=1')");
    const DepositSource::Kind kind = kind_of(type, where);
    std::vector<Field> fields;
    for (std::string word; words >> word;) {
        const size_t eq = word.find('=');
        if (eq == std::string::npos || eq == 0)
            throw std::runtime_error(fmt::format("{}: '{}' is not key=value", where, word));
        Field f;
        f.key = word.substr(0, eq);
        f.where = where;
        std::string rest = word.substr(eq + 1);
        std::istringstream items(rest);
        for (std::string item; std::getline(items, item, ',');) {
            char* end = nullptr;
            errno = 0;
            const double v = std::strtod(item.c_str(), &end);
            if (item.empty() || end != item.c_str() + item.size() || errno == ERANGE)
                throw std::runtime_error(
                    fmt::format("{}: '{}' in '{}' is not a number", where, item, word));
            f.numbers.push_back(v);
        }
        if (rest.empty() || rest.back() == ',')
            throw std::runtime_error(fmt::format("{}: '{}' has an empty value", where, word));
        fields.push_back(std::move(f));
    }
    return build_source(kind, fields, where);
}

std::vector<DepositSource> load_sources_file(const fs::path& path)
{
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw std::runtime_error(fmt::format("sources file '{}' does not exist", path.string()));
    const toml::table root = formats::parse_toml_file(path);
    for (auto&& [key, node] : root)
        if (key.str() != "source")
            throw std::runtime_error(fmt::format("{}: unknown key '{}' (a sources file holds "
                                                 "[[source]] tables only)",
                                                 formats::toml_where(path, node.source().begin), key.str()));
    const toml::node* list = root.get("source");
    if (!list)
        throw std::runtime_error(fmt::format("{}: no [[source]] table", path.string()));
    const toml::array* tables = list->as_array();
    if (!tables)
        throw std::runtime_error(fmt::format("{}: 'source' must be an array of tables "
                                             "([[source]])",
                                             formats::toml_where(path, list->source().begin)));

    std::vector<DepositSource> sources;
    for (const toml::node& item : *tables) {
        const toml::table* t = item.as_table();
        const std::string where = formats::toml_where(path, item.source().begin);
        if (!t)
            throw std::runtime_error(
                fmt::format("{}: each source must be a table ([[source]])", where));
        const toml::node* type = t->get("type");
        if (!type)
            throw std::runtime_error(fmt::format(
                "{}: [[source]] needs 'type' (sphere, disc, rectangle or directional)", where));
        if (!type->is_string())
            throw std::runtime_error(
                fmt::format("{}: 'type' must be a string", formats::toml_where(path, type->source().begin)));
        const DepositSource::Kind kind =
            kind_of(**type->as_string(), formats::toml_where(path, type->source().begin));
        std::vector<Field> fields;
        for (auto&& [key, value] : *t) {
            if (key.str() == "type")
                continue;
            Field f;
            f.key = std::string(key.str());
            f.where = formats::toml_where(path, value.source().begin);
            if (value.is_number()) {
                f.numbers.push_back(*value.value<double>());
            } else if (const toml::array* a = value.as_array()) {
                for (const toml::node& e : *a) {
                    if (!e.is_number())
                        throw std::runtime_error(fmt::format("{}: '{}' must hold numbers",
                                                             formats::toml_where(path, e.source().begin), f.key));
                    f.numbers.push_back(*e.value<double>());
                }
            } else {
                throw std::runtime_error(fmt::format("{}: '{}' must be a number or an array of "
                                                     "numbers",
                                                     f.where, f.key));
            }
            fields.push_back(std::move(f));
        }
        sources.push_back(build_source(kind, fields, where));
    }
    if (sources.empty())
        throw std::runtime_error(fmt::format("{}: no [[source]] table", path.string()));
    return sources;
}

} // namespace patina::texgen
