// patina-texgen export, gltf preset: the .glb's layout (GLB header and chunks, §4.4 of the
// glTF 2.0 specification), a material variant per step, and every map read back (OIIO)
// against the flattened maps it was made from: bit depth, packing and colour encoding.
#include "texgen/export/export_patina.h"
#include "texgen/export/export_flattened.h"

#include "texgen/flatten/flatten_stack.h"
#include "texgen/flatten/patina_stack_files.h"
#include "core/image_io.h"
#include "test_util.h"

#include <OpenImageIO/imageio.h>
#include <tbb/global_control.h>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <cstring>
#include <fstream>

namespace patina::texgen {
namespace {

namespace fs = std::filesystem;

class Export : public ::testing::Test {
protected:
    // Each test in a folder of its own: CTest runs the tests of this file in parallel
    // processes.
    void SetUp() override
    {
        dir_ = fs::path(PATINA_TEST_BUILD_DIR) / "export_test" /
               ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::remove_all(dir_);
        fs::create_directories(dir_);
        const std::string command = std::string(PATINA_TEST_BIN_DIR) +
                                    "/patina-texgen patina '" + PATINA_SOURCE_DIR +
                                    "/samples/copper_strips/rural.patina' -o '" +
                                    (dir_ / "rural").string() +
                                    "' --resolution 24 --times 0,12,30 --quiet --no-preview";
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
    }

    /// The flattened maps of one step, as export made them.
    FlattenedStack flat(const std::string& step) const
    {
        const PatinaStackFiles stack = read_patina_stack(dir_ / "rural" / step);
        return flatten_stack(stack, colors_, {});
    }

    static const FlatMap& map_of(const FlattenedStack& f, const std::string& name)
    {
        for (const FlatMap& m : f.maps)
            if (m.name == name)
                return m;
        throw std::runtime_error("no map " + name);
    }

    /// A PNG's pixels in [0, 1], with its bits per channel.
    static std::vector<float> read_png(const fs::path& file, int* bits, int* channels)
    {
        // The channels as stored: a fourth is data, not an alpha to premultiply by.
        OIIO::ImageSpec config;
        config.attribute("oiio:UnassociatedAlpha", 1);
        auto in = OIIO::ImageInput::open(file.string(), &config);
        EXPECT_TRUE(in) << file;
        if (!in)
            return {};
        const OIIO::ImageSpec& spec = in->spec();
        *bits = static_cast<int>(spec.format.size()) * 8;
        *channels = spec.nchannels;
        std::vector<float> px(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
        EXPECT_TRUE(in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, px.data()));
        return px;
    }

    fs::path dir_;
    ColorManager colors_{fs::path(PATINA_SOURCE_DIR) / "ocio/config.ocio"};
};

TEST_F(Export, GlbHoldsOneVariantPerStepNamedByAge)
{
    const fs::path out = dir_ / "rural.glb";
    const ExportResult r = export_patina(dir_ / "rural", out, {}, colors_);
    EXPECT_EQ(r.steps, 3u);
    std::ifstream in(out, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    ASSERT_GE(bytes.size(), 28u);
    auto u32 = [&](size_t at) {
        uint32_t v;
        std::memcpy(&v, bytes.data() + at, 4);
        return v;
    };
    // §4.4.2: magic "glTF", version 2, the total length; §4.4.3: JSON chunk, then BIN.
    EXPECT_EQ(u32(0), 0x46546C67u);
    EXPECT_EQ(u32(4), 2u);
    EXPECT_EQ(u32(8), bytes.size());
    const uint32_t json_length = u32(12);
    EXPECT_EQ(u32(16), 0x4E4F534Au);
    EXPECT_EQ(json_length % 4, 0u);
    const size_t bin_at = 20 + json_length;
    EXPECT_EQ(u32(bin_at + 4), 0x004E4942u);
    EXPECT_EQ(bin_at + 8 + u32(bin_at), bytes.size());

    const nlohmann::json doc = nlohmann::json::parse(bytes.substr(20, json_length));
    // The buffer is the BIN chunk without its padding to 4 bytes (§4.4.3.2).
    const size_t buffer = doc["buffers"][0]["byteLength"].get<size_t>();
    EXPECT_LE(buffer, u32(bin_at));
    EXPECT_LT(u32(bin_at) - buffer, 4u);
    const auto& variants = doc["extensions"]["KHR_materials_variants"]["variants"];
    ASSERT_EQ(variants.size(), 3u);
    EXPECT_EQ(variants[0]["name"], "0 y");
    EXPECT_EQ(variants[1]["name"], "12 y");
    EXPECT_EQ(variants[2]["name"], "30 y");
    const auto& primitive = doc["meshes"][0]["primitives"][0];
    const auto& mappings = primitive["extensions"]["KHR_materials_variants"]["mappings"];
    ASSERT_EQ(mappings.size(), 3u);
    for (size_t k = 0; k < 3; ++k) {
        EXPECT_EQ(mappings[k]["variants"][0], k);
        EXPECT_EQ(doc["materials"][mappings[k]["material"].get<int>()]["extras"]["patina"]
                     ["time_years"],
                  std::vector<double>({0.0, 12.0, 30.0})[k]);
    }
    EXPECT_EQ(primitive["material"], mappings[2]["material"]);  // the default: the last age
    for (const auto& image : doc["images"]) {
        EXPECT_EQ(image["mimeType"], "image/png");
        EXPECT_TRUE(image.contains("bufferView"));
    }
    // The strip at its real size: strip_size_m wide (the patina default, 0.1 m).
    const auto& position = doc["accessors"][primitive["attributes"]["POSITION"].get<int>()];
    const double strip = read_patina_stack(dir_ / "rural" / "t30").strip_size_m;
    EXPECT_NEAR(position["max"][0].get<double>() - position["min"][0].get<double>(), strip, 1e-6);
}

TEST_F(Export, MapsReadBackAsTheFlattenedMapsEncodedForGltf)
{
    ExportOptions o;
    o.separate = true;
    const fs::path out = dir_ / "sep" / "rural.gltf";
    export_patina(dir_ / "rural" / "t30", out, o, colors_);
    const FlattenedStack f = flat("t30");
    const size_t texels = static_cast<size_t>(f.width) * f.height;

    // Base colour: 8-bit sRGB-encoded (OCIO lin_rec709 -> srgb_texture), as glTF requires.
    int bits = 0, channels = 0;
    std::vector<float> base = map_of(f, "gltf_base_color").tiles[0];
    colors_.convert("lin_rec709", "srgb_texture", base.data(), texels);
    const std::vector<float> png = read_png(out.parent_path() / "rural_t30_base_color.png", &bits,
                                            &channels);
    EXPECT_EQ(bits, 8);
    ASSERT_EQ(channels, 3);
    ASSERT_EQ(png.size(), base.size());
    double worst = 0.0;
    for (size_t i = 0; i < png.size(); ++i)
        worst = std::max(worst, std::abs(double(png[i]) - std::clamp(double(base[i]), 0.0, 1.0)));
    EXPECT_LE(worst, 0.5 / 255 + 1e-6);  // rounding to 8 bits, nothing else

    // Data maps: linear, packed as flatten packs them (metallicRoughness: G roughness,
    // B metallic; clearcoat: R factor, G roughness; normal: OpenGL +Y, n * 0.5 + 0.5). The
    // clearcoat map is there exactly when the fit gave some texel a coat.
    const std::vector<float>& coat = map_of(f, "gltf_clearcoat").tiles[0];
    bool coated = false;
    for (size_t t = 0; t < texels; ++t)
        coated |= coat[t * 3] > 0.0f;
    EXPECT_EQ(fs::exists(out.parent_path() / "rural_t30_clearcoat.png"), coated);
    for (const auto& [file, map] :
         {std::pair{"rural_t30_metallic_roughness.png", "gltf_metallic_roughness"},
          std::pair{"rural_t30_clearcoat.png", "gltf_clearcoat"},
          std::pair{"rural_t30_normal.png", "normal"}}) {
        if (std::string(map) == "gltf_clearcoat" && !coated)
            continue;
        const std::vector<float> data = read_png(out.parent_path() / file, &bits, &channels);
        const std::vector<float>& expected = map_of(f, map).tiles[0];
        EXPECT_EQ(bits, 8) << file;
        ASSERT_EQ(data.size(), expected.size()) << file;
        double e = 0.0;
        for (size_t i = 0; i < data.size(); ++i)
            e = std::max(e, std::abs(double(data[i]) - std::clamp(double(expected[i]), 0.0, 1.0)));
        EXPECT_LE(e, 0.5 / 255 + 1e-6) << file;
    }
}

TEST_F(Export, PresetsPackTheFlattenedMapsAsDocumented)
{
    // Each engine preset read back (OIIO) against the maps flatten made, channel by channel:
    // docs/export.md's tables.
    const FlattenedStack f = flat("t30");
    const size_t texels = static_cast<size_t>(f.width) * f.height;
    const std::vector<float>& mr = map_of(f, "gltf_metallic_roughness").tiles[0];
    const std::vector<float>& coat = map_of(f, "gltf_clearcoat").tiles[0];
    const std::vector<float>& normal = map_of(f, "normal").tiles[0];
    const std::vector<float>& height = map_of(f, "height").tiles[0];
    const double q8 = 0.5 / 255 + 1e-6, q16 = 0.5 / 65535 + 1e-6;
    auto expect_packed = [&](const fs::path& file, int want_bits, int want_channels,
                             double tolerance, auto&& expected) {
        int bits = 0, channels = 0;
        const std::vector<float> px = read_png(file, &bits, &channels);
        EXPECT_EQ(bits, want_bits) << file;
        ASSERT_EQ(channels, want_channels) << file;
        ASSERT_EQ(px.size(), texels * channels) << file;
        double worst = 0.0;
        for (size_t t = 0; t < texels; ++t)
            for (int c = 0; c < channels; ++c)
                worst = std::max(worst, std::abs(double(px[t * channels + c]) -
                                                 std::clamp(double(expected(t, c)), 0.0, 1.0)));
        EXPECT_LE(worst, tolerance) << file;
    };

    ExportOptions o;
    o.preset = "unreal";
    export_patina(dir_ / "rural" / "t30", dir_ / "unreal", o, colors_);
    // ORM: R occlusion, G roughness, B metallic; the normal DirectX (green down).
    expect_packed(dir_ / "unreal" / "unreal_t30_OcclusionRoughnessMetallic.png", 8, 3, q8,
                  [&](size_t t, int c) { return mr[t * 3 + c]; });
    expect_packed(dir_ / "unreal" / "unreal_t30_Normal.png", 8, 3, q8, [&](size_t t, int c) {
        return c == 1 ? 1.0f - normal[t * 3 + 1] : normal[t * 3 + c];
    });
    double top = 0.0;
    for (float h : height)
        top = std::max(top, double(h));
    ASSERT_GT(top, 0.0);
    expect_packed(dir_ / "unreal" / "unreal_t30_Height.png", 16, 1, q16,
                  [&](size_t t, int) { return float(height[t] / top); });

    o.preset = "unity-hdrp";
    export_patina(dir_ / "rural" / "t30", dir_ / "unity", o, colors_);
    // Mask map: R metallic, G occlusion, B detail mask (1), A smoothness = 1 - roughness.
    expect_packed(dir_ / "unity" / "unity_t30_MaskMap.png", 8, 4, q8, [&](size_t t, int c) {
        return c == 0 ? mr[t * 3 + 2] : c == 1 ? mr[t * 3] : c == 2 ? 1.0f : 1.0f - mr[t * 3 + 1];
    });
    expect_packed(dir_ / "unity" / "unity_t30_CoatMask.png", 8, 1, q8,
                  [&](size_t t, int) { return coat[t * 3]; });

    o.preset = "exr";
    export_patina(dir_ / "rural" / "t30", dir_ / "exr", o, colors_);
    // Linear float: the flattened values themselves; displacement in metres.
    const ImageData base = read_image(dir_ / "exr" / "exr_t30_base_color.exr");
    const std::vector<float>& flat_base = map_of(f, "gltf_base_color").tiles[0];
    for (size_t t = 0; t < texels; t += 7)
        EXPECT_EQ(base.at(int(t % f.width), int(t / f.width), base.channel("G")),
                  flat_base[t * 3 + 1]);
    const ImageData disp = read_image(dir_ / "exr" / "exr_t30_displacement.exr");
    for (size_t t = 0; t < texels; t += 7)
        EXPECT_FLOAT_EQ(disp.at(int(t % f.width), int(t / f.width), 0), height[t] * 1e-6f);
}

TEST_F(Export, FlattenedMapsExportAsTheStackDoes)
{
    // A baked texture stack (flatten's maps, float EXRs, the colour map sRGB-encoded) gives
    // the asset the stack gives, to one 8-bit step (the colour map's round trip through
    // sRGB), on the strip of the stack it came from.
    const std::string command = std::string(PATINA_TEST_BIN_DIR) + "/patina-texgen flatten '" +
                                (dir_ / "rural" / "t30").string() + "' -o '" +
                                (dir_ / "flat").string() + "' --quiet";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    ASSERT_TRUE(is_flattened_stack(dir_ / "flat"));
    EXPECT_FALSE(is_flattened_stack(dir_ / "rural" / "t30"));
    ExportOptions o;
    o.separate = true;
    o.name_template = "$map";
    export_patina(dir_ / "rural" / "t30", dir_ / "from_stack" / "a.gltf", o, colors_);
    export_flattened(dir_ / "flat", dir_ / "from_maps" / "a.gltf", o, colors_);
    for (const char* map : {"base_color", "metallic_roughness", "normal", "clearcoat"}) {
        // A map both have or neither (a clearcoat only where the fit gave a coat).
        const fs::path file_a = dir_ / "from_stack" / (std::string(map) + ".png");
        ASSERT_EQ(fs::exists(file_a), fs::exists(dir_ / "from_maps" / (std::string(map) + ".png")))
            << map;
        if (!fs::exists(file_a))
            continue;
        int bits_a = 0, bits_b = 0, ch_a = 0, ch_b = 0;
        const std::vector<float> a =
            read_png(dir_ / "from_stack" / (std::string(map) + ".png"), &bits_a, &ch_a);
        const std::vector<float> b =
            read_png(dir_ / "from_maps" / (std::string(map) + ".png"), &bits_b, &ch_b);
        ASSERT_EQ(a.size(), b.size()) << map;
        EXPECT_EQ(bits_a, bits_b);
        double worst = 0.0;
        for (size_t i = 0; i < a.size(); ++i)
            worst = std::max(worst, std::abs(double(a[i]) - b[i]));
        EXPECT_LE(worst, 1.0 / 255.0 + 1e-6) << map;
    }
    auto json_of = [](const fs::path& f) {
        std::ifstream in(f);
        return nlohmann::json::parse(in);
    };
    // The strip's size: 0.1 m wide (rural.patina's strip), as the stack's export has it.
    EXPECT_EQ(json_of(dir_ / "from_maps" / "a.gltf")["accessors"][0]["max"],
              json_of(dir_ / "from_stack" / "a.gltf")["accessors"][0]["max"]);
}

TEST_F(Export, SameBytesWithAnyThreadCount)
{
    // Steps are flattened and their maps encoded in parallel; the asset must not depend on
    // the threads' order.
    fs::create_directories(dir_ / "one_thread");
    fs::create_directories(dir_ / "threads");
    {
        tbb::global_control one(tbb::global_control::max_allowed_parallelism, 1);
        export_patina(dir_ / "rural", dir_ / "one_thread" / "a.glb", {}, colors_);
    }
    export_patina(dir_ / "rural", dir_ / "threads" / "a.glb", {}, colors_);
    auto bytes = [](const fs::path& f) {
        std::ifstream in(f, std::ios::binary);
        return std::string((std::istreambuf_iterator<char>(in)), {});
    };
    EXPECT_EQ(bytes(dir_ / "one_thread" / "a.glb"), bytes(dir_ / "threads" / "a.glb"));
}

TEST_F(Export, StepsThatDisagreeAreRefusedBeforeAnythingIsWritten)
{
    // Step t12 replaced by a stack grown at another resolution: one asset cannot hold both.
    const std::string command = std::string(PATINA_TEST_BIN_DIR) + "/patina-texgen patina '" +
                                PATINA_SOURCE_DIR + "/samples/copper_strips/rural.patina' -o '" +
                                (dir_ / "other").string() +
                                "' --resolution 16 --times 12 --quiet --no-preview";
    ASSERT_EQ(std::system(command.c_str()), 0) << command;
    fs::remove_all(dir_ / "rural" / "t12");
    fs::copy(dir_ / "other", dir_ / "rural" / "t12", fs::copy_options::recursive);
    const std::string m = test::message_of(
        [&] { export_patina(dir_ / "rural", dir_ / "x.glb", {}, colors_); });
    EXPECT_NE(m.find("the steps disagree: t00 is 24x24 texels on 1 tile(s)"), std::string::npos)
        << m;
    EXPECT_NE(m.find("t12 is 16x16"), std::string::npos) << m;
    EXPECT_FALSE(fs::exists(dir_ / "x.glb"));
}

TEST_F(Export, BadInputsNameTheOptionOrFile)
{
    ExportOptions o;
    o.preset = "maya";
    std::string m = test::message_of(
        [&] { export_patina(dir_ / "rural", dir_ / "x.glb", o, colors_); });
    EXPECT_NE(m.find("--preset 'maya': expected one of gltf, unreal, unity-hdrp, exr"),
              std::string::npos) << m;
    o.preset = "unreal";
    o.bits = 12;
    m = test::message_of(
        [&] { export_patina(dir_ / "rural", dir_ / "x", o, colors_); });
    EXPECT_NE(m.find("--bits 12"), std::string::npos) << m;
    o.bits = 8;
    m = test::message_of(
        [&] { export_patina(dir_ / "rural", dir_ / "x.glb", o, colors_); });
    EXPECT_NE(m.find("writes a folder of textures"), std::string::npos) << m;
    m = test::message_of(
        [&] { export_patina(dir_ / "rural", dir_ / "x.gltf", {}, colors_); });
    EXPECT_NE(m.find("a binary glTF file"), std::string::npos) << m;
    EXPECT_FALSE(fs::exists(dir_ / "x.glb"));
    EXPECT_FALSE(fs::exists(dir_ / "x.gltf"));
}

}  // namespace
}  // namespace patina::texgen
