// The operators beyond the §5.1 scripts (fill, polish, offset, D&H 1996 §3.2), the
// declarations (map, curve, let) and expressions: precedence, names, calls, texture
// parameters.
#include "script_test_util.h"

#include "texgen/patina/script_names.h"

#include <fstream>

namespace pt = patina::texgen;
using pt::test::let_text;
using pt::test::only;
using pt::test::parse;

TEST(Statements, FillPolishOffset)
{
    const auto fill = only<pt::FillStatement>("fill dirt 2.5 1 - height;");
    EXPECT_EQ(fill.material, "dirt");
    EXPECT_EQ(fill.height_um, 2.5);
    EXPECT_EQ(fill.material_location, (pt::SourceLocation{1, 6}));
    ASSERT_TRUE(fill.map.has_value());
    EXPECT_EQ(pt::to_string(*fill.map), "(1 - height)");

    const auto polish = only<pt::PolishStatement>("polish 1.5");
    EXPECT_EQ(polish.mode, pt::PolishStatement::Mode::ToHeight);
    EXPECT_EQ(polish.height_um, 1.5);
    EXPECT_FALSE(polish.map.has_value());

    const auto until = only<pt::PolishStatement>("polish until 0.3 exposed;");
    EXPECT_EQ(until.mode, pt::PolishStatement::Mode::UntilExposed);
    EXPECT_EQ(until.exposed_fraction, 0.3);

    const auto tangent = only<pt::OffsetStatement>("offset tarnish 1 0.002");
    EXPECT_EQ(tangent.material, "tarnish 1");
    EXPECT_EQ(tangent.radius_m, 0.002);
    EXPECT_EQ(tangent.variant, pt::OffsetStatement::Variant::Tangent);
    const auto closing = only<pt::OffsetStatement>("offset dirt 0.01 closing");
    EXPECT_EQ(closing.material, "dirt");
    EXPECT_EQ(closing.variant, pt::OffsetStatement::Variant::Closing);
    EXPECT_EQ(only<pt::OffsetStatement>("offset dirt 0.01 tangent;").variant,
              pt::OffsetStatement::Variant::Tangent);
}

TEST(Statements, MapCurveLetDeclareNames)
{
    const pt::Script script = parse(
        "map access = \"out/bake/accessibility.exr\"\n"
        "map sun = \"exposure.exr\" \"sun\";\n"
        "# body of figure 10: thickness against years, over two lines inside the parentheses\n"
        "curve body = (0 0, 6 0.4,\n"
        "              30 -1e-1)\n"
        "let wet = clamp(1 - sun, 0, 1) * inclination\n"
        "coat marine patina 3 3.0 body * wet + access\n");
    ASSERT_EQ(script.statements.size(), 5u);
    const auto& access = std::get<pt::MapStatement>(script.statements[0]);
    EXPECT_EQ(access.name, "access");
    EXPECT_EQ(access.path, "out/bake/accessibility.exr");
    EXPECT_EQ(access.channel, "");
    const auto& sun = std::get<pt::MapStatement>(script.statements[1]);
    EXPECT_EQ(sun.path, "exposure.exr");
    EXPECT_EQ(sun.channel, "sun");

    const auto& body = std::get<pt::CurveStatement>(script.statements[2]);
    EXPECT_EQ(body.location, (pt::SourceLocation{4, 1}));
    ASSERT_EQ(body.points.size(), 3u);
    EXPECT_EQ(body.points[1].time_years, 6.0);
    EXPECT_EQ(body.points[1].value, 0.4);
    EXPECT_EQ(body.points[2].time_years, 30.0);
    EXPECT_EQ(body.points[2].value, -0.1);

    const auto& wet = std::get<pt::LetStatement>(script.statements[3]);
    EXPECT_EQ(wet.location, (pt::SourceLocation{6, 1}));
    EXPECT_EQ(pt::to_string(wet.value), "(clamp((1 - sun), 0, 1) * inclination)");
    ASSERT_EQ(wet.value.operands.size(), 2u);
    const pt::Expr& clamp = wet.value.operands[0];
    EXPECT_EQ(clamp.kind, pt::ExprKind::Call);
    EXPECT_EQ(clamp.location, (pt::SourceLocation{6, 11}));
    EXPECT_EQ(clamp.operands[0].operands[1].name_kind, pt::NameKind::Map);
    EXPECT_EQ(wet.value.operands[1].name_kind, pt::NameKind::Field);

    const auto& coat = std::get<pt::CoatStatement>(script.statements[4]);
    ASSERT_TRUE(coat.map.has_value());
    EXPECT_EQ(pt::to_string(*coat.map), "((body * wet) + access)");
    const pt::Expr& product = coat.map->operands[0];
    EXPECT_EQ(product.operands[0].name_kind, pt::NameKind::Curve);
    EXPECT_EQ(product.operands[1].name_kind, pt::NameKind::Let);
    EXPECT_EQ(product.operands[1].location, (pt::SourceLocation{7, 33}));
}

TEST(Expressions, Precedence)
{
    // * and / bind tighter than + and -; all four associate to the left; unary minus binds
    // tightest; parentheses group.
    EXPECT_EQ(let_text("1 + 2 * 3"), "(1 + (2 * 3))");
    EXPECT_EQ(let_text("1 * 2 + 3"), "((1 * 2) + 3)");
    EXPECT_EQ(let_text("8 - 4 - 2"), "((8 - 4) - 2)");
    EXPECT_EQ(let_text("8 / 4 / 2"), "((8 / 4) / 2)");
    EXPECT_EQ(let_text("8 / 4 * 2"), "((8 / 4) * 2)");
    EXPECT_EQ(let_text("-t * 2"), "((-t) * 2)");
    EXPECT_EQ(let_text("2 - -t"), "(2 - (-t))");
    EXPECT_EQ(let_text("(1 + 2) * 3"), "((1 + 2) * 3)");
    EXPECT_EQ(let_text("1 - (2 - 3)"), "(1 - (2 - 3))");
    EXPECT_EQ(let_text("t + height * inclination - 1 / 2"),
              "((t + (height * inclination)) - (1 / 2))");
    EXPECT_EQ(let_text("mix(0, 1, smoothstep(0.2, 0.8, height)) * pow(t, 0.5)"),
              "(mix(0, 1, smoothstep(0.2, 0.8, height)) * pow(t, 0.5))");
    EXPECT_EQ(let_text("min(1, max(abs(-t), step(0.5, facing_south)))"),
              "min(1, max(abs((-t)), step(0.5, facing_south)))");
    // Numbers in their shortest form: 1e-3 is 0.001, .5 is 0.5.
    EXPECT_EQ(let_text("1e-3 + .5 + 2.50"), "((0.001 + 0.5) + 2.5)");
}

TEST(Expressions, OperatorNodesCarryTheirLocation)
{
    const pt::Script script = parse("let a = 1 + 2 * t");
    const pt::Expr& sum = std::get<pt::LetStatement>(script.statements[0]).value;
    EXPECT_EQ(sum.kind, pt::ExprKind::Add);
    EXPECT_EQ(sum.location, (pt::SourceLocation{1, 11}));
    EXPECT_EQ(sum.operands[0].kind, pt::ExprKind::Number);
    EXPECT_EQ(sum.operands[0].number, 1.0);
    EXPECT_EQ(sum.operands[1].kind, pt::ExprKind::Multiply);
    EXPECT_EQ(sum.operands[1].location, (pt::SourceLocation{1, 15}));
    EXPECT_EQ(sum.operands[1].operands[1].location, (pt::SourceLocation{1, 17}));
}

TEST(Expressions, TextureParametersAndNesting)
{
    const auto coat = only<pt::CoatStatement>(
        "coat dirt 1.9 ((0.5 + texture(noise linear 0 1 scale=0.05 octaves=4 seed=-3)) *\n"
        "               (1 - height))\n");
    ASSERT_TRUE(coat.map.has_value());
    const pt::Expr& noise = coat.map->operands[0].operands[1];
    ASSERT_EQ(noise.kind, pt::ExprKind::Texture);
    EXPECT_EQ(noise.location, (pt::SourceLocation{1, 23}));
    EXPECT_EQ(noise.texture.model, "noise");
    EXPECT_EQ(noise.texture.step, 0);
    EXPECT_EQ(noise.texture.total, 1);
    ASSERT_EQ(noise.texture.parameters.size(), 3u);
    EXPECT_EQ(noise.texture.parameters[0].name, "scale");
    EXPECT_EQ(noise.texture.parameters[0].value, 0.05);
    EXPECT_EQ(noise.texture.parameters[1].value, 4.0);
    EXPECT_EQ(noise.texture.parameters[2].value, -3.0);
    EXPECT_EQ(noise.texture.parameters[2].location, (pt::SourceLocation{1, 69}));
    EXPECT_EQ(pt::to_string(*coat.map),
              "((0.5 + texture(noise linear 0 1 scale=0.05 octaves=4 seed=-3)) * (1 - height))");
}

TEST(Expressions, EveryModelAndRateOfTheTablesParses)
{
    for (const std::string& model : pt::texture_model_names())
        for (const std::string& rate : pt::texture_rate_names()) {
            const auto erode =
                only<pt::ErodeStatement>("erode 1 texture(" + model + " " + rate + " 3 7)");
            EXPECT_EQ(erode.map->texture.model, model);
            EXPECT_EQ(erode.map->texture.rate, rate);
        }
}

TEST(Statements, EmptyStatementsAndBlankLinesAreSkipped)
{
    const pt::Script script = parse("\n\n;;new copper;;\n\n   \n# end\n");
    ASSERT_EQ(script.statements.size(), 1u);
    EXPECT_EQ(pt::location_of(script.statements[0]), (pt::SourceLocation{3, 3}));
    EXPECT_TRUE(parse("").statements.empty());
    EXPECT_TRUE(parse("// nothing\n# at all").statements.empty());
}

TEST(Statements, ParenthesesCarryAStatementOverLines)
{
    const auto erode = only<pt::ErodeStatement>("erode 0.5 texture(BD linear\n   5 20)\n");
    ASSERT_TRUE(erode.map.has_value());
    EXPECT_EQ(erode.map->texture.total, 20);
    // Comments and blank lines may follow "render maps".
    const pt::Script script = parse("new copper\nrender maps;\n# done\n\n");
    ASSERT_EQ(script.statements.size(), 2u);
    EXPECT_TRUE(std::holds_alternative<pt::RenderStatement>(script.statements[1]));
}

TEST(Statements, ParseScriptFileReadsAFileAndNamesIt)
{
    const std::string path = std::string(PATINA_TEST_BUILD_DIR) + "/patina_script_file.patina";
    {
        std::ofstream out(path, std::ios::binary);
        out << "new copper;\ncoat tarnish 1 0.35 texture(BD linear 1 20);\nrender maps;\n";
    }
    const pt::Script script = pt::parse_script_file(path, pt::test::paper_materials());
    EXPECT_EQ(script.file_name, path);
    EXPECT_EQ(script.statements.size(), 3u);

    const std::string missing = std::string(PATINA_TEST_BUILD_DIR) + "/no_such.patina";
    const std::string message = patina::test::message_of<std::runtime_error>(
        [&] { pt::parse_script_file(missing, pt::test::paper_materials()); });
    EXPECT_NE(message.find("no_such.patina"), std::string::npos) << message;
}
