#include "texgen/deposit/deposit_sources.h"

#include "texgen/wetness/bake_fixture.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <fstream>

namespace patina::texgen {
namespace {

    using patina::test::message_of;

    std::filesystem::path write_file(const std::string& name, const std::string& text)
    {
        const auto path = test::scratch("deposit_sources_test", name);
        std::ofstream(path) << text;
        return path;
    }

    bool contains(const std::string& text, const std::string& part)
    {
        return text.find(part) != std::string::npos;
    }

    TEST(DepositSources, ParsesEveryKindFromTheCommandLine)
    {
        const DepositSource s = parse_source_option("sphere center=0,5,-1 radius=0.5 strength=2");
        EXPECT_EQ(s.kind, DepositSource::Kind::Sphere);
        EXPECT_EQ(s.center, Imath::V3f(0.0f, 5.0f, -1.0f));
        EXPECT_FLOAT_EQ(s.radius, 0.5f);
        EXPECT_FLOAT_EQ(s.strength, 2.0f);
        const DepositSource d = parse_source_option("disc center=1,2,3 normal=0,-2,0 radius=1");
        EXPECT_EQ(d.kind, DepositSource::Kind::Disc);
        EXPECT_EQ(d.normal, Imath::V3f(0.0f, -1.0f, 0.0f)); // normalised
        EXPECT_FLOAT_EQ(d.strength, 1.0f);                  // default
        const DepositSource r =
            parse_source_option("rectangle corner=0,1,0 edge1=2,0,0 edge2=0,0,1e0");
        EXPECT_EQ(r.kind, DepositSource::Kind::Rectangle);
        EXPECT_EQ(r.edge2, Imath::V3f(0.0f, 0.0f, 1.0f));
        const DepositSource w = parse_source_option("directional direction=1,-1,0 spread_deg=15");
        EXPECT_EQ(w.kind, DepositSource::Kind::Directional);
        EXPECT_NEAR(w.direction.x, std::sqrt(0.5f), 1e-6f);
        EXPECT_FLOAT_EQ(w.spread_deg, 15.0f);
        // describe() round-trips.
        const DepositSource again = parse_source_option(s.describe());
        EXPECT_EQ(again.center, s.center);
        EXPECT_EQ(again.radius, s.radius);
        EXPECT_EQ(again.strength, s.strength);
    }

    TEST(DepositSources, CommandLineErrorsQuoteTheSourceAndKey)
    {
        const auto msg = [](const std::string& text) {
            return message_of([&] { parse_source_option(text); });
        };
        const std::string unknown = msg("sphere centre=0,5,0 radius=1");
        EXPECT_TRUE(contains(unknown, "--source 'sphere centre=0,5,0 radius=1'")) << unknown;
        EXPECT_TRUE(contains(unknown, "unknown key 'centre'")) << unknown;
        EXPECT_TRUE(contains(unknown, "allowed: center, radius, strength")) << unknown;
        EXPECT_TRUE(contains(msg("sphere center=0,5,0"), "needs 'radius'"));
        EXPECT_TRUE(contains(msg("sphere center=0,5 radius=1"), "'center' must be 3 numbers"));
        EXPECT_TRUE(
            contains(msg("sphere center=0,x,0 radius=1"), "'x' in 'center=0,x,0' is not a number"));
        EXPECT_TRUE(contains(msg("sphere center=0,5,0 radius=-1"), "'radius' must be > 0"));
        EXPECT_TRUE(contains(msg("sphere center=0,5,0 radius=1 radius=2"), "given twice"));
        EXPECT_TRUE(contains(msg("cone direction=0,-1,0"), "unknown source type 'cone'"));
        EXPECT_TRUE(contains(msg("rectangle corner=0,0,0 edge1=1,0,0 edge2=2,0,0"), "no area"));
        EXPECT_TRUE(contains(msg("directional direction=0,-1,0 spread_deg=90"), "[0, 90)"));
        EXPECT_TRUE(contains(msg(""), "empty"));
        EXPECT_TRUE(contains(msg("sphere radius"), "not key=value"));
    }

    TEST(DepositSources, ReadsATomlFile)
    {
        const auto path = write_file("good.toml", R"(# two sources
[[source]]
type = "sphere"
center = [0, 5, 0]
radius = 1

[[source]]
type = "directional"
direction = [0.0, -1.0, 0.0]
spread_deg = 10
strength = 0.5
)");
        const std::vector<DepositSource> sources = load_sources_file(path);
        ASSERT_EQ(sources.size(), 2u);
        EXPECT_EQ(sources[0].kind, DepositSource::Kind::Sphere);
        EXPECT_EQ(sources[0].center, Imath::V3f(0.0f, 5.0f, 0.0f));
        EXPECT_EQ(sources[1].kind, DepositSource::Kind::Directional);
        EXPECT_FLOAT_EQ(sources[1].strength, 0.5f);
    }

    TEST(DepositSources, TomlErrorsNameFileLineAndKey)
    {
        const auto unknown = write_file("unknown_key.toml", R"([[source]]
type = "sphere"
center = [0, 5, 0]
radius = 1

[[source]]
type = "disc"
centre = [0, 5, 0]
)");
        const std::string a = message_of([&] { load_sources_file(unknown); });
        EXPECT_TRUE(contains(a, unknown.string() + ":8:")) << a;
        EXPECT_TRUE(contains(a, "unknown key 'centre'")) << a;

        const auto missing = write_file("missing_key.toml", "[[source]]\ntype = \"sphere\"\n"
                                                            "center = [0, 5, 0]\n");
        const std::string b = message_of([&] { load_sources_file(missing); });
        EXPECT_TRUE(contains(b, missing.string() + ":")) << b;
        EXPECT_TRUE(contains(b, "needs 'radius'")) << b;

        const auto wrong_type = write_file("wrong_type.toml", "[[source]]\ntype = \"sphere\"\n"
                                                              "center = [0, 5, 0]\n"
                                                              "radius = \"big\"\n");
        const std::string c = message_of([&] { load_sources_file(wrong_type); });
        EXPECT_TRUE(contains(c, wrong_type.string() + ":4:")) << c;
        EXPECT_TRUE(contains(c, "'radius'")) << c;

        const auto syntax = write_file("syntax.toml", "[[source]]\ntype = \"sphere\"\n"
                                                      "center = [0, 5, 0\nradius = 1\n");
        const std::string d = message_of([&] { load_sources_file(syntax); });
        EXPECT_TRUE(contains(d, syntax.string() + ":4:")) << d;

        const auto stray = write_file("stray.toml", "sources = 1\n");
        const std::string e = message_of([&] { load_sources_file(stray); });
        EXPECT_TRUE(contains(e, stray.string() + ":1:")) << e;
        EXPECT_TRUE(contains(e, "unknown key 'sources'")) << e;

        const auto out_of_range = write_file("range.toml", "[[source]]\ntype = \"directional\"\n"
                                                           "direction = [0, -1, 0]\n"
                                                           "spread_deg = 95\n");
        const std::string f = message_of([&] { load_sources_file(out_of_range); });
        EXPECT_TRUE(contains(f, out_of_range.string() + ":4:")) << f;
        EXPECT_TRUE(contains(f, "spread_deg")) << f;

        const std::string g = message_of(
            [&] { load_sources_file(test::scratch("deposit_sources_test", "none.toml")); });
        EXPECT_TRUE(contains(g, "none.toml")) << g;
        EXPECT_TRUE(contains(g, "does not exist")) << g;
    }

} // namespace
} // namespace patina::texgen
