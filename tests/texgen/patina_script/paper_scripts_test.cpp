// The three copper-strip scripts of Dorsey & Hanrahan 1996 §5.1, copied exactly as printed
// (blank lines, and the marine script's statement without ';'), parse to the statements the
// paper describes: materials (with their stage numbers), thicknesses in µm, growth models,
// rates, steps and totals, in order.
#include "script_test_util.h"

#include <optional>

namespace pt = patina::texgen;
using pt::test::parse;

namespace {

// D&H 1996 §5.1, "Marine environment".
const char* const kMarine = R"(new copper;

coat tarnish 1 0.35 texture(BD linear 1 20);

coat cuprite 2 1.2 texture(DPD linear 5 40);

coat marine patina 3 3.0 texture(BD linear 10 20)

coat marine patina 4 1.8 texture(DPD linear 20 40);

erode 0.5 texture(BD linear 5 20);

render maps;
)";

// D&H 1996 §5.1, "Rural environment".
const char* const kRural = R"(new copper;

coat tarnish 1 0.25 texture(ST cubic 1 20);

coat cuprite 2 1.0 texture(ST cubic 5 20);

coat rural patina 3 1.0 texture(ST cubic 10 20);

coat rural patina 4 1.1 texture(ST cubic 15 20);

render maps;
)";

// D&H 1996 §5.1, "Urban environment".
const char* const kUrban = R"(new copper;

coat tarnish 1 0.55 texture(RD linear 1 40);

coat cuprite urban 2 1.0 texture(RD cubic 10 40);

coat patina urban 3 4.0 texture(DPD cubic 5 40);

coat patina urban 4 3.0 texture(DPD cubic 10 40);

erode 0.8 texture(DPD linear 30 40);

coat dirt 1.9 texture(BD linear 5 20);

render maps;
)";

// One statement as the paper prints it: keyword, material, amount and its texture.
struct Expected {
    std::string keyword;
    std::string material;
    double amount = 0;
    std::string model, rate;
    int step = 0, total = 0;
    int line = 0;  // of the keyword, column 1
};

void expect_statements(const pt::Script& script, const std::vector<Expected>& expected)
{
    ASSERT_EQ(script.statements.size(), expected.size());
    for (size_t i = 0; i < expected.size(); ++i) {
        SCOPED_TRACE("statement " + std::to_string(i + 1) + ": " + expected[i].keyword + " " +
                     expected[i].material);
        const pt::Statement& statement = script.statements[i];
        const Expected& e = expected[i];
        EXPECT_EQ(pt::keyword_of(statement), e.keyword);
        EXPECT_EQ(pt::location_of(statement), (pt::SourceLocation{e.line, 1}));
        const std::optional<pt::Expr>* map = nullptr;
        if (const auto* s = std::get_if<pt::NewStatement>(&statement)) {
            EXPECT_EQ(s->material, e.material);
        } else if (const auto* s = std::get_if<pt::CoatStatement>(&statement)) {
            EXPECT_EQ(s->material, e.material);
            EXPECT_EQ(s->thickness_um, e.amount);
            EXPECT_EQ(s->material_location, (pt::SourceLocation{e.line, 6}));
            map = &s->map;
        } else if (const auto* s = std::get_if<pt::ErodeStatement>(&statement)) {
            EXPECT_EQ(s->thickness_um, e.amount);
            map = &s->map;
        } else {
            EXPECT_TRUE(std::holds_alternative<pt::RenderStatement>(statement));
        }
        if (e.model.empty()) {
            EXPECT_TRUE(map == nullptr || !map->has_value());
            continue;
        }
        ASSERT_TRUE(map && map->has_value());
        const pt::Expr& texture = **map;
        ASSERT_EQ(texture.kind, pt::ExprKind::Texture);
        EXPECT_EQ(texture.texture.model, e.model);
        EXPECT_EQ(texture.texture.rate, e.rate);
        EXPECT_EQ(texture.texture.step, e.step);
        EXPECT_EQ(texture.texture.total, e.total);
        EXPECT_TRUE(texture.texture.parameters.empty());
    }
}

}  // namespace

TEST(PaperScripts, MarineParsesAsPrinted)
{
    const pt::Script script = parse(kMarine);
    EXPECT_EQ(script.file_name, "test.patina");
    // Line 7, "coat marine patina 3 3.0 texture(BD linear 10 20)", has no ';': it ends at
    // the end of its line (D&H 1996 §5.1 prints it so).
    expect_statements(script, {
                                  {"new", "copper", 0, "", "", 0, 0, 1},
                                  {"coat", "tarnish 1", 0.35, "BD", "linear", 1, 20, 3},
                                  {"coat", "cuprite 2", 1.2, "DPD", "linear", 5, 40, 5},
                                  {"coat", "marine patina 3", 3.0, "BD", "linear", 10, 20, 7},
                                  {"coat", "marine patina 4", 1.8, "DPD", "linear", 20, 40, 9},
                                  {"erode", "", 0.5, "BD", "linear", 5, 20, 11},
                                  {"render", "", 0, "", "", 0, 0, 13},
                              });
}

TEST(PaperScripts, RuralParsesAsPrinted)
{
    expect_statements(parse(kRural), {
                                         {"new", "copper", 0, "", "", 0, 0, 1},
                                         {"coat", "tarnish 1", 0.25, "ST", "cubic", 1, 20, 3},
                                         {"coat", "cuprite 2", 1.0, "ST", "cubic", 5, 20, 5},
                                         {"coat", "rural patina 3", 1.0, "ST", "cubic", 10, 20, 7},
                                         {"coat", "rural patina 4", 1.1, "ST", "cubic", 15, 20, 9},
                                         {"render", "", 0, "", "", 0, 0, 11},
                                     });
}

TEST(PaperScripts, UrbanParsesAsPrinted)
{
    // "coat dirt 1.9": one number after the material, so 1.9 is the thickness of "dirt".
    expect_statements(parse(kUrban), {
                                         {"new", "copper", 0, "", "", 0, 0, 1},
                                         {"coat", "tarnish 1", 0.55, "RD", "linear", 1, 40, 3},
                                         {"coat", "cuprite urban 2", 1.0, "RD", "cubic", 10, 40, 5},
                                         {"coat", "patina urban 3", 4.0, "DPD", "cubic", 5, 40, 7},
                                         {"coat", "patina urban 4", 3.0, "DPD", "cubic", 10, 40, 9},
                                         {"erode", "", 0.8, "DPD", "linear", 30, 40, 11},
                                         {"coat", "dirt", 1.9, "BD", "linear", 5, 20, 13},
                                         {"render", "", 0, "", "", 0, 0, 15},
                                     });
}

TEST(PaperScripts, MarineStatementWithoutSemicolonAlone)
{
    // The statement the paper prints without ';', as the last line of a file without a
    // final line break, and followed by another statement on the next line.
    const auto coat = pt::test::only<pt::CoatStatement>(
        "coat marine patina 3 3.0 texture(BD linear 10 20)");
    EXPECT_EQ(coat.material, "marine patina 3");
    EXPECT_EQ(coat.thickness_um, 3.0);
    ASSERT_TRUE(coat.map.has_value());
    EXPECT_EQ(pt::to_string(*coat.map), "texture(BD linear 10 20)");

    const pt::Script two = parse("coat marine patina 3 3.0 texture(BD linear 10 20)\n"
                                 "erode 0.5\n");
    ASSERT_EQ(two.statements.size(), 2u);
    EXPECT_EQ(std::get<pt::ErodeStatement>(two.statements[1]).thickness_um, 0.5);
    EXPECT_FALSE(std::get<pt::ErodeStatement>(two.statements[1]).map.has_value());
}

TEST(PaperScripts, WindowsLineEndingsAndCommentsChangeNothing)
{
    std::string crlf;
    for (const char c : std::string(kUrban)) {
        if (c == '\n')
            crlf += "  # a comment\r";
        crlf += c;
    }
    const pt::Script a = parse(kUrban);
    const pt::Script b = parse("// urban strip, D&H 1996 §5.1\n" + crlf);
    ASSERT_EQ(a.statements.size(), b.statements.size());
    for (size_t i = 0; i < a.statements.size(); ++i) {
        EXPECT_EQ(pt::keyword_of(a.statements[i]), pt::keyword_of(b.statements[i]));
        const pt::SourceLocation la = pt::location_of(a.statements[i]);
        EXPECT_EQ(pt::location_of(b.statements[i]), (pt::SourceLocation{la.line + 1, 1}));
    }
}

TEST(PaperScripts, StageReadingWinsOnlyWhenTheLibraryKnowsIt)
{
    // The library knows both "tarnish" and "tarnish 1": two numbers make the first a stage.
    EXPECT_EQ(pt::test::only<pt::CoatStatement>("coat tarnish 1 0.35").material, "tarnish 1");
    // One number is the thickness, whatever the library.
    const auto plain = pt::test::only<pt::CoatStatement>("coat tarnish 1");
    EXPECT_EQ(plain.material, "tarnish");
    EXPECT_EQ(plain.thickness_um, 1.0);
    // "3.0" is not a stage: "tarnish" 3.0 µm thick, times the map 0.5.
    const auto decimal = pt::test::only<pt::CoatStatement>("coat tarnish 3.0 0.5");
    EXPECT_EQ(decimal.material, "tarnish");
    EXPECT_EQ(decimal.thickness_um, 3.0);
    ASSERT_TRUE(decimal.map.has_value());
    EXPECT_EQ(pt::to_string(*decimal.map), "0.5");
    // "dirt 2" is not in the library, "dirt" is: 2 µm of dirt times 0.5 * height.
    const auto dirt = pt::test::only<pt::CoatStatement>("coat dirt 2 0.5 * height");
    EXPECT_EQ(dirt.material, "dirt");
    EXPECT_EQ(dirt.thickness_um, 2.0);
    ASSERT_TRUE(dirt.map.has_value());
    EXPECT_EQ(pt::to_string(*dirt.map), "(0.5 * height)");
    // `new` takes a stage number too.
    EXPECT_EQ(pt::test::only<pt::NewStatement>("new marine patina 3").material,
              "marine patina 3");
}
