// Where a value sits in a TOML file, for error messages in the one form every reader of
// Patina's TOML files uses (scenes, shader parameters, texture-stack manifests, fade
// stacks, material libraries): "<file>:<line>:<column>: <what>". Header-only: plugins
// include it as they include the other readers of the file-format library.
#pragma once

#include <toml++/toml.h>

#include <filesystem>
#include <stdexcept>
#include <string>
#include <initializer_list>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace patina::formats {

/// "file:line:column" of a position; just "file" when toml++ knows no position.
inline std::string toml_where(const std::filesystem::path& file, const toml::source_position& at)
{
    // Appended piece by piece: ":" + std::to_string(...) trips a false -Wrestrict of GCC 12.
    std::string out = file.string();
    if (at) {
        out += ':';
        out += std::to_string(at.line);
        out += ':';
        out += std::to_string(at.column);
    }
    return out;
}

/// "file:line:column" of a node (where its value begins); "file" for a null node.
inline std::string toml_where(const std::filesystem::path& file, const toml::node* node)
{
    return node ? toml_where(file, node->source().begin) : file.string();
}

/// Throws std::runtime_error("file:line:column: what").
[[noreturn]] inline void toml_fail(const std::filesystem::path& file, const toml::node* node,
                                   std::string_view what)
{
    throw std::runtime_error(toml_where(file, node) + ": " + std::string(what));
}

/// Throws std::runtime_error("file:line:column: <prefix><key>: unknown key (known: a, b)")
/// for the first key of `table` not in `allowed` (a typo must not pass as a default).
inline void toml_check_keys(const std::filesystem::path& file, const toml::table& table,
                            const std::string& prefix, std::span<const char* const> allowed)
{
    for (const auto& [k, v] : table) {
        const std::string_view key = k.str();
        bool known = false;
        for (const char* a : allowed)
            known |= key == a;
        if (known)
            continue;
        std::string list;
        for (const char* a : allowed) {
            if (!list.empty())
                list += ", ";
            list += a;
        }
        toml_fail(file, &v, prefix + std::string(key) + ": unknown key (known: " + list + ")");
    }
}
inline void toml_check_keys(const std::filesystem::path& file, const toml::table& table,
                            const std::string& prefix, std::initializer_list<const char*> allowed)
{
    toml_check_keys(file, table, prefix, std::span<const char* const>(allowed.begin(), allowed.size()));
}

/// The value of `key` in `table` as exactly a T (std::string, int64_t, double, bool);
/// throws "file:line:column: <prefix><key>: missing" or "...: wrong type" naming where.
template <class T>
T toml_value(const std::filesystem::path& file, const toml::table& table, const char* key,
             const std::string& prefix)
{
    const toml::node* node = table.get(key);
    const std::optional<T> value = node ? node->value_exact<T>() : std::nullopt;
    if (!value)
        toml_fail(file, node ? node : &table,
                  prefix + key + (node ? ": wrong type" : ": missing"));
    return *value;
}

/// `text` parsed (`source` names it in errors), or std::runtime_error("source:line:column:
/// <toml++'s description>").
inline toml::table parse_toml_text(std::string_view text, const std::filesystem::path& source)
{
    try {
        return toml::parse(text, source.string());
    } catch (const toml::parse_error& e) {
        throw std::runtime_error(toml_where(source, e.source().begin) + ": " +
                                 std::string(e.description()));
    }
}

/// The tables of the array of tables `key` of `root` ([[key]]), in order; throws
/// "file:line:column: no [[key]]" when there is none and "...: a [[key]] that is not a
/// table" for an item of another type.
inline std::vector<const toml::table*> toml_table_array(const std::filesystem::path& file,
                                                        const toml::table& root,
                                                        const char* key)
{
    const toml::node* node = root.get(key);
    const toml::array* array = node ? node->as_array() : nullptr;
    const std::string name = std::string("[[") + key + "]]";
    if (!array || array->empty())
        toml_fail(file, node, "no " + name);
    std::vector<const toml::table*> out;
    for (const toml::node& item : *array) {
        const toml::table* t = item.as_table();
        if (!t)
            toml_fail(file, &item, "a " + name + " that is not a table");
        out.push_back(t);
    }
    return out;
}

/// The parsed file, or std::runtime_error("file:line:column: <toml++'s description>").
inline toml::table parse_toml_file(const std::filesystem::path& file)
{
    try {
        return toml::parse_file(file.string());
    } catch (const toml::parse_error& e) {
        throw std::runtime_error(toml_where(file, e.source().begin) + ": " +
                                 std::string(e.description()));
    }
}

}  // namespace patina::formats
