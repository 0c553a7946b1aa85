// The tokens of the script language and the edit distance behind "did you mean".
#include "texgen/patina/script_lexer.h"
#include "texgen/patina/script_names.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

namespace pt = patina::texgen;

TEST(ScriptLexer, TokensKindsTextAndLocations)
{
    const std::vector<pt::Token> tokens =
        pt::tokenize("coat marine patina 3 3.0 texture(BD linear 10 20) # x\n"
                     "map a = \"d\\\"q\" // y\n",
                     "f");
    std::vector<pt::TokenKind> kinds;
    for (const pt::Token& t : tokens)
        kinds.push_back(t.kind);
    using K = pt::TokenKind;
    EXPECT_EQ(kinds, (std::vector<K>{K::Word, K::Word, K::Word, K::Number, K::Number, K::Word,
                                     K::LeftParen, K::Word, K::Word, K::Number, K::Number,
                                     K::RightParen, K::Newline, K::Word, K::Word, K::Equals,
                                     K::String, K::Newline, K::End}));
    EXPECT_EQ(tokens[3].text, "3");
    EXPECT_TRUE(tokens[3].is_integer);
    EXPECT_EQ(tokens[4].number, 3.0);
    EXPECT_FALSE(tokens[4].is_integer);  // "3.0" is a thickness, never a stage
    EXPECT_EQ(tokens[4].location, (pt::SourceLocation{1, 22}));
    EXPECT_EQ(tokens[6].location, (pt::SourceLocation{1, 33}));
    EXPECT_EQ(tokens[12].location, (pt::SourceLocation{1, 54}));  // the line break
    EXPECT_EQ(tokens[16].text, "d\"q");
    EXPECT_EQ(tokens[16].location, (pt::SourceLocation{2, 9}));
    EXPECT_EQ(tokens[18].location, (pt::SourceLocation{3, 1}));
}

TEST(ScriptLexer, Numbers)
{
    const std::vector<pt::Token> tokens = pt::tokenize("0 .5 2.5e-1 1E+2 007", "f");
    ASSERT_EQ(tokens.size(), 6u);
    EXPECT_EQ(tokens[0].number, 0.0);
    EXPECT_EQ(tokens[1].number, 0.5);
    EXPECT_EQ(tokens[2].number, 0.25);
    EXPECT_EQ(tokens[3].number, 100.0);
    EXPECT_FALSE(tokens[3].is_integer);
    EXPECT_EQ(tokens[4].number, 7.0);
    EXPECT_TRUE(tokens[4].is_integer);
    // A minus sign is its own token: "-3" is unary minus and 3.
    const std::vector<pt::Token> minus = pt::tokenize("-3", "f");
    ASSERT_EQ(minus.size(), 3u);
    EXPECT_EQ(minus[0].kind, pt::TokenKind::Minus);
    EXPECT_EQ(minus[1].location, (pt::SourceLocation{1, 2}));
}

TEST(ScriptLexer, DescribeNamesTokensForMessages)
{
    const std::vector<pt::Token> tokens = pt::tokenize("coat ;\"a\"\n", "f");
    EXPECT_EQ(pt::describe(tokens[0]), "'coat'");
    EXPECT_EQ(pt::describe(tokens[1]), "';'");
    EXPECT_EQ(pt::describe(tokens[2]), "string \"a\"");
    EXPECT_EQ(pt::describe(tokens[3]), "end of line");
    EXPECT_EQ(pt::describe(tokens[4]), "end of file");
}

TEST(ScriptSuggestions, EditDistance)
{
    EXPECT_EQ(pt::edit_distance("copper", "copper"), 0);
    EXPECT_EQ(pt::edit_distance("coper", "copper"), 1);       // insertion
    EXPECT_EQ(pt::edit_distance("linera", "linear"), 1);      // swapped neighbours
    EXPECT_EQ(pt::edit_distance("DBD", "BD"), 1);             // deletion
    EXPECT_EQ(pt::edit_distance("DBD", "DPD"), 1);            // substitution
    EXPECT_EQ(pt::edit_distance("bd", "BD"), 0);              // case is ignored
    EXPECT_EQ(pt::edit_distance("", "abc"), 3);
    EXPECT_EQ(pt::edit_distance("kitten", "sitting"), 3);     // the textbook example
    // Restricted swaps: "ca" -> "abc" is 3 (not 2, which needs editing a swapped pair).
    EXPECT_EQ(pt::edit_distance("ca", "abc"), 3);
}

TEST(ScriptSuggestions, ClosestNamesWithinABound)
{
    const std::vector<std::string> models(pt::texture_model_names().begin(),
                                          pt::texture_model_names().end());
    EXPECT_EQ(pt::closest_names("DBD", models), (std::vector<std::string>{"BD", "DPD"}));
    EXPECT_EQ(pt::closest_names("turbulance", models),
              (std::vector<std::string>{"turbulence"}));
    EXPECT_TRUE(pt::closest_names("XYZ", models).empty());  // 3 letters: bound 1
    EXPECT_EQ(pt::did_you_mean("nois", models), " (did you mean 'noise'?)");
    EXPECT_EQ(pt::did_you_mean("qqqq", models), "");
    const std::vector<std::string> three = {"ab", "ac", "ad"};
    EXPECT_EQ(pt::did_you_mean("a", three), " (did you mean 'ab', 'ac' or 'ad'?)");
}

TEST(ScriptNames, TablesAreConsistent)
{
    // Every built-in function's arity is what its description shows; names are unique
    // across fields, functions and keywords, so a NAME means one thing.
    std::set<std::string> seen;
    for (const pt::BuiltinField& f : pt::builtin_fields())
        EXPECT_TRUE(seen.insert(std::string(f.name)).second) << f.name;
    for (const pt::BuiltinFunction& f : pt::builtin_functions()) {
        EXPECT_TRUE(seen.insert(std::string(f.name)).second) << f.name;
        const std::string_view d = f.description;
        const auto commas = std::count(d.begin(), d.begin() + d.find(')'), ',');
        EXPECT_EQ(static_cast<int>(commas) + 1, f.arity) << f.name;
    }
    for (const std::string& k : pt::operator_keywords())
        EXPECT_TRUE(seen.insert(k).second) << k;
    EXPECT_TRUE(pt::find_builtin_field("inclination"));
    EXPECT_EQ(pt::find_builtin_function("smoothstep")->arity, 3);
    EXPECT_EQ(pt::find_builtin_function("texture"), nullptr);  // a syntax of its own
}
