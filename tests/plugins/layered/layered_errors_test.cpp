// Bad input to the layered shader: every error names the file (and line or key) through
// host->error, and create returns no instance.
#include "layered_fixture.h"

namespace patina::test {
namespace {

    const TestMaterial kCopper{"copper", true, 0, -1, 0, 0.9f, 0.2f, 0.27f, 3.4f};
    const TestMaterial kGreen{"green", false, 0.6f, 0.1f, 0.35f, 0.04f, 0.5f};

    fs::path good_stack(const std::string& name)
    {
        return write_stack(name, {"copper", {{"green", 1.0f}}, {kCopper, kGreen}});
    }

    std::string read(const fs::path& p)
    {
        std::ifstream in(p);
        return std::string(std::istreambuf_iterator<char>(in), {});
    }

    void replace(const fs::path& p, const std::string& from, const std::string& to)
    {
        std::string text = read(p);
        const size_t at = text.find(from);
        ASSERT_NE(at, std::string::npos) << from;
        text.replace(at, from.size(), to);
        std::ofstream(p) << text;
    }

}  // namespace

TEST(LayeredErrors, MissingThicknessMap)
{
    const fs::path p = good_stack("err_map");
    fs::remove(p.parent_path() / "layer1.exr");
    const Layered l(p);
    EXPECT_FALSE(l);
    EXPECT_NE(l.errors().find("layer 1"), std::string::npos) << l.errors();
    EXPECT_NE(l.errors().find("layer1.exr"), std::string::npos) << l.errors();
}

TEST(LayeredErrors, UnknownMaterial)
{
    const fs::path p = good_stack("err_material");
    replace(p, "material = 'green'", "material = 'verdigris'");
    const Layered l(p);
    EXPECT_FALSE(l);
    EXPECT_NE(l.errors().find("verdigris"), std::string::npos) << l.errors();
    EXPECT_NE(l.errors().find("stack.toml:"), std::string::npos) << l.errors();
}

TEST(LayeredErrors, TomlSyntaxErrorNamesTheLine)
{
    const fs::path p = good_stack("err_syntax");
    replace(p, "base = 'copper'", "base = 'copper");
    const Layered l(p);
    EXPECT_FALSE(l);
    EXPECT_NE(l.errors().find("stack.toml:"), std::string::npos) << l.errors();
}

TEST(LayeredErrors, NewerStackFormatIsRefused)
{
    // A manifest of a layout this build does not know is refused before anything is read,
    // naming the file, the line and both versions.
    const fs::path p = good_stack("err_format");
    const std::string text = read(p);
    std::ofstream(p) << "[stack]\nformat = 2\n\n" << text;
    const Layered l(p);
    EXPECT_FALSE(l);
    EXPECT_NE(l.errors().find("stack.toml:2:"), std::string::npos) << l.errors();
    EXPECT_NE(l.errors().find("stack format 2 is newer than the 1"), std::string::npos)
        << l.errors();
}

TEST(LayeredErrors, StackWithoutMaterialsSection)
{
    const fs::path p = good_stack("err_old");
    std::string text = read(p);
    text = text.substr(0, text.find("[patina.materials"));
    std::ofstream(p) << text;
    const Layered l(p);
    EXPECT_FALSE(l);
    EXPECT_NE(l.errors().find("[patina.materials]"), std::string::npos) << l.errors();
}

TEST(LayeredErrors, BadTablesAndParameters)
{
    {
        const fs::path p = good_stack("err_length");
        replace(p, "scattering_per_um = [0.349999994, 0.349999994]",
                "scattering_per_um = [0.35, 0.35, 0.35]");
        const Layered l(p);
        EXPECT_FALSE(l);
        EXPECT_NE(l.errors().find("scattering_per_um"), std::string::npos) << l.errors();
    }
    {
        const fs::path p = good_stack("err_negative");
        replace(p, "absorption_per_um = [0.600000024", "absorption_per_um = [-1");
        const Layered l(p);
        EXPECT_FALSE(l);
        EXPECT_NE(l.errors().find("absorption_per_um"), std::string::npos) << l.errors();
    }
    {
        const Layered l(good_stack("err_model"), "montecarlo");
        EXPECT_FALSE(l);
        EXPECT_NE(l.errors().find("model"), std::string::npos) << l.errors();
    }
    {
        const fs::path p = good_stack("err_nometal");
        replace(p, "n = [0.270000011, 0.270000011]\n", "");
        const Layered l(p);
        EXPECT_FALSE(l);
        EXPECT_NE(l.errors().find("'n'"), std::string::npos) << l.errors();
    }
}

TEST(LayeredErrors, UnknownChannelOfAMultiChannelMap)
{
    const fs::path p = write_stack("err_channel", {"copper", {{"green", 1.0f}, {"green", 0.5f}},
                                                   {kCopper, kGreen}},
                                   MapLayout::one_map);
    replace(p, "channel = 'c0_layer2'", "channel = 'layer7'");
    const Layered l(p);
    EXPECT_FALSE(l);
    EXPECT_NE(l.errors().find("channel 'layer7'"), std::string::npos) << l.errors();
    EXPECT_NE(l.errors().find("stack.toml:"), std::string::npos) << l.errors();
}

}  // namespace patina::test
