// Parameter binding from TOML: names, types, ranges, defaults, colour spaces, messages.
#include "host/host.h"
#include "host/plugin_registry.h"
#include "host/shader_instance.h"

#include "core/image_io.h"

#include <gtest/gtest.h>

#include <fstream>

#include <filesystem>

namespace fs = std::filesystem;

namespace {

class ShaderInstanceTest : public ::testing::Test {
protected:
    void SetUp() override
    {
        registry.load_file(fs::path(PATINA_FIXTURE_PLUGIN_DIR) / "good" / "patina_fixture_good.so");
    }

    // Binds `toml_text` to the fixture shader and reads the bound values back through eval
    // at a shading point with texture coordinates `uv`.
    std::array<float, PATINA_MAX_WAVELENGTHS> bind(std::string_view toml_text,
                                                   PatinaVec2 uv = {0.5f, 0.5f})
    {
        const toml::table params = toml::parse(toml_text, std::string_view("scene.toml"));
        auto inst = patina::create_shader_instance(registry, "fixture_diffuse", params, "probe",
                                                   {"scene.toml", PATINA_TEST_BUILD_DIR, {"type"}});
        std::array<float, PATINA_MAX_WAVELENGTHS> f{};
        PatinaWavelengths wl{8, {400, 450, 500, 550, 600, 650, 700, 750}};
        PatinaShadingContext ctx{};
        ctx.uv = uv;
        inst->bsdf()->eval(inst->get(), &ctx, {0, 0, 1}, {0, 0, 1}, &wl, f.data());
        return f;
    }

    std::string error_of(std::string_view toml_text)
    {
        try {
            bind(toml_text);
        } catch (const patina::ParamError& e) {
            return e.what();
        }
        ADD_FAILURE() << "no ParamError for: " << toml_text;
        return {};
    }

    patina::PluginRegistry registry{patina::default_host().c_host()};
};

}  // namespace

TEST_F(ShaderInstanceTest, DefaultsFillMissingParameters)
{
    const auto f = bind("type = 'fixture_diffuse'");
    EXPECT_FLOAT_EQ(f[0], 0.5f);  // weight default
    EXPECT_FLOAT_EQ(f[1], 3.0f);  // count default
    EXPECT_FLOAT_EQ(f[2], 0.0f);  // flag default
    // Default spectrum is the table (400, 0.25) - (700, 0.75): at 500 nm 0.25 + 0.5/3.
    EXPECT_NEAR(f[3], 0.25f + 0.5f / 3.0f, 1e-6f);
    // Default colour is a 0.5 grey: uplifted exactly to the constant 0.5.
    EXPECT_EQ(f[4], 0.5f);
    EXPECT_FLOAT_EQ(f[5], 0.0f);
}

TEST_F(ShaderInstanceTest, ValuesOfEveryTypeBind)
{
    const auto f = bind(R"(
        weight = 0.25
        count = 7
        flag = true
        color = 0.8
        spectrum = [[400.0, 1.0], [600.0, 3.0]]
        mode = "slow"
    )");
    EXPECT_FLOAT_EQ(f[0], 0.25f);
    EXPECT_FLOAT_EQ(f[1], 7.0f);
    EXPECT_FLOAT_EQ(f[2], 1.0f);
    EXPECT_FLOAT_EQ(f[3], 2.0f);
    EXPECT_EQ(f[4], 0.8f);  // grey stays a constant spectrum exactly
    EXPECT_FLOAT_EQ(f[5], 1.0f);
}

TEST_F(ShaderInstanceTest, IntegerIsAcceptedForAFloatAndConstantSpectrum)
{
    const auto f = bind("weight = 1\nspectrum = 2");
    EXPECT_FLOAT_EQ(f[0], 1.0f);
    EXPECT_FLOAT_EQ(f[3], 2.0f);
}

TEST_F(ShaderInstanceTest, UnknownParameterIsAnErrorWithSuggestion)
{
    const std::string msg = error_of("weigth = 0.3");
    EXPECT_NE(msg.find("scene.toml:1:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'weigth'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("unknown parameter"), std::string::npos) << msg;
    EXPECT_NE(msg.find("did you mean 'weight'"), std::string::npos) << msg;
}

TEST_F(ShaderInstanceTest, OutOfRangeValueNamesTheParameter)
{
    const std::string msg = error_of("\n\nweight = 1.5");
    EXPECT_NE(msg.find("scene.toml:3:"), std::string::npos) << msg;
    EXPECT_NE(msg.find("parameter 'weight'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("outside the range [0, 1]"), std::string::npos) << msg;
    EXPECT_NE(error_of("count = 0").find("parameter 'count'"), std::string::npos);
    EXPECT_NE(error_of("color = [0.2, 1.2, 0.3]").find("parameter 'color'"), std::string::npos);
    EXPECT_NE(error_of("spectrum = [[400.0, -1.0]]").find("parameter 'spectrum'"), std::string::npos);
}

TEST_F(ShaderInstanceTest, WrongTypesAreErrors)
{
    EXPECT_NE(error_of("weight = 'heavy'").find("expected a number, got a string"), std::string::npos);
    EXPECT_NE(error_of("count = 2.5").find("expected an integer"), std::string::npos);
    EXPECT_NE(error_of("flag = 1").find("expected true or false"), std::string::npos);
    EXPECT_NE(error_of("color = [1, 2]").find("3 components"), std::string::npos);
    EXPECT_NE(error_of("mode = 3").find("expected a string"), std::string::npos);
    EXPECT_NE(error_of("spectrum = [[500.0, 1.0], [400.0, 1.0]]").find("increase"), std::string::npos);
    EXPECT_NE(error_of("weight = nan").find("not a finite number"), std::string::npos);
}

TEST_F(ShaderInstanceTest, UnknownColourSpaceIsNamed)
{
    const std::string msg = error_of("color = { rgb = [0.5, 0.2, 0.1], colorspace = 'sRGB-ish' }");
    EXPECT_NE(msg.find("unknown colour space 'sRGB-ish'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("parameter 'color'"), std::string::npos) << msg;
}

TEST_F(ShaderInstanceTest, ColourInAnotherSpaceIsConvertedToTheWorkingSpace)
{
    // A grey is grey in every RGB space with the same white: sRGB-encoded 0.5 is linear
    // 0.21404 (IEC 61966-2-1 transfer function), still a constant spectrum.
    const auto f = bind("color = { rgb = [0.5, 0.5, 0.5], colorspace = 'srgb_texture' }");
    EXPECT_NEAR(f[4], 0.214041f, 2e-4f);
}

TEST_F(ShaderInstanceTest, PluginRefusalIsReportedWithItsMessage)
{
    const std::string msg = error_of("mode = 'medium'");
    EXPECT_NE(msg.find("mode must be 'fast' or 'slow'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("shader 'probe' (fixture_diffuse)"), std::string::npos) << msg;
}

TEST_F(ShaderInstanceTest, ShaderThatNoPluginProvides)
{
    const toml::table params;
    try {
        patina::create_shader_instance(registry, "velvet", params, "cloth", {"scene.toml", {}, {}});
        FAIL() << "expected an error";
    } catch (const patina::ParamError& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("no plugin provides shader 'velvet'"), std::string::npos) << msg;
        EXPECT_NE(msg.find("scene.toml"), std::string::npos) << msg;
    }
}

TEST_F(ShaderInstanceTest, DescriptionListsEveryParameter)
{
    const std::string text = patina::describe_shader(*registry.get("fixture_diffuse").desc);
    for (const char* name : {"weight", "count", "flag", "color", "spectrum", "mode", "map",
                             "data"})
        EXPECT_NE(text.find(name), std::string::npos) << name;
    EXPECT_NE(text.find("[0, 1]"), std::string::npos) << text;
}

TEST_F(ShaderInstanceTest, TextureIsOpenedRelativeToTheSceneAndLookedUpInMeshUv)
{
    // A 2x2 raw texture; rows run top to bottom in the file: top (10, 20), bottom (30, 40).
    const float pixels[4] = {10.0f, 20.0f, 30.0f, 40.0f};
    patina::TextureOptions opt;
    opt.format = OIIO::TypeDesc::FLOAT;
    patina::make_texture_atomic(fs::path(PATINA_TEST_BUILD_DIR) / "fixture_map.exr", pixels, 2, 2,
                                1, {"Y"}, opt);
    EXPECT_FLOAT_EQ(bind("").at(6), -1.0f);  // no map: the plugin sees a NULL handle
    // Mesh uv has v = 0 at the bottom of the image: (0.25, 0.25) is the bottom-left texel.
    EXPECT_NEAR(bind("map = 'fixture_map.exr'", {0.25f, 0.25f}).at(6), 30.0f, 1e-4f);
    EXPECT_NEAR(bind("map = 'fixture_map.exr'", {0.75f, 0.75f}).at(6), 20.0f, 1e-4f);
    EXPECT_NEAR(bind("map = { file = 'fixture_map.exr', colorspace = 'raw' }", {0.25f, 0.75f}).at(6),
                10.0f, 1e-4f);
    const std::string msg = error_of("map = 'no_such_map.exr'");
    EXPECT_NE(msg.find("parameter 'map'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("no_such_map.exr"), std::string::npos) << msg;
}

TEST_F(ShaderInstanceTest, DataFileIsResolvedAgainstTheSceneAndMustExist)
{
    // ABI 1.1 PATINA_PARAM_FILE: the plugin gets an absolute path (the fixture refuses a
    // relative one) of a file that exists.
    const fs::path file = fs::path(PATINA_TEST_BUILD_DIR) / "fixture_data.toml";
    std::ofstream(file) << "x = 1\n";
    EXPECT_FLOAT_EQ(bind("").at(7), 0.0f);
    EXPECT_FLOAT_EQ(bind("data = 'fixture_data.toml'").at(7),
                    static_cast<float>(fs::absolute(file).string().size()));
    const std::string msg = error_of("data = 'no_such_stack.toml'");
    EXPECT_NE(msg.find("parameter 'data'"), std::string::npos) << msg;
    EXPECT_NE(msg.find("no such file"), std::string::npos) << msg;
    EXPECT_NE(msg.find("no_such_stack.toml"), std::string::npos) << msg;
}

// A plugin reading its values by name (patina/plugin_support.h Parameters) is refused at
// create when it reads a name its table does not declare, or a declared one as another
// type: the host's error names the shader and the parameter, instead of a silently rebound
// value.
TEST(ParametersByName, MisnamedOrMistypedReadIsCaughtAtCreate)
{
    patina::PluginRegistry registry{patina::default_host().c_host()};
    registry.load_file(fs::path(PATINA_FIXTURE_PLUGIN_DIR) / "by_name" /
                       "patina_fixture_by_name.so");
    auto create = [&](const char* type) {
        const toml::table params{{"type", type}, {"albedo", 0.25}};
        return patina::create_shader_instance(registry, type, params, "probe",
                                              {"scene.toml", PATINA_TEST_BUILD_DIR, {"type"}});
    };
    auto error_of = [&](const char* type) -> std::string {
        try {
            create(type);
        } catch (const std::exception& e) {
            return e.what();
        }
        ADD_FAILURE() << type << " was created";
        return {};
    };
    // Read right: the value arrives by name.
    const auto good = create("fixture_by_name");
    std::array<float, PATINA_MAX_WAVELENGTHS> f{};
    PatinaWavelengths wl{1, {550}};
    PatinaShadingContext ctx{};
    good->bsdf()->eval(good->get(), &ctx, {0, 0, 1}, {0, 0, 1}, &wl, f.data());
    EXPECT_FLOAT_EQ(f[0], 0.25f * 0.318309886f);

    const std::string misnamed = error_of("fixture_misnamed");
    EXPECT_NE(misnamed.find("fixture_misnamed"), std::string::npos) << misnamed;
    EXPECT_NE(misnamed.find("reads parameter 'albedoo', which it does not declare"),
              std::string::npos) << misnamed;
    const std::string mistyped = error_of("fixture_mistyped");
    EXPECT_NE(mistyped.find("parameter 'albedo' is declared float but read as int"),
              std::string::npos) << mistyped;
}
