// The names a patina script knows without declaring them: the built-in fields and functions
// of its expressions, the growth models and rates of texture(...) (D&H 1996 §3.3), and the
// keywords. One table each, so that the parser, its "did you mean" suggestions, the
// interpreter and docs/patina-script.md all read the same list; add a row here to add a name.
#pragma once

#include <span>
#include <string>
#include <string_view>

namespace patina::texgen {

/// A value the interpreter provides at every surface point.
struct BuiltinField {
    std::string_view name;
    std::string_view description;
};

/// t, inclination, height, facing_south (see the .cpp for their definitions).
std::span<const BuiltinField> builtin_fields();

/// A function of an expression: name(arg, ...), exactly `arity` arguments.
struct BuiltinFunction {
    std::string_view name;
    int arity = 0;
    std::string_view description;
};

/// clamp, min, max, smoothstep, mix, pow, abs, step.
std::span<const BuiltinFunction> builtin_functions();

/// The growth models a texture(MODEL ...) names: ST, RD, RDR, BD, DPD, noise, turbulence.
/// (A local table until texgen/growth names its models; spelt as in the paper.)
std::span<const std::string> texture_model_names();
/// The growth rates of texture(MODEL RATE ...): linear, parabolic, logarithmic, cubic.
std::span<const std::string> texture_rate_names();

/// The first word of each statement: new, coat, erode, fill, polish, offset, render, map,
/// curve, let.
std::span<const std::string> operator_keywords();

const BuiltinField* find_builtin_field(std::string_view name);
const BuiltinFunction* find_builtin_function(std::string_view name);

}  // namespace patina::texgen
