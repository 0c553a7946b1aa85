// flatten_stack / write_flattened on a stack written in code: maps, colour spaces,
// manifest, and the bad inputs (missing stack, missing map, unknown material, NaN texel).
#include "texgen/flatten/flat_texel.h"
#include "texgen/flatten/flatten_stack.h"
#include "texgen/patina/stack_materials.h"

#include "core/image_io.h"
#include "test_util.h"

#include <fmt/format.h>
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iterator>
#include <limits>
#include <sstream>

namespace patina::texgen {
namespace {

namespace fs = std::filesystem;

constexpr int kSize = 16;

class FlattenStack : public ::testing::Test {
protected:
    void SetUp() override
    {
        dir_ = fs::path(PATINA_TEST_BUILD_DIR) / "flatten_stack_test" /
               ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::remove_all(dir_);
        fs::create_directories(dir_ / "stack");
        library_.load(fs::path(PATINA_SOURCE_DIR) / "shaders/patina/copper.toml", colors_);
    }

    /// A strip stack of 16x16 texels, 0.1 m wide: `layers` (material, thickness function).
    void write_stack(const std::vector<std::pair<std::string, std::vector<float>>>& layers)
    {
        std::string toml = "[stack]\nformat = 1\n\n";
        std::vector<float> total(kSize * kSize, 0.0f);
        std::string patina = "[patina]\nbase = 'copper'\ntime_years = 30.0\n"
                             "total_thickness = 'total_thickness'\n";
        auto map_entry = [&](const std::string& name, const std::vector<float>& values) {
            write_image_atomic(dir_ / "stack" / (name + ".exr"), values.data(), kSize, kSize, 1,
                               {"thickness"}, OIIO::TypeDesc::FLOAT);
            toml += fmt::format("[maps.{0}]\nfile = '{0}.exr'\nchannels = ['thickness']\n"
                                "resolution = [{1}, {1}]\n[maps.{0}.parameters]\n"
                                "strip_size_m = 0.1\n\n", name, kSize);
        };
        for (size_t l = 0; l < layers.size(); ++l) {
            const std::string name = fmt::format("layer{:02}", l + 1);
            map_entry(name, layers[l].second);
            for (size_t i = 0; i < total.size(); ++i)
                total[i] += layers[l].second[i];
            patina += fmt::format("[[patina.layers]]\nmaterial = '{}'\nmap = '{}'\n",
                                  layers[l].first, name);
        }
        map_entry("total_thickness", total);
        // The optics of the base and every layer, as the patina writer records them.
        std::vector<std::string> names = {"copper"};
        for (const auto& layer : layers)
            names.push_back(layer.first);
        std::ostringstream materials;
        for (const std::string& name : names) {
            // A name the library lacks (the UnknownMaterial case) gets tarnish's optics.
            const PatinaMaterial* m = library_.find(name);
            materials << "\n[patina.materials.\"" << name << "\"]\n"
                      << formats::to_toml(stack_optics(m ? *m : *library_.find("tarnish"), colors_))
                      << "\n";
        }
        std::ofstream(dir_ / "stack" / "stack.toml") << toml << patina << materials.str();
    }

    FlattenedStack flatten(FlattenOptions options = {})
    {
        const PatinaStackFiles stack = read_patina_stack(dir_ / "stack");
        return flatten_stack(stack, colors_, options);
    }

    std::vector<fs::path> flatten_to(const fs::path& out, FlattenOptions options = {})
    {
        const PatinaStackFiles stack = read_patina_stack(dir_ / "stack");
        const FlattenedStack flat = flatten_stack(stack, colors_, options);
        return write_flattened(out, flat, stack, options, colors_);
    }

    static std::vector<float> ramp(float scale)
    {
        std::vector<float> v(kSize * kSize);
        for (int y = 0; y < kSize; ++y)
            for (int x = 0; x < kSize; ++x)
                v[y * kSize + x] = scale * static_cast<float>(x) / (kSize - 1);
        return v;
    }

    fs::path dir_;
    ColorManager colors_{fs::path(PATINA_SOURCE_DIR) / "ocio/config.ocio"};
    MaterialLibrary library_;
};

TEST_F(FlattenStack, MapsHoldTheTexelsOfFlattenTexel)
{
    write_stack({{"tarnish", ramp(0.5f)}, {"rural patina 3", std::vector<float>(256, 2.0f)}});
    const fs::path out = dir_ / "out";
    const auto files = flatten_to(out);
    EXPECT_EQ(files.size(), 1 + 2 * 3 + 5 + 1u);  // + the manifest

    BandStack stack = band_stack(read_patina_stack(dir_ / "stack"));
    const BandsToRgb to_rgb(colors_);
    tabulate_lobe_albedos(stack, to_rgb);  // the glTF maps are fitted (khronos, the default)
    const GltfFitting fitting{&gltf_albedo_model(), GltfTarget::khronos};
    const ImageData diffuse = read_image(out / "diffuse_albedo.exr");
    const ImageData spec0 = read_image(out / "interface00_copper_specular.exr");
    const ImageData rough1 = read_image(out / "interface01_tarnish_roughness.exr");
    const ImageData height = read_image(out / "height.exr");
    const ImageData mr = read_image(out / "gltf_metallic_roughness.exr");
    const ImageData coat = read_image(out / "gltf_clearcoat.exr");
    ASSERT_EQ(diffuse.width, kSize);
    for (int x = 0; x < kSize; x += 5) {
        const float d[2] = {0.5f * x / (kSize - 1), 2.0f};
        const FlatTexel f = flatten_texel(stack, d, to_rgb, fitting);
        // Colour maps are sRGB-encoded through OCIO (lin_rec709 -> srgb_texture).
        Imath::V3f want = f.diffuse, want_spec = f.interfaces[0].specular;
        colors_.convert("lin_rec709", "srgb_texture", &want.x, 1);
        colors_.convert("lin_rec709", "srgb_texture", &want_spec.x, 1);
        for (int c = 0; c < 3; ++c) {
            EXPECT_NEAR(diffuse.at(x, 3, c), want[c], 1e-5) << x;
            EXPECT_NEAR(spec0.at(x, 3, c), want_spec[c], 1e-5) << x;
        }
        EXPECT_FLOAT_EQ(rough1.at(x, 3, 0), library_.find("tarnish")->roughness);
        EXPECT_FLOAT_EQ(height.at(x, 3, 0), d[0] + d[1]);
        EXPECT_FLOAT_EQ(mr.at(x, 3, mr.channel("G")), f.two_lobe.roughness);
        EXPECT_FLOAT_EQ(mr.at(x, 3, mr.channel("B")), f.two_lobe.metallic);
        EXPECT_FLOAT_EQ(coat.at(x, 3, coat.channel("R")), f.two_lobe.coat_weight);
    }

    // The manifest says what each map is and how it is encoded.
    const toml::table m = toml::parse_file((out / "stack.toml").string());
    EXPECT_EQ(m["maps"]["diffuse_albedo"]["colorspace"].value<std::string>(), "srgb_texture");
    EXPECT_EQ(m["maps"]["interface01_tarnish_specular"]["colorspace"].value<std::string>(),
              "srgb_texture");
    EXPECT_EQ(m["maps"]["interface01_tarnish_roughness"]["colorspace"].value<std::string>(),
              "raw");
    EXPECT_EQ(m["maps"]["normal"]["colorspace"].value<std::string>(), "raw");
    EXPECT_EQ(m["maps"]["height"]["units"].value<std::string>(), "um");
    EXPECT_EQ(m["maps"]["height"]["baker"].value<std::string>(), "flatten");
    EXPECT_EQ(m["flatten"]["interfaces"].as_array()->size(), 3u);
    const auto desc = m["maps"]["interface00_copper_specular"]["description"].value<std::string>();
    ASSERT_TRUE(desc);
    EXPECT_NE(desc->find("square of the KM diffuse transmittance"), std::string::npos);
}

TEST_F(FlattenStack, AcesCgAndAPlanarHeight)
{
    write_stack({{"cuprite", std::vector<float>(256, 0.7f)}});
    const fs::path out = dir_ / "out";
    FlattenOptions o;
    o.color_space = "acescg";
    o.half = true;
    flatten_to(out, o);
    const ImageData normal = read_image(out / "normal.exr");
    for (int y = 0; y < kSize; ++y)
        for (int x = 0; x < kSize; ++x) {
            // A planar height: the normal is (0, 0, 1), encoded (0.5, 0.5, 1).
            EXPECT_EQ(normal.at(x, y, normal.channel("R")), 0.5f);
            EXPECT_EQ(normal.at(x, y, normal.channel("G")), 0.5f);
            EXPECT_EQ(normal.at(x, y, normal.channel("B")), 1.0f);
        }
    const toml::table m = toml::parse_file((out / "stack.toml").string());
    EXPECT_EQ(m["maps"]["gltf_base_color"]["colorspace"].value<std::string>(), "ACEScg");
    // ACEScg is linear: the diffuse map is the Rec.709 value sent through OCIO.
    const float d[1] = {0.7f};
    const FlatTexel f =
        flatten_texel(band_stack(read_patina_stack(dir_ / "stack")), d, BandsToRgb(colors_));
    Imath::V3f want = f.diffuse;
    colors_.convert("lin_rec709", "ACEScg", &want.x, 1);
    const ImageData diffuse = read_image(out / "diffuse_albedo.exr");
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(diffuse.at(4, 4, c), want[c], 2e-3 * want[c] + 1e-4);  // half floats
}

TEST_F(FlattenStack, ResolutionResamples)
{
    write_stack({{"tarnish", std::vector<float>(256, 0.3f)}});
    FlattenOptions o;
    o.resolution = 32;
    const FlattenedStack flat = flatten(o);
    EXPECT_EQ(flat.width, 32);
    EXPECT_EQ(flat.height, 32);
    EXPECT_DOUBLE_EQ(flat.texel_size_m, 0.1 / 32);
    for (const FlatMap& map : flat.maps) {
        if (map.name != "height")
            continue;
        for (float v : map.tiles[0])
            EXPECT_NEAR(v, 0.3f, 1e-6f);
    }
}

TEST_F(FlattenStack, IntoTheStacksOwnFolder)
{
    write_stack({{"tarnish", ramp(0.5f)}});
    flatten_to(dir_ / "stack");
    const toml::table m = toml::parse_file((dir_ / "stack" / "stack.toml").string());
    EXPECT_TRUE(m["patina"]);  // the stack's own table and maps are kept
    EXPECT_TRUE(m["maps"]["layer01"]);
    EXPECT_TRUE(m["maps"]["diffuse_albedo"]);
}

TEST_F(FlattenStack, RerunWithFewerLayersDropsStaleMaps)
{
    write_stack({{"tarnish", ramp(0.5f)}, {"cuprite", ramp(1.0f)}});
    const fs::path out = dir_ / "out";
    flatten_to(out);
    ASSERT_TRUE(fs::exists(out / "interface02_cuprite_specular.exr"));
    write_stack({{"tarnish", ramp(0.5f)}});
    flatten_to(out);
    EXPECT_FALSE(fs::exists(out / "interface02_cuprite_specular.exr"));
    const toml::table m = toml::parse_file((out / "stack.toml").string());
    EXPECT_FALSE(m["maps"]["interface02_cuprite_specular"]);
    EXPECT_TRUE(m["maps"]["interface01_tarnish_specular"]);
}

TEST_F(FlattenStack, ALayerWithoutAChannelReadsItsMapsFirstChannel)
{
    // The rule layered_km follows (channel index 0): a map whose first channel is not
    // called "thickness" still gives the layer its thickness.
    write_stack({{"cuprite urban 2", ramp(3.0f)}});
    std::string toml;
    {
        std::ifstream in(dir_ / "stack" / "stack.toml");
        toml.assign(std::istreambuf_iterator<char>(in), {});
    }
    const std::vector<float> depth = ramp(3.0f);
    write_image_atomic(dir_ / "stack" / "layer01.exr", depth.data(), kSize, kSize, 1, {"depth"},
                       OIIO::TypeDesc::FLOAT);
    const std::string from = "[maps.layer01]\nfile = 'layer01.exr'\nchannels = ['thickness']";
    const size_t at = toml.find(from);
    ASSERT_NE(at, std::string::npos);
    toml.replace(at, from.size(), "[maps.layer01]\nfile = 'layer01.exr'\nchannels = ['depth']");
    std::ofstream(dir_ / "stack" / "stack.toml") << toml;
    const PatinaStackFiles stack = read_patina_stack(dir_ / "stack");
    ASSERT_EQ(stack.layers.size(), 1u);
    EXPECT_EQ(stack.layers[0].channel, "depth");
    EXPECT_NO_THROW(flatten());
}

TEST_F(FlattenStack, NewerStackFormatIsRefused)
{
    write_stack({{"cuprite urban 2", ramp(3.0f)}});
    std::string toml;
    {
        std::ifstream in(dir_ / "stack" / "stack.toml");
        toml.assign(std::istreambuf_iterator<char>(in), {});
    }
    const std::string from = "[stack]\nformat = 1";
    ASSERT_EQ(toml.rfind(from, 0), 0u);
    toml.replace(0, from.size(), "[stack]\nformat = 7");
    std::ofstream(dir_ / "stack" / "stack.toml") << toml;
    const std::string message = patina::test::message_of([&] { read_patina_stack(dir_ / "stack"); });
    EXPECT_NE(message.find("stack.toml:2:"), std::string::npos) << message;
    EXPECT_NE(message.find("stack format 7 is newer"), std::string::npos) << message;
}

TEST_F(FlattenStack, OutputManifestOfANewerFormatIsLeftAlone)
{
    // flatten updates the output folder's stack.toml like every writer: a newer layout is
    // refused before anything is written, and the file stays as it was.
    write_stack({{"tarnish", ramp(0.5f)}});
    const fs::path out = dir_ / "out";
    fs::create_directories(out);
    const std::string newer = "[stack]\nformat = 9\n";
    std::ofstream(out / "stack.toml") << newer;
    const std::string m = test::message_of([&] { flatten_to(out); });
    EXPECT_NE(m.find("cannot update manifest"), std::string::npos) << m;
    EXPECT_NE(m.find("stack.toml:2:"), std::string::npos) << m;
    EXPECT_NE(m.find("stack format 9 is newer"), std::string::npos) << m;
    std::ifstream in(out / "stack.toml");
    EXPECT_EQ(std::string(std::istreambuf_iterator<char>(in), {}), newer);
    EXPECT_FALSE(fs::exists(out / "diffuse_albedo.exr"));
}

TEST_F(FlattenStack, MissingStack)
{
    const std::string m =
        test::message_of([&] { read_patina_stack(dir_ / "nowhere"); });
    EXPECT_NE(m.find("nowhere"), std::string::npos) << m;
    EXPECT_NE(m.find("no such file"), std::string::npos) << m;
    std::ofstream(dir_ / "stack" / "stack.toml") << "[maps]\n";
    const std::string n = test::message_of([&] { read_patina_stack(dir_ / "stack"); });
    EXPECT_NE(n.find("no [patina] table"), std::string::npos) << n;
}

TEST_F(FlattenStack, MissingMap)
{
    write_stack({{"tarnish", ramp(0.5f)}});
    fs::remove(dir_ / "stack" / "layer01.exr");
    const std::string m = test::message_of([&] { read_patina_stack(dir_ / "stack"); });
    EXPECT_NE(m.find("map 'layer01': file"), std::string::npos) << m;
    EXPECT_NE(m.find("does not exist"), std::string::npos) << m;
}

/// The stack.toml of `dir` with `edit` applied to its text.
template <class Edit>
void edit_manifest(const fs::path& dir, Edit edit)
{
    std::string toml;
    {
        std::ifstream in(dir / "stack.toml");
        toml.assign(std::istreambuf_iterator<char>(in), {});
    }
    edit(toml);
    std::ofstream(dir / "stack.toml") << toml;
}

TEST_F(FlattenStack, AMaterialWithoutOpticsIsNamed)
{
    write_stack({{"tarnish", ramp(0.5f)}, {"marine patina 9", ramp(1.0f)}});
    edit_manifest(dir_ / "stack", [](std::string& toml) {
        const size_t table = toml.find("[patina.materials.\"marine patina 9\"]");
        ASSERT_NE(table, std::string::npos);
        const size_t next = toml.find("\n[", table + 1);
        toml.erase(table, next == std::string::npos ? std::string::npos : next - table);
    });
    const std::string m = test::message_of(
        [&] { flatten_stack(read_patina_stack(dir_ / "stack"), colors_, {}); });
    EXPECT_NE(m.find("'marine patina 9'"), std::string::npos) << m;
    EXPECT_NE(m.find("has no [patina.materials."), std::string::npos) << m;
    EXPECT_NE(m.find("stack.toml"), std::string::npos) << m;
}

TEST_F(FlattenStack, TheOpticsTheStackRecordsAreTheOnesUsed)
{
    // flatten sees the material layered_km renders: the optics in the stack, whatever the
    // library says now (another library, an edited stack). No library is read.
    write_stack({{"tarnish", ramp(0.5f)}});
    edit_manifest(dir_ / "stack", [](std::string& toml) {
        const size_t table = toml.find("[patina.materials.\"tarnish\"]");
        ASSERT_NE(table, std::string::npos);
        const size_t at = toml.find("roughness = ", table);
        ASSERT_NE(at, std::string::npos);
        toml.replace(at, toml.find('\n', at) - at, "roughness = 0.987");
    });
    const FlattenedStack flat = flatten();
    const auto map = std::find_if(flat.maps.begin(), flat.maps.end(), [](const FlatMap& m) {
        return m.name == "interface01_tarnish_roughness";
    });
    ASSERT_NE(map, flat.maps.end());
    EXPECT_FLOAT_EQ(map->tiles[0][0], 0.987f);
}

TEST_F(FlattenStack, NanTexelWritesNothing)
{
    std::vector<float> bad = ramp(0.5f);
    bad[3 * kSize + 7] = std::numeric_limits<float>::quiet_NaN();
    write_stack({{"tarnish", bad}});
    const fs::path out = dir_ / "out";
    const std::string m = test::message_of([&] { flatten_to(out); });
    EXPECT_NE(m.find("layer01.exr': texel (7, 3) is nan"), std::string::npos) << m;
    EXPECT_FALSE(fs::exists(out));
}

TEST_F(FlattenStack, MeshStackNeedsATexelSize)
{
    write_stack({{"tarnish", ramp(0.5f)}});
    PatinaStackFiles stack = read_patina_stack(dir_ / "stack");
    stack.strip_size_m = 0.0;  // as a mesh stack has none
    const std::string m = test::message_of([&] { flatten_stack(stack, colors_, {}); });
    EXPECT_NE(m.find("pass --texel-size"), std::string::npos) << m;
    FlattenOptions o;
    o.texel_size_m = 0.001;
    EXPECT_DOUBLE_EQ(flatten_stack(stack, colors_, o).texel_size_m, 0.001);
    EXPECT_THROW(flatten_colorspace("rec2020"), std::runtime_error);
}

}  // namespace
}  // namespace patina::texgen
