// The texture stack's one reader and writer (formats/texture_stack/texture_stack.h): a round trip of every
// key, the refusals, and the two consumers of a patina stack (the layered_km plugin's
// reader and flatten's) seeing the same layers, channels and optics.
#include "formats/texture_stack/texture_stack.h"
#include "formats/texture_stack/stack_format.h"

#include "layered/stack_file.h"

#include "core/color_management.h"
#include "texgen/flatten/flatten_stack.h"
#include "texgen/flatten/patina_stack_files.h"
#include "texgen/patina/stack_materials.h"
#include "test_util.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>

namespace patina::formats {
namespace {

namespace fs = std::filesystem;

fs::path test_dir(const char* name)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "texture_stack_test" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

void touch(const fs::path& file)
{
    std::ofstream(file) << "x";
}

MaterialOptics layer_optics(const std::string& name)
{
    MaterialOptics m;
    m.name = name;
    m.description = "a test layer";
    m.roughness = 0.375;
    m.lambda_nm = {400.0, 550.0, 700.0};
    m.absorption_per_um = {0.5, 0.25, 0.125};
    m.scattering_per_um = {1.0, 1.5, 2.0};
    m.specular = {0.04, 0.04, 0.05};
    return m;
}

MaterialOptics metal_optics()
{
    MaterialOptics m;
    m.name = "copper";
    m.metal = true;
    m.roughness = 0.15;
    m.lambda_nm = {400.0, 550.0, 700.0};
    m.n = {1.2, 0.9, 0.2};
    m.k = {2.2, 2.6, 4.2};
    m.specular = {0.5, 0.6, 0.95};
    return m;
}

/// A stack of two layers in one two-channel UDIM map over two tiles, plus a lone map.
void write_stack(const fs::path& dir)
{
    StackMap thickness;
    thickness.name = "thickness";
    thickness.pattern = "thickness.<UDIM>.exr";
    thickness.tiles = {1001, 1002};
    thickness.channels = {"layer01_green", "layer02_black", kCoverageChannel};
    thickness.coverage = kCoverageChannel;
    thickness.units = "um";
    thickness.baker = "patina";
    thickness.description = "layer thicknesses";
    thickness.width = 64;
    thickness.height = 32;
    thickness.parameters.insert_or_assign("strip_size_m", 0.25);
    StackMap total = thickness;
    total.name = "total_thickness";
    total.pattern = "total_thickness.<UDIM>.exr";
    total.channels = {"thickness", kCoverageChannel};
    StackMap ao;
    ao.name = "ao";
    ao.file = "ao.exr";
    ao.channels = {"ao"};
    ao.units = "1";
    ao.baker = "ao";
    for (const StackMap* m : {&thickness, &total})
        for (const fs::path& f : m->files(dir))
            touch(f);
    touch(dir / "ao.exr");

    PatinaTable p;
    p.script = "urban.patina";
    p.time_years = 30.5;
    p.base = "copper";
    p.preview = "preview.png";
    PatinaLayer green;
    green.material = "green";
    green.map = "thickness";
    green.channel = "layer01_green";
    green.made_by = "coat";
    green.mean_um = 1.5;
    green.max_um = 3.25;
    green.coverage = 0.75;
    PatinaLayer black = green;
    black.material = "black";
    black.channel = "layer02_black";
    black.channel_index = 1;
    p.layers = {green, black};
    p.materials = {{"copper", metal_optics()},
                   {"green", layer_optics("green")},
                   {"black", layer_optics("black")}};

    toml::table maps;
    for (const StackMap* m : {&thickness, &total, &ao})
        maps.insert_or_assign(m->name, to_toml(*m));
    FlattenTable f;
    f.stack = "../t30";
    f.color_space = "srgb_texture";
    f.texel_size_m = 0.00039;
    f.normal_scale = 2.5;
    f.gltf_target = "blender";
    f.interfaces = {{"interface00_copper_specular", "interface00_copper_roughness"}};
    const toml::table root{{"stack", toml::table{{"format", kStackFormatVersion}}},
                           {"maps", maps},
                           {"patina", to_toml(p)},
                           {"flatten", to_toml(f)}};
    std::ofstream(dir / kStackManifest) << root << "\n";
}

std::string read_text(const fs::path& file)
{
    std::ifstream in(file);
    return {std::istreambuf_iterator<char>(in), {}};
}

void write_text(const fs::path& file, const std::string& text)
{
    std::ofstream(file) << text;
}

TEST(TextureStackFormat, RoundTripsEveryKey)
{
    const fs::path dir = test_dir("round_trip");
    write_stack(dir);
    const TextureStack s = read_texture_stack(dir);
    EXPECT_EQ(s.manifest, dir / kStackManifest);
    EXPECT_EQ(s.format, kStackFormatVersion);
    ASSERT_EQ(s.maps.size(), 3u);

    const StackMap& t = s.map("thickness");
    EXPECT_EQ(t.pattern, "thickness.<UDIM>.exr");
    EXPECT_EQ(t.tiles, (std::vector<int>{1001, 1002}));
    EXPECT_EQ(t.udims(), t.tiles);
    EXPECT_EQ(t.files(dir)[1], dir / "thickness.1002.exr");
    EXPECT_EQ(t.channels.size(), 3u);
    EXPECT_EQ(t.coverage, kCoverageChannel);
    EXPECT_EQ(t.channel_index("layer02_black"), 1);
    EXPECT_EQ(t.units, "um");
    EXPECT_EQ(t.colorspace, "raw");
    EXPECT_EQ(t.baker, "patina");
    EXPECT_EQ(t.description, "layer thicknesses");
    EXPECT_EQ(t.width, 64);
    EXPECT_EQ(t.height, 32);
    EXPECT_EQ(t.parameters["strip_size_m"].value<double>(), 0.25);
    const StackMap& ao = s.map("ao");
    EXPECT_EQ(ao.file, "ao.exr");
    EXPECT_EQ(ao.udims(), std::vector<int>{1001});
    EXPECT_EQ(ao.files(dir).front(), dir / "ao.exr");

    ASSERT_TRUE(s.patina);
    const PatinaTable& p = *s.patina;
    EXPECT_EQ(p.script, "urban.patina");
    EXPECT_EQ(p.time_years, 30.5);
    EXPECT_EQ(p.base, "copper");
    EXPECT_EQ(p.preview, "preview.png");
    EXPECT_EQ(p.total_thickness, "total_thickness");
    ASSERT_EQ(p.layers.size(), 2u);
    EXPECT_EQ(p.layers[1].material, "black");
    EXPECT_EQ(p.layers[1].channel, "layer02_black");
    EXPECT_EQ(p.layers[1].channel_index, 1);
    EXPECT_EQ(p.layers[0].made_by, "coat");
    EXPECT_EQ(p.layers[0].mean_um, 1.5);
    EXPECT_EQ(p.layers[0].max_um, 3.25);
    EXPECT_EQ(p.layers[0].coverage, 0.75);
    ASSERT_EQ(p.materials.size(), 3u);
    EXPECT_EQ(optics_difference(p.materials.at("copper"), metal_optics(), 0.0), "");
    EXPECT_EQ(optics_difference(p.materials.at("green"), layer_optics("green"), 0.0), "");
    EXPECT_EQ(p.materials.at("green").description, "a test layer");

    ASSERT_TRUE(s.flatten);
    const FlattenTable& f = *s.flatten;
    EXPECT_EQ(f.stack, "../t30");
    EXPECT_EQ(f.color_space, "srgb_texture");
    EXPECT_EQ(f.texel_size_m, 0.00039);
    EXPECT_EQ(f.normal_scale, 2.5);
    EXPECT_EQ(f.gltf_target, "blender");
    ASSERT_EQ(f.interfaces.size(), 1u);
    EXPECT_EQ(f.interfaces[0].roughness, "interface00_copper_roughness");
}

TEST(TextureStackFormat, ChannelByIndexOrByNameOrTheFirst)
{
    const fs::path dir = test_dir("channels");
    write_stack(dir);
    std::string text = read_text(dir / kStackManifest);
    // The second layer's channel by index, the first's left out: both name the same channels.
    const size_t second = text.find("channel = 'layer02_black'");
    ASSERT_NE(second, std::string::npos);
    text.replace(second, std::string("channel = 'layer02_black'").size(), "channel = 1");
    const size_t first = text.find("channel = 'layer01_green'");
    ASSERT_NE(first, std::string::npos);
    text.erase(first, std::string("channel = 'layer01_green'").size());
    write_text(dir / kStackManifest, text);
    const PatinaTable p = patina_of(read_texture_stack(dir));
    EXPECT_EQ(p.layers[0].channel, "layer01_green");
    EXPECT_EQ(p.layers[0].channel_index, 0);
    EXPECT_EQ(p.layers[1].channel, "layer02_black");
    EXPECT_EQ(p.layers[1].channel_index, 1);
}

TEST(TextureStackFormat, BadInputsNameFileLineAndKey)
{
    const fs::path dir = test_dir("bad");
    write_stack(dir);
    const std::string good = read_text(dir / kStackManifest);
    auto message_with = [&](const std::string& from, const std::string& to) {
        std::string text = good;
        const size_t at = text.find(from);
        EXPECT_NE(at, std::string::npos) << from;
        if (at != std::string::npos)
            text.replace(at, from.size(), to);
        write_text(dir / kStackManifest, text);
        return test::message_of([&] { read_texture_stack(dir); });
    };
    std::string m = message_with("format = 1", "format = 3");
    EXPECT_NE(m.find("stack.toml:"), std::string::npos) << m;
    EXPECT_NE(m.find("stack format 3 is newer than the 1"), std::string::npos) << m;
    m = message_with("channel = 'layer02_black'", "channel = 'layer09'");
    EXPECT_NE(m.find("layer 2: channel 'layer09' is not in map 'thickness'"), std::string::npos)
        << m;
    m = message_with("channel = 'layer02_black'", "channel = 5");
    EXPECT_NE(m.find("'channel' 5 is not an index into map 'thickness''s 3 channels"),
              std::string::npos) << m;
    m = message_with("tiles = [ 1001, 1002 ]", "tiles = [ 1001, 'x' ]");
    EXPECT_NE(m.find("'tiles' must hold UDIM numbers"), std::string::npos) << m;
    m = message_with("roughness = 0.375", "roughness = 2");
    EXPECT_NE(m.find("'roughness' must be a number in [0, 1]"), std::string::npos) << m;
    EXPECT_NE(m.find("stack.toml:"), std::string::npos) << m;

    write_text(dir / kStackManifest, good);
    fs::remove(dir / "thickness.1002.exr");
    m = test::message_of([&] { read_texture_stack(dir); });
    EXPECT_NE(m.find("layer 1: map 'thickness': file"), std::string::npos) << m;
    EXPECT_NE(m.find("thickness.1002.exr' does not exist"), std::string::npos) << m;

    const fs::path series = test_dir("series");
    touch(series / "series.toml");
    m = test::message_of([&] { read_texture_stack(series); });
    EXPECT_NE(m.find("a time series"), std::string::npos) << m;
}

TEST(TextureStackFormat, SeriesRoundTripAndRefusals)
{
    const fs::path dir = test_dir("series_round_trip");
    StackSeries series;
    series.script = "urban.patina";
    series.steps = {{0.0, "t00"}, {6.5, "t06"}, {30.0, "t30"}};
    for (const SeriesStep& s : series.steps)
        fs::create_directories(dir / s.folder);
    write_text(dir / kSeriesManifest, stack_series_text(series));
    const StackSeries r = read_stack_series(dir);
    EXPECT_EQ(r.manifest, dir / kSeriesManifest);
    EXPECT_EQ(r.script, "urban.patina");
    ASSERT_EQ(r.steps.size(), 3u);
    EXPECT_EQ(r.steps[1].time_years, 6.5);
    EXPECT_EQ(r.steps[2].folder, "t30");

    fs::remove_all(dir / "t06");
    std::string m = test::message_of([&] { read_stack_series(dir); });
    EXPECT_NE(m.find("series.toml:"), std::string::npos) << m;
    EXPECT_NE(m.find("step 2: folder 't06' does not exist"), std::string::npos) << m;
    fs::create_directories(dir / "t06");
    std::string text = read_text(dir / kSeriesManifest);
    const size_t at = text.find("time_years = 6.5");
    ASSERT_NE(at, std::string::npos);
    text.replace(at, std::string("time_years = 6.5").size(), "time_years = 40.0");
    write_text(dir / kSeriesManifest, text);
    m = test::message_of([&] { read_stack_series(dir); });
    EXPECT_NE(m.find("step 3: times must ascend"), std::string::npos) << m;
}

// The two consumers of one stack, written by `patina-texgen patina`: the layered_km
// plugin's reader (plugins/layered/stack_file.cpp, compiled into this test) and flatten's
// (texgen/flatten) see the same base, the same layers bottom to top, the same file and
// channel for each, and the same optics.
TEST(TextureStackFormat, LayeredKmAndFlattenSeeOneStack)
{
    const fs::path dir = test_dir("consumers");
    const std::string command = std::string(PATINA_TEST_BIN_DIR) + "/patina-texgen patina '" +
                                PATINA_SOURCE_DIR + "/samples/copper_strips/urban.patina' -o '" +
                                (dir / "urban").string() +
                                "' --resolution 16 --quiet --no-preview";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;

    const layered::StackFile plugin = layered::read_stack_file(dir / "urban" / kStackManifest);
    const texgen::PatinaStackFiles flatten = texgen::read_patina_stack(dir / "urban");
    ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio/config.ocio");
    texgen::MaterialLibrary library;
    library.load(fs::path(PATINA_SOURCE_DIR) / "shaders/patina/copper.toml", colors);
    std::vector<const texgen::PatinaMaterial*> materials{library.find(flatten.base)};
    for (const texgen::StackLayerFiles& l : flatten.layers)
        materials.push_back(library.find(l.material));

    EXPECT_EQ(plugin.base, flatten.base);
    ASSERT_EQ(plugin.layers.size(), 5u);
    ASSERT_EQ(plugin.layers.size(), flatten.layers.size());
    ASSERT_EQ(materials.size(), flatten.layers.size() + 1);
    for (size_t l = 0; l < plugin.layers.size(); ++l) {
        SCOPED_TRACE("layer " + std::to_string(l + 1));
        EXPECT_EQ(plugin.layers[l].material, flatten.layers[l].material);
        ASSERT_EQ(flatten.layers[l].files.size(), 1u);
        EXPECT_EQ(plugin.layers[l].map_file, flatten.layers[l].files[0].lexically_normal());
        // The plugin's channel index is the file's channel that flatten reads by name.
        auto in = OIIO::ImageInput::open(plugin.layers[l].map_file.string());
        ASSERT_TRUE(in);
        const std::vector<std::string> names = in->spec().channelnames;
        ASSERT_LT(plugin.layers[l].channel, static_cast<int>(names.size()));
        EXPECT_EQ(names[static_cast<size_t>(plugin.layers[l].channel)], flatten.layers[l].channel);
    }
    // The optics: what the library resolved, recorded once, read alike by both (flatten
    // in double, the plugin in float).
    for (const texgen::PatinaMaterial* m : materials) {
        ASSERT_TRUE(m);
        SCOPED_TRACE(m->name);
        const MaterialOptics expected = texgen::stack_optics(*m, colors);
        EXPECT_EQ(optics_difference(flatten.materials.at(m->name), expected, 0.0), "");
        const layered::MaterialOptics& seen = plugin.materials.at(m->name);
        EXPECT_EQ(seen.metal, expected.metal);
        EXPECT_EQ(seen.roughness, static_cast<float>(expected.roughness));
        auto same = [](const std::vector<float>& a, const std::vector<double>& b) {
            return std::vector<float>(b.begin(), b.end()) == a;
        };
        EXPECT_TRUE(same(seen.lambda_nm, expected.lambda_nm));
        EXPECT_TRUE(same(seen.absorption_per_um, expected.absorption_per_um));
        EXPECT_TRUE(same(seen.scattering_per_um, expected.scattering_per_um));
        EXPECT_TRUE(same(seen.specular, expected.specular));
        EXPECT_TRUE(same(seen.n, expected.n));
        EXPECT_TRUE(same(seen.k, expected.k));
    }
}

}  // namespace
}  // namespace patina::formats
