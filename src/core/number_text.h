// Numbers in text a user wrote (an option's value, a list item), read whole.
#pragma once

#include <cmath>
#include <optional>
#include <stdexcept>
#include <string>

namespace patina {

/// `text` read as a whole as a finite number (std::stod's syntax: "12", "1e6", "-0.5");
/// nullopt when any of it is not part of the number, or the number is not finite.
inline std::optional<double> parse_double(const std::string& text)
{
    size_t used = 0;
    double value = 0.0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        return std::nullopt;
    }
    if (used != text.size() || !std::isfinite(value))
        return std::nullopt;
    return value;
}

}  // namespace patina
