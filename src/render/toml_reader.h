// Reading scene-file tables with messages that name the file, line and column, and strict
// key checking (a misspelt key is an error, never a silent default).
#pragma once

#include <Imath/ImathVec.h>
#include <fmt/format.h>
#include <toml++/toml.h>

#include "formats/toml_location.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <initializer_list>
#include <stdexcept>
#include <string>
#include <string_view>

namespace patina::render {

// Every message names the file and line: "<file>:<line>:<col>: <what>".
struct TomlReader {
    const std::filesystem::path& file;

    [[noreturn]] void fail(const toml::node* node, std::string_view what) const
    {
        formats::toml_fail(file, node, what);
    }

    // Unknown keys are errors: a misspelt setting must not silently fall back.
    void check_keys(const toml::table& t, std::string_view table,
                    std::initializer_list<std::string_view> allowed) const
    {
        for (auto&& [k, v] : t)
            if (std::find(allowed.begin(), allowed.end(), k.str()) == allowed.end()) {
                std::string list;
                for (auto a : allowed)
                    list += (list.empty() ? "" : ", ") + std::string(a);
                fail(&v, fmt::format("unknown key '{}' in [{}] (allowed: {})", k.str(), table, list));
            }
    }

    double number(const toml::table& t, std::string_view key, double def, double lo,
                  double hi, std::string_view table) const
    {
        const toml::node* n = t.get(key);
        if (!n)
            return def;
        if (!n->is_number())
            fail(n, fmt::format("[{}] {} must be a number", table, key));
        const double v = *n->value<double>();
        if (!(v >= lo && v <= hi))
            fail(n, fmt::format("[{}] {} = {} is outside [{}, {}]", table, key, v, lo, hi));
        return v;
    }

    int integer(const toml::table& t, std::string_view key, int def, int lo, int hi,
                std::string_view table) const
    {
        const toml::node* n = t.get(key);
        if (!n)
            return def;
        if (!n->is_integer())
            fail(n, fmt::format("[{}] {} must be an integer", table, key));
        const int64_t v = **n->as_integer();
        if (v < lo || v > hi)
            fail(n, fmt::format("[{}] {} = {} is outside [{}, {}]", table, key, v, lo, hi));
        return static_cast<int>(v);
    }

    bool boolean(const toml::table& t, std::string_view key, bool def, std::string_view table) const
    {
        const toml::node* n = t.get(key);
        if (!n)
            return def;
        if (!n->is_boolean())
            fail(n, fmt::format("[{}] {} must be true or false", table, key));
        return **n->as_boolean();
    }

    Imath::V3f vec3(const toml::table& t, std::string_view key, Imath::V3f def,
                    std::string_view table) const
    {
        const toml::node* n = t.get(key);
        if (!n)
            return def;
        const toml::array* a = n->as_array();
        if (!a || a->size() != 3)
            fail(n, fmt::format("[{}] {} must be an array of 3 numbers", table, key));
        Imath::V3f v;
        for (size_t i = 0; i < 3; ++i) {
            const toml::node* e = a->get(i);
            if (!e->is_number())
                fail(e, fmt::format("[{}] {} must be an array of 3 numbers", table, key));
            v[static_cast<int>(i)] = static_cast<float>(*e->value<double>());
            if (!std::isfinite(v[static_cast<int>(i)]))
                fail(e, fmt::format("[{}] {} is not finite", table, key));
        }
        return v;
    }

    std::string string(const toml::table& t, std::string_view key, std::string def,
                       std::string_view table) const
    {
        const toml::node* n = t.get(key);
        if (!n)
            return def;
        if (!n->is_string())
            fail(n, fmt::format("[{}] {} must be a string", table, key));
        return **n->as_string();
    }

    const toml::table* table(const toml::table& root, std::string_view key) const
    {
        const toml::node* n = root.get(key);
        if (n && !n->is_table())
            fail(n, fmt::format("'{}' must be a table ([{}])", key, key));
        return n ? n->as_table() : nullptr;
    }
};

}  // namespace patina::render
