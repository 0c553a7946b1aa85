// Shared by the patina script tests: a material library with the names of the §5.1 scripts,
// and helpers to parse a text and to read a statement or the error it raises.
#pragma once

#include "texgen/patina/script_parser.h"

#include "test_util.h"

#include <gtest/gtest.h>

#include <set>
#include <string>

namespace patina::texgen::test {

/// The materials of D&H 1996 §5.1 (figure 2's stages), plus the plain "tarnish" and
/// "cuprite" the project's library also knows (shaders/patina/copper.toml), so that the
/// stage reading is seen to win over the plain one.
inline const std::set<std::string>& paper_materials()
{
    static const std::set<std::string> kMaterials = {
        "copper",          "tarnish",         "tarnish 1",      "cuprite",
        "cuprite 2",       "marine patina 3", "marine patina 4", "rural patina 3",
        "rural patina 4",  "cuprite urban 2", "patina urban 3",  "patina urban 4",
        "dirt"};
    return kMaterials;
}

inline Script parse(const std::string& text)
{
    return parse_script(text, "test.patina", paper_materials());
}

/// The what() of the ScriptError `text` raises, or "(no exception)".
inline std::string error_of(const std::string& text)
{
    return patina::test::message_of<ScriptError>([&] { parse(text); });
}

/// The single statement of `text`, as alternative T.
template <class T>
T only(const std::string& text)
{
    const Script script = parse(text);
    EXPECT_EQ(script.statements.size(), 1u) << text;
    if (script.statements.empty() || !std::holds_alternative<T>(script.statements[0])) {
        ADD_FAILURE() << "not the expected statement: " << text;
        return T{};
    }
    return std::get<T>(script.statements[0]);
}

/// The expression of `let x = EXPR`, fully parenthesised (to_string), after `prelude`.
inline std::string let_text(const std::string& expr, const std::string& prelude = "")
{
    const Script script = parse(prelude + "let x_ = " + expr + "\n");
    return to_string(std::get<LetStatement>(script.statements.back()).value);
}

}  // namespace patina::texgen::test
