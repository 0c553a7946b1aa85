// The version of the texture-stack manifest's layout, stack.toml `[stack] format`
// (docs/file-formats.md), and the check every reader makes before it reads anything else.
#pragma once

#include "formats/toml_location.h"

#include <toml++/toml.h>

#include <cstdint>
#include <filesystem>
#include <string>

namespace patina::formats {

/// The layout this build writes and reads. A reader refuses a newer one: its keys may mean
/// something this reader would misread.
inline constexpr int kStackFormatVersion = 1;

/// Throws "file:line:column: ..." when `root` (a parsed stack.toml) declares a `[stack]
/// format` that is not an integer or is newer than kStackFormatVersion. A manifest without
/// `[stack]` or without `format` reads as version 1.
inline void check_stack_format(const std::filesystem::path& file, const toml::table& root)
{
    const toml::node* stack = root.get("stack");
    if (!stack)
        return;
    const toml::table* table = stack->as_table();
    if (!table)
        toml_fail(file, stack, "'stack' must be a table");
    const toml::node* format = table->get("format");
    if (!format)
        return;
    const auto version = format->value<int64_t>();
    if (!version || !format->is_integer())
        toml_fail(file, format, "[stack] format must be an integer");
    if (*version > kStackFormatVersion)
        toml_fail(file, format,
                  "stack format " + std::to_string(*version) + " is newer than the " +
                      std::to_string(kStackFormatVersion) +
                      " this Patina reads (the stack was written by a newer Patina)");
}

}  // namespace patina::formats
