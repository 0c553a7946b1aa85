#include "texgen/patina/script_names.h"

#include <array>

namespace patina::texgen {

namespace {

// The world frame is Patina's: +y up, north -z, east +x (texgen/sun/solar_position.h).
constexpr std::array kFields = {
    BuiltinField{"t", "the time of the step being computed, years since the start"},
    BuiltinField{"inclination",
                 "cos of the angle between the surface normal and up: 1 facing up, 0 vertical, "
                 "-1 facing down (horizontal surfaces hold water, D&H 1996 §2.2)"},
    BuiltinField{"height",
                 "the world up coordinate normalised to [0, 1] over the mesh's bounds (0 at the "
                 "bottom, where water collects, §5.2)"},
    BuiltinField{"facing_south",
                 "the normal's component towards the south (+z), -1..1: inclined surfaces "
                 "facing south are dryer (§5.3)"},
};

constexpr std::array kFunctions = {
    BuiltinFunction{"clamp", 3, "clamp(x, a, b): x limited to [a, b]"},
    BuiltinFunction{"min", 2, "min(a, b)"},
    BuiltinFunction{"max", 2, "max(a, b)"},
    BuiltinFunction{"smoothstep", 3,
                    "smoothstep(a, b, x): 0 below a, 1 above b, 3s^2 - 2s^3 between"},
    BuiltinFunction{"mix", 3, "mix(a, b, s): a (1 - s) + b s"},
    BuiltinFunction{"pow", 2, "pow(x, y): x to the power y"},
    BuiltinFunction{"abs", 1, "abs(x)"},
    BuiltinFunction{"step", 2, "step(edge, x): 0 where x < edge, else 1"},
};

// D&H 1996 §3.3: steady thickening, random deposition (RDR: with surface relaxation),
// ballistic deposition, directed percolation depinning, and noise / turbulence [6].
const std::array<std::string, 7> kModels = {"ST",  "RD",    "RDR",       "BD",
                                            "DPD", "noise", "turbulence"};
// D&H 1996 §3.3 ("linear, parabolic, and logarithmic") and §5.1 (cubic).
const std::array<std::string, 4> kRates = {"linear", "parabolic", "logarithmic", "cubic"};

const std::array<std::string, 10> kKeywords = {"new",    "coat",   "erode", "fill",  "polish",
                                               "offset", "render", "map",   "curve", "let"};

}  // namespace

std::span<const BuiltinField> builtin_fields() { return kFields; }
std::span<const BuiltinFunction> builtin_functions() { return kFunctions; }
std::span<const std::string> texture_model_names() { return kModels; }
std::span<const std::string> texture_rate_names() { return kRates; }
std::span<const std::string> operator_keywords() { return kKeywords; }

const BuiltinField* find_builtin_field(std::string_view name)
{
    for (const BuiltinField& field : kFields)
        if (field.name == name)
            return &field;
    return nullptr;
}

const BuiltinFunction* find_builtin_function(std::string_view name)
{
    for (const BuiltinFunction& function : kFunctions)
        if (function.name == name)
            return &function;
    return nullptr;
}

}  // namespace patina::texgen
