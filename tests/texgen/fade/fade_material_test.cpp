// The shipped fading materials (shaders/fade/*.toml) and the rules of the format.
#include "texgen/fade/fade_material.h"

#include "test_util.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

namespace fs = std::filesystem;
using namespace patina::texgen::fade;

namespace {

FadeLibrary shipped()
{
    const fs::path dir = fs::path(PATINA_SOURCE_DIR) / "shaders" / "fade";
    return FadeLibrary::load_files({dir / "paper.toml", dir / "pigments.toml"});
}

std::string load_error(const std::string& text)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "fade_materials";
    fs::create_directories(dir);
    const fs::path file = dir / "bad.toml";
    std::ofstream(file) << text;
    return patina::test::message_of([&] { FadeLibrary().load(file); });
}

const char* kGood = R"(
[colorants.dye]
absorption_per_m = { nm = [400, 500], value = [1e5, 2e5] }
fading = { rate = 1e-9 }
[materials.m]
thickness_um = 10
colorants = { dye = 0.1 }
)";

}  // namespace

TEST(FadeMaterial, ShippedMaterialsLoadWithThePapersRates)
{
    const FadeLibrary lib = shipped();
    for (const char* name : {"newsprint", "newsprint_free", "congo_red", "toluidine_blue_o",
                             "cork", "cyan", "magenta", "yellow", "cyan_magenta_yellow"})
        EXPECT_NE(lib.find(name), nullptr) << name;
    const FadeMaterial& news = lib.material("newsprint");
    EXPECT_NEAR(news.thickness_m, 70e-6, 1e-15);  // §5: 70 µm
    // §5.1: lignin at the midpoint of 20-27%; its product starts at 0 (added by the loader).
    EXPECT_EQ(news.initial_fractions[news.colorant_index("lignin")], 0.235);
    EXPECT_EQ(news.initial_fractions[news.colorant_index("o_quinone")], 0.0);
    // Table II, Table III.
    const Colorant& lignin = news.colorants[news.colorant_index("lignin")];
    EXPECT_EQ(lignin.fading.rate_m3_per_j, 1.670e-9);
    EXPECT_EQ(lignin.fading.cutoff_nm, 400.0);
    ASSERT_TRUE(lignin.breakdown.has_value());
    EXPECT_EQ(lignin.breakdown->product, "o_quinone");
    EXPECT_EQ(lignin.breakdown->rate.rate_m3_per_j, 1.670e-9);
    EXPECT_EQ(lib.colorant("newsprint_other").fading.rate_m3_per_j, 1.002e-8);
    EXPECT_EQ(lib.colorant("cork_other").fading.rate_m3_per_j, 2.000e-13);
    EXPECT_EQ(lib.colorant("congo_red").fading.rate_m3_per_j, 1.336e-13);
    EXPECT_EQ(lib.colorant("toluidine_blue_o").fading.rate_m3_per_j, 1.336e-13);
    // §5.3: cork holds 22.7% lignin.
    const FadeMaterial& cork = lib.material("cork");
    EXPECT_EQ(cork.initial_fractions[cork.colorant_index("lignin")], 0.227);
    // Table V, rows 1-4, at 500 nm.
    EXPECT_EQ(lib.colorant("yellow").fading.reference_nm, 500.0);
    EXPECT_EQ(lib.rate_set("table_v_row4").at("yellow"), 2.511e-7);
    EXPECT_EQ(lib.rate_set("table_v_row3").at("magenta"), 1.217e-7);
    const FadeMaterial row2 = with_rates(lib.material("cyan_magenta_yellow"),
                                         lib.rate_set("table_v_row2"));
    EXPECT_EQ(row2.colorants[row2.colorant_index("magenta")].fading.rate_m3_per_j, 4.867e-8);
    EXPECT_THROW(with_rates(lib.material("cyan"), lib.rate_set("table_v_row1")),
                 std::runtime_error);  // cyan alone holds no magenta
}

TEST(FadeMaterial, TyposAndBadValuesNameTheFileAndKey)
{
    EXPECT_EQ(load_error(kGood), "(no exception)");
    auto expect = [](const std::string& text, const std::string& part1, const std::string& part2) {
        const std::string msg = load_error(text);
        EXPECT_NE(msg.find("bad.toml:"), std::string::npos) << msg;
        EXPECT_NE(msg.find(part1), std::string::npos) << msg;
        EXPECT_NE(msg.find(part2), std::string::npos) << msg;
    };
    std::string t = kGood;
    expect(std::string(kGood).replace(t.find("thickness_um"), 12, "thicknes_um"),
           "materials.m.thicknes_um", "unknown key");
    expect(std::string(kGood).replace(t.find("dye = 0.1"), 9, "dey = 0.1"),
           "materials.m.colorants.dey", "unknown colorant");
    expect(std::string(kGood).replace(t.find("[400, 500]"), 10, "[500, 400]"),
           "colorants.dye.absorption_per_m.nm", "increase");
    expect(std::string(kGood).replace(t.find("rate = 1e-9"), 11, "rate = -1e-9"),
           "colorants.dye.fading.rate", ">= 0");
    expect(std::string(kGood).replace(t.find("dye = 0.1"), 9, "dye = 1.5"),
           "materials.m.colorants.dye", "<= 1");
    expect(std::string(kGood) + "[colorants.x]\nscattering_per_m = 1.0\n", "colorants.x",
           "missing key 'absorption_per_m'");
    expect(std::string(kGood) +
               "[colorants.y]\nabsorption_per_m = 1.0\nbreakdown = { product = \"zz\", rate = 1 }\n",
           "colorants.y.breakdown.product", "unknown colorant 'zz'");
    // A syntax error names its line.
    const std::string msg = load_error("[materials.m\nthickness_um = 1\n");
    EXPECT_NE(msg.find("bad.toml:1:"), std::string::npos) << msg;
}

TEST(FadeMaterial, UnknownMaterialListsTheKnownOnes)
{
    const FadeLibrary lib = shipped();
    const std::string msg = patina::test::message_of([&] { lib.material("newsprnt"); });
    EXPECT_NE(msg.find("newsprint"), std::string::npos) << msg;
}

TEST(FadeMaterial, MeasuredSpectraComeFromACsvFile)
{
    // Measured absorption and scattering per unit volume fraction (1/m), as a spectral CSV
    // beside the material file: read as its knots; a broken row is named by its line.
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "fade_materials";
    fs::create_directories(dir);
    std::ofstream(dir / "measured.csv") << "# K and S of a dye, 1/m per unit fraction\n"
                                           "wavelength_nm,K,S\n400,1e5,2e3\n500,3e5,2e3\n600,5e4,2e3\n";
    std::ofstream(dir / "broken.csv") << "wavelength_nm,K\n400,1e5\n500,oops\n";
    const std::string text = R"(
[colorants.dye]
absorption_per_m = { file = "measured.csv", column = "K" }
scattering_per_m = { file = "measured.csv", column = "S" }
fading = { rate = 1e-9 }
[materials.m]
thickness_um = 10
colorants = { dye = 0.1 }
)";
    std::ofstream(dir / "measured.toml") << text;
    FadeLibrary lib;
    lib.load(dir / "measured.toml");
    const Colorant& dye = lib.colorant("dye");
    EXPECT_EQ(dye.absorption_per_m.nm, (std::vector<double>{400, 500, 600}));
    EXPECT_EQ(dye.absorption_per_m.value, (std::vector<double>{1e5, 3e5, 5e4}));
    EXPECT_DOUBLE_EQ(dye.scattering_per_m.at(550.0), 2e3);

    std::string broken = text;
    broken.replace(broken.find("\"measured.csv\", column = \"K\""), 28, "\"broken.csv\", column = \"K\"");
    const std::string msg = load_error(broken);
    EXPECT_NE(msg.find("colorants.dye.absorption_per_m"), std::string::npos) << msg;
    EXPECT_NE(msg.find("broken.csv:3"), std::string::npos) << msg;
}
