// Bad scripts: every error is "FILE:LINE:COL: error: ..." at the offending token, naming it,
// with a suggestion for a misspelt name. The expected columns are counted by hand from the
// script text (1-based).
#include "script_test_util.h"

namespace pt = patina::texgen;
using pt::test::error_of;

TEST(ScriptErrors, UnknownOperator)
{
    EXPECT_EQ(error_of("new copper;\ncoatt tarnish 1 0.35;\n"),
              "test.patina:2:1: error: unknown operator 'coatt' (did you mean 'coat'?)");
    EXPECT_EQ(error_of("new copper\n  paint copper 1\n"),
              "test.patina:2:3: error: unknown operator 'paint'");
    EXPECT_EQ(error_of("new copper\n3 + 4\n"),
              "test.patina:2:1: error: expected an operator (new, coat, erode, fill, polish, "
              "offset, render, map, curve or let), found '3'");
}

TEST(ScriptErrors, UnknownMaterialWithSuggestion)
{
    EXPECT_EQ(error_of("new coper;"),
              "test.patina:1:5: error: unknown material 'coper' (did you mean 'copper'?)");
    // The stage reading names the material; both stages of marine patina are one edit away.
    EXPECT_EQ(error_of("new copper;\n\ncoat marine patina 5 3.0 texture(BD linear 10 20)\n"),
              "test.patina:3:6: error: unknown material 'marine patina 5' (did you mean "
              "'marine patina 3' or 'marine patina 4'?)");
    EXPECT_EQ(error_of("coat tarnsh 1 0.35"),
              "test.patina:1:6: error: unknown material 'tarnsh 1' (did you mean 'tarnish 1'?)");
    EXPECT_EQ(error_of("fill zinc 1.0"), "test.patina:1:6: error: unknown material 'zinc'");
    EXPECT_EQ(error_of("offset Dirt 0.1"),
              "test.patina:1:8: error: unknown material 'Dirt' (did you mean 'dirt'?)");
}

TEST(ScriptErrors, MissingAmountAfterAStagedMaterial)
{
    // "tarnish 1" then the end of the line: the stage is there, the thickness is not. (The
    // library also knows "tarnish", so "coat tarnish 1" alone is a valid 1 µm coat; "cuprite
    // urban 2" has no plain form.)
    EXPECT_EQ(error_of("coat cuprite urban 2;"),
              "test.patina:1:21: error: expected a thickness after the material 'cuprite urban "
              "2', found ';'");
    EXPECT_EQ(error_of("coat copper\n"),
              "test.patina:1:12: error: expected a thickness after the material 'copper', "
              "found end of line");
    EXPECT_EQ(error_of("coat 0.5 texture(BD linear 1 2)"),
              "test.patina:1:6: error: expected a material name after 'coat', found '0.5'");
}

TEST(ScriptErrors, GrowthModelAndRateTypos)
{
    EXPECT_EQ(error_of("erode 0.5 texture(DBD linear 5 20);"),
              "test.patina:1:19: error: unknown growth model 'DBD' (did you mean 'BD' or "
              "'DPD'?)");
    EXPECT_EQ(error_of("erode 0.5 texture(bd linear 5 20);"),
              "test.patina:1:19: error: unknown growth model 'bd' (did you mean 'BD'?)");
    EXPECT_EQ(error_of("erode 0.5 texture(BD linaer 5 20);"),
              "test.patina:1:22: error: unknown growth rate 'linaer' (did you mean 'linear'?)");
    EXPECT_EQ(error_of("erode 0.5 texture(BD quadratic 5 20);"),
              "test.patina:1:22: error: unknown growth rate 'quadratic'");
    EXPECT_EQ(error_of("erode 0.5 texture(5 20)"),
              "test.patina:1:19: error: expected a growth model (ST, RD, RDR, BD, DPD, noise, "
              "turbulence) in texture(...), found '5'");
}

TEST(ScriptErrors, NegativeAmounts)
{
    EXPECT_EQ(error_of("coat tarnish 1 -0.35 texture(BD linear 1 20);"),
              "test.patina:1:16: error: negative thickness -0.35");
    EXPECT_EQ(error_of("coat dirt -1.9"), "test.patina:1:11: error: negative thickness -1.9");
    EXPECT_EQ(error_of("new copper\nerode -1"), "test.patina:2:7: error: negative thickness -1");
    EXPECT_EQ(error_of("fill dirt -2"), "test.patina:1:11: error: negative height -2");
    EXPECT_EQ(error_of("polish -2 height"), "test.patina:1:8: error: negative height -2");
    EXPECT_EQ(error_of("offset dirt -0.1 closing"),
              "test.patina:1:13: error: negative radius -0.1");
    EXPECT_EQ(error_of("polish until 1.5 exposed"),
              "test.patina:1:14: error: exposed fraction 1.5 is not between 0 and 1");
}

TEST(ScriptErrors, MissingArguments)
{
    EXPECT_EQ(error_of("map wet =\n"),
              "test.patina:1:10: error: expected the file of map 'wet' (a \"quoted\" path), "
              "found end of line");
    EXPECT_EQ(error_of("map wet = wetness.exr"),
              "test.patina:1:11: error: expected the file of map 'wet' (a \"quoted\" path), "
              "found 'wetness'");
    EXPECT_EQ(error_of("map wet \"wet.exr\""),
              "test.patina:1:9: error: expected '=' after 'map wet', found string \"wet.exr\"");
    EXPECT_EQ(error_of("erode 0.5 texture(BD linear 5);"),
              "test.patina:1:30: error: expected the total number of steps in texture(...), "
              "found ')'");
    EXPECT_EQ(error_of("erode"),
              "test.patina:1:6: error: expected a thickness (µm) after 'erode', found end of "
              "file");
    EXPECT_EQ(error_of("let w = clamp(t, 0)"),
              "test.patina:1:9: error: clamp takes 3 arguments, found 2");
    EXPECT_EQ(error_of("render"),
              "test.patina:1:7: error: expected 'maps' after 'render', found end of file");
    EXPECT_EQ(error_of("polish until 0.5\n"),
              "test.patina:1:17: error: expected 'exposed' after the fraction of 'polish "
              "until', found end of line");
}

TEST(ScriptErrors, UnbalancedParentheses)
{
    EXPECT_EQ(error_of("coat tarnish 1 0.35 texture(BD linear 1 20;\n"),
              "test.patina:1:43: error: expected ')' to close the '(' at 1:28, found ';'");
    EXPECT_EQ(error_of("erode 0.5 texture(BD linear 5 20));"),
              "test.patina:1:34: error: unbalanced parenthesis: ')' without a matching '('");
    EXPECT_EQ(error_of("let a = 2 * t)"),
              "test.patina:1:14: error: unbalanced parenthesis: ')' without a matching '('");
    // Inside parentheses a statement goes on over lines, so the next statement is where the
    // ')' was expected.
    EXPECT_EQ(error_of("let a = (1 + 2\ncoat dirt 1\n"),
              "test.patina:2:1: error: expected ')' to close the '(' at 1:9, found 'coat'");
    EXPECT_EQ(error_of("let a = min(1, 2"),
              "test.patina:1:17: error: expected ')' to close the '(' at 1:12, found end of "
              "file");
}

TEST(ScriptErrors, UnknownNamesAndFunctions)
{
    EXPECT_EQ(error_of("map wetness = \"wet.exr\"\ncoat dirt 1.9 wetnes * 2\n"),
              "test.patina:2:15: error: unknown name 'wetnes' (did you mean 'wetness'?)");
    // Names are declared before use: a let cannot see itself or a later declaration.
    EXPECT_EQ(error_of("let a = a + 1"), "test.patina:1:9: error: unknown name 'a'");
    EXPECT_EQ(error_of("let a = hieght"),
              "test.patina:1:9: error: unknown name 'hieght' (did you mean 'height'?)");
    EXPECT_EQ(error_of("let a = clmp(t, 0, 1)"),
              "test.patina:1:9: error: unknown function 'clmp' (did you mean 'clamp'?)");
    EXPECT_EQ(error_of("map w = \"w.exr\"\nlet a = w(1)"),
              "test.patina:2:9: error: 'w' is a map, not a function");
    EXPECT_EQ(error_of("let a = texture"),
              "test.patina:1:16: error: expected '(' after 'texture' (texture(MODEL RATE STEP "
              "TOTAL)), found end of file");
}

TEST(ScriptErrors, Declarations)
{
    EXPECT_EQ(error_of("let w = 1\nlet w = 2"),
              "test.patina:2:5: error: 'w' is already declared as a let at 1:5");
    EXPECT_EQ(error_of("curve body = (0 0)\nmap body = \"b.exr\""),
              "test.patina:2:5: error: 'body' is already declared as a curve at 1:7");
    EXPECT_EQ(error_of("let t = 1"),
              "test.patina:1:5: error: 't' is a built-in field and cannot name a let");
    EXPECT_EQ(error_of("let mix = 1"),
              "test.patina:1:5: error: 'mix' is a function and cannot name a let");
    EXPECT_EQ(error_of("curve coat = (0 0)"),
              "test.patina:1:7: error: 'coat' is a keyword and cannot name a curve");
}

TEST(ScriptErrors, CurveTimesMustAscend)
{
    EXPECT_EQ(error_of("curve body = (0 0, 12 1, 6 2)"),
              "test.patina:1:26: error: curve 'body': time 6 does not follow 12 (times must "
              "ascend)");
    EXPECT_EQ(error_of("curve body = (0 0,\n              0 1)"),
              "test.patina:2:15: error: curve 'body': time 0 does not follow 0 (times must "
              "ascend)");
    EXPECT_EQ(error_of("curve body = (0 0 6 1)"),
              "test.patina:1:19: error: expected ',' or ')' to close the '(' at 1:14, found '6'");
    EXPECT_EQ(error_of("curve body = ()"),
              "test.patina:1:15: error: expected a time (years) in curve 'body', found ')'");
}

TEST(ScriptErrors, BadNumbersStringsAndCharacters)
{
    EXPECT_EQ(error_of("coat tarnish 1 0.3.5"), "test.patina:1:16: error: bad number '0.3.5'");
    EXPECT_EQ(error_of("new copper\nerode 10x"), "test.patina:2:7: error: bad number '10x'");
    EXPECT_EQ(error_of("erode 1e"), "test.patina:1:7: error: bad number '1e'");
    EXPECT_EQ(error_of("map a = \"a.exr"),
              "test.patina:1:9: error: string is not closed on its line");
    EXPECT_EQ(error_of("map a = \"a\\q.exr\""),
              "test.patina:1:11: error: unknown escape '\\q' in a string");
    EXPECT_EQ(error_of("let a = 2 ^ 3"), "test.patina:1:11: error: unexpected character '^'");
    // A column counts characters, not bytes: "é" is one column.
    EXPECT_EQ(error_of("# é\nlet a = 2 € 3"),
              "test.patina:2:11: error: unexpected character '€'");
    EXPECT_EQ(error_of("map a = \"é\" \"x\" ?"),
              "test.patina:1:17: error: unexpected character '?'");
}

TEST(ScriptErrors, TextureStepsAndParameters)
{
    EXPECT_EQ(error_of("erode 1 texture(BD linear 30 20)"),
              "test.patina:1:27: error: step 30 is beyond the total of 20 steps");
    EXPECT_EQ(error_of("erode 1 texture(BD linear 1.5 20)"),
              "test.patina:1:27: error: the step number 1.5 is not a whole number >= 0");
    EXPECT_EQ(error_of("erode 1 texture(BD linear -1 20)"),
              "test.patina:1:27: error: the step number -1 is not a whole number >= 0");
    EXPECT_EQ(error_of("erode 1 texture(BD linear 0 0)"),
              "test.patina:1:29: error: the total number of steps must be at least 1");
    EXPECT_EQ(error_of("erode 1 texture(BD linear 1 2 seed=1 seed=2)"),
              "test.patina:1:38: error: texture parameter 'seed' is already given at 1:31");
    EXPECT_EQ(error_of("erode 1 texture(BD linear 1 2 seed)"),
              "test.patina:1:35: error: expected '=' after texture parameter 'seed', found ')'");
}

TEST(ScriptErrors, StatementBoundaries)
{
    // A statement ends at the end of its line; a line ending in an operator gets a hint.
    EXPECT_EQ(error_of("let w = height *\n  inclination"),
              "test.patina:1:17: error: expected an expression, found end of line (a statement "
              "ends at the end of its line; wrap a long expression in parentheses to continue "
              "it)");
    EXPECT_EQ(error_of("coat dirt 1.9 texture(BD linear 5 20) height"),
              "test.patina:1:39: error: expected ';' or end of line after the coat statement, "
              "found 'height'");
    EXPECT_EQ(error_of("offset dirt 0.1 closng"),
              "test.patina:1:17: error: unknown offset variant 'closng', expected 'tangent' or "
              "'closing' (did you mean 'closing'?)");
    // "render maps" ends the script.
    EXPECT_EQ(error_of("new copper;\nrender maps;\n\n  erode 0.5;\n"),
              "test.patina:4:3: error: 'erode' after 'render maps' (at 2:1), which must be the "
              "last statement");
    EXPECT_EQ(error_of("render maps; render maps"),
              "test.patina:1:14: error: 'render' after 'render maps' (at 1:1), which must be "
              "the last statement");
}

TEST(ScriptErrors, ScriptErrorKeepsItsParts)
{
    try {
        pt::test::parse("new copper\n\n  coat dirt -1");
        FAIL() << "no error";
    } catch (const pt::ScriptError& e) {
        EXPECT_EQ(e.file(), "test.patina");
        EXPECT_EQ(e.location(), (pt::SourceLocation{3, 13}));
        EXPECT_EQ(e.message(), "negative thickness -1");
    }
}

TEST(ScriptErrors, NestingBeyondTheLimitIsRefusedAtItsToken)
{
    // Without the limit, 4000 parentheses or 200,000 minus signs overflowed the parser's
    // stack (SIGSEGV). The expression starts at column 16 of line 2; its 257th level opens
    // at the 257th '(' (column 272).
    const std::string prefix = "new copper\ncoat tarnish 1 ";
    const auto nested = [&](int n) {
        return prefix + std::string(n, '(') + "1" + std::string(n, ')') + "\n";
    };
    EXPECT_EQ(pt::test::parse(nested(pt::kMaxExpressionDepth - 1)).statements.size(), 2u);
    const std::string too_deep = error_of(nested(4000));
    EXPECT_EQ(too_deep.rfind("test.patina:2:272: error: expression nested more than 256 levels "
                             "deep", 0), 0u) << too_deep;
    const std::string minus = error_of(prefix + std::string(200000, '-') + "1\n");
    EXPECT_EQ(minus.rfind("test.patina:2:", 0), 0u) << minus;
    EXPECT_NE(minus.find("nested more than 256"), std::string::npos) << minus;
    // A long chain of one operator is as deep a tree: the interpreter recurses over it.
    std::string chain = prefix + "(";
    for (int i = 0; i < 1000; ++i)
        chain += "1 + ";
    const std::string chained = error_of(chain + "1)\n");
    EXPECT_NE(chained.find("nested more than 256"), std::string::npos) << chained;
}
