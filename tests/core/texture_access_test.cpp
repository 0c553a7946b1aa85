#include "core/texture_access.h"

#include "core/image_io.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <atomic>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace patina {
namespace {

    const std::filesystem::path kConfig = PATINA_SOURCE_DIR "/ocio/config.ocio";

    std::filesystem::path scratch(const std::string& name)
    {
        const std::filesystem::path dir =
            std::filesystem::path(PATINA_TEST_BUILD_DIR) / "texture_access_test";
        std::filesystem::create_directories(dir);
        return dir / name;
    }

    /// A 32x32 texture: left half (s < 0.5) one value, right half another, per channel.
    std::filesystem::path make_halves(const std::string& name, const std::vector<float>& left,
                                      const std::vector<float>& right)
    {
        const int w = 32, h = 32, c = static_cast<int>(left.size());
        std::vector<float> p(static_cast<size_t>(w) * h * c);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int k = 0; k < c; ++k)
                    p[(static_cast<size_t>(y) * w + x) * c + k] = x < w / 2 ? left[k] : right[k];
        const auto path = scratch(name);
        TextureOptions opt;
        opt.format = OIIO::TypeDesc::FLOAT;
        opt.tile_size = 16;
        make_texture_atomic(path, p.data(), w, h, c, {}, opt);
        return path;
    }

    using patina::test::message_of;

}  // namespace

TEST(TextureAccess, RawLookupsReturnStoredValuesAndFilteredMean)
{
    ColorManager cm(kConfig);
    TextureAccess tex(cm);
    const auto path = make_halves("raw.exr", {0.2f, 5.0f}, {0.6f, 7.0f});
    TextureAccess::Handle* h = tex.open(path, "raw");
    ASSERT_NE(h, nullptr);
    EXPECT_EQ(h->channels, 2);
    EXPECT_EQ(h->width, 32);
    EXPECT_TRUE(h->is_data);
    EXPECT_EQ(tex.open(path, "raw"), h); // same file, same handle

    float out[2] = {};
    // Point samples at texel centres inside each half.
    ASSERT_TRUE(tex.lookup(h, 0.25f, 0.5f, 0, 0, 0, 0, 0, 2, out));
    EXPECT_NEAR(out[0], 0.2f, 1e-5f);
    EXPECT_NEAR(out[1], 5.0f, 1e-5f);
    ASSERT_TRUE(tex.lookup(h, 0.75f, 0.5f, 0, 0, 0, 0, 1, 1, out));
    EXPECT_NEAR(out[0], 7.0f, 1e-5f);
    // A footprint covering the whole texture reads the coarsest mip level: the mean.
    ASSERT_TRUE(tex.lookup(h, 0.5f, 0.5f, 1.0f, 0, 0, 1.0f, 0, 1, out));
    EXPECT_NEAR(out[0], 0.4f, 1e-4f);
    // Channels past the texture's count read 0.
    float three[3] = {-1, -1, -1};
    ASSERT_TRUE(tex.lookup(h, 0.25f, 0.5f, 0, 0, 0, 0, 1, 2, three));
    EXPECT_NEAR(three[0], 5.0f, 1e-5f);
    EXPECT_EQ(three[1], 0.0f);
}

TEST(TextureAccess, ColourTexturesAreConvertedToTheWorkingSpace)
{
    ColorManager cm(kConfig);
    TextureAccess tex(cm);
    // sRGB-encoded 0.46136 is linear 0.18; a neutral stays neutral in ACEScg.
    const auto path = make_halves("srgb.exr", {0.46136f, 0.46136f, 0.46136f, 0.5f},
                                  {1.0f, 0.0f, 0.0f, 1.0f});
    TextureAccess::Handle* h = tex.open(path, "srgb_texture");
    EXPECT_FALSE(h->is_data);
    float rgba[4] = {};
    ASSERT_TRUE(tex.lookup(h, 0.25f, 0.5f, 0, 0, 0, 0, 0, 4, rgba));
    EXPECT_NEAR(rgba[0], 0.18f, 2e-4f);
    EXPECT_NEAR(rgba[1], 0.18f, 2e-4f);
    EXPECT_NEAR(rgba[2], 0.18f, 2e-4f);
    EXPECT_NEAR(rgba[3], 0.5f, 1e-6f); // alpha is never converted

    // Pure sRGB red in ACEScg, cross-checked through ColorManager; a lookup of channel 1
    // alone still converts the whole triple.
    float red[3] = {1.0f, 0.0f, 0.0f};
    cm.convert("srgb_texture", "ACEScg", red, 1);
    float rgb[3] = {};
    ASSERT_TRUE(tex.lookup(h, 0.75f, 0.5f, 0, 0, 0, 0, 0, 3, rgb));
    for (int k = 0; k < 3; ++k)
        EXPECT_NEAR(rgb[k], red[k], 1e-5f) << k;
    float green = -1;
    ASSERT_TRUE(tex.lookup(h, 0.75f, 0.5f, 0, 0, 0, 0, 1, 1, &green));
    EXPECT_NEAR(green, red[1], 1e-5f);

    // The same file declared raw is not converted.
    TextureAccess::Handle* raw = tex.open(path, "raw");
    EXPECT_NE(raw, h);
    ASSERT_TRUE(tex.lookup(raw, 0.25f, 0.5f, 0, 0, 0, 0, 0, 1, rgb));
    EXPECT_NEAR(rgb[0], 0.46136f, 1e-5f);
}

TEST(TextureAccess, ParallelLookupsAgreeWithSerial)
{
    ColorManager cm(kConfig);
    TextureAccess tex(cm);
    const auto path = make_halves("par.exr", {0.1f, 0.2f, 0.3f}, {0.9f, 0.8f, 0.7f});
    TextureAccess::Handle* h = tex.open(path, "lin_rec709");
    auto sample = [&](int i, float* out) {
        const float s = (i % 97) / 97.0f, t = (i % 89) / 89.0f;
        return tex.lookup(h, s, t, 0.01f, 0, 0, 0.01f, 0, 3, out);
    };
    std::vector<float> serial(3000 * 3);
    for (int i = 0; i < 3000; ++i)
        ASSERT_TRUE(sample(i, &serial[i * 3]));
    std::atomic<int> mismatches{0};
    std::vector<std::thread> threads;
    for (int k = 0; k < 4; ++k)
        threads.emplace_back([&, k] {
            for (int i = k; i < 3000; i += 4) {
                float v[3];
                if (!sample(i, v) || v[0] != serial[i * 3] || v[1] != serial[i * 3 + 1] ||
                    v[2] != serial[i * 3 + 2])
                    ++mismatches;
            }
        });
    for (auto& t : threads)
        t.join();
    EXPECT_EQ(mismatches.load(), 0);
}

TEST(TextureAccess, MissingFileBadFileAndUnknownColourSpaceAreNamed)
{
    ColorManager cm(kConfig);
    TextureAccess tex(cm);
    const std::string missing = message_of([&] { tex.open("/nonexistent/rust.exr", "raw"); });
    EXPECT_NE(missing.find("texture '/nonexistent/rust.exr'"), std::string::npos) << missing;
    EXPECT_NE(missing.find("not found"), std::string::npos) << missing;

    const auto garbage = scratch("garbage.exr");
    { std::ofstream(garbage) << "not an image"; }
    const std::string bad = message_of([&] { tex.open(garbage, "raw"); });
    EXPECT_NE(bad.find("texture '" + garbage.string() + "'"), std::string::npos) << bad;

    const auto ok = make_halves("ok.exr", {0.0f}, {1.0f});
    const std::string space = message_of([&] { tex.open(ok, "Adobe RGB"); });
    EXPECT_NE(space.find("unknown colour space 'Adobe RGB'"), std::string::npos) << space;
    EXPECT_NE(space.find(ok.string()), std::string::npos) << space;

    float out[2] = {7, 7};
    EXPECT_FALSE(tex.lookup(nullptr, 0.5f, 0.5f, 0, 0, 0, 0, 0, 2, out));
    EXPECT_EQ(out[0], 0.0f);
}

}  // namespace patina

namespace patina {
namespace {

    /// A 32x32 UDIM tile file `name`: `top` in the upper half of the image (v in [0.5, 1)
    /// of the tile, mesh uvs), `bottom` in the lower.
    void make_tile(const std::string& name, float top, float bottom)
    {
        const int w = 32, h = 32;
        std::vector<float> p(static_cast<size_t>(w) * h);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                p[static_cast<size_t>(y) * w + x] = y < h / 2 ? top : bottom;
        TextureOptions opt;
        opt.format = OIIO::TypeDesc::FLOAT;
        opt.tile_size = 16;
        make_texture_atomic(scratch(name), p.data(), w, h, 1, {}, opt);
    }

    /// A lookup at the mesh uv (u, v), as the host makes it (t = 1 - v).
    float at_uv(const TextureAccess& tex, const TextureAccess::Handle* h, float u, float v,
                bool* ok = nullptr)
    {
        float out = -1.0f;
        const bool found = tex.lookup(h, u, 1.0f - v, 0, 0, 0, 0, 0, 1, &out);
        if (ok)
            *ok = found;
        return out;
    }

}  // namespace

TEST(TextureAccess, UdimPatternsReadTheTileOfEachUv)
{
    make_tile("thickness.1001.exr", 1.1f, 1.2f);
    make_tile("thickness.1002.exr", 2.1f, 2.2f);
    make_tile("thickness.1011.exr", 11.1f, 11.2f);
    ColorManager cm(kConfig);
    TextureAccess tex(cm);
    TextureAccess::Handle* h = tex.open(scratch("thickness.<UDIM>.exr"), "raw");
    ASSERT_NE(h, nullptr);
    EXPECT_TRUE(h->udim);
    EXPECT_EQ(h->width, 32);
    // Tile 1001 + floor(u) + 10 floor(v); within it v runs up the image, as in every tile of
    // a texel map (texgen/texels/texel_grid.h).
    EXPECT_FLOAT_EQ(at_uv(tex, h, 0.5f, 0.75f), 1.1f);
    EXPECT_FLOAT_EQ(at_uv(tex, h, 0.5f, 0.25f), 1.2f);
    EXPECT_FLOAT_EQ(at_uv(tex, h, 1.5f, 0.75f), 2.1f);
    EXPECT_FLOAT_EQ(at_uv(tex, h, 1.5f, 0.25f), 2.2f);
    EXPECT_FLOAT_EQ(at_uv(tex, h, 0.5f, 1.75f), 11.1f);
    EXPECT_FLOAT_EQ(at_uv(tex, h, 0.5f, 1.25f), 11.2f);
    // No tile 1003: nothing there.
    bool ok = true;
    EXPECT_EQ(at_uv(tex, h, 2.5f, 0.5f, &ok), 0.0f);
    EXPECT_FALSE(ok);
}

TEST(TextureAccess, AMissingFileWhoseTilesExistNamesTheUdimToken)
{
    make_tile("exposure.1001.exr", 1.0f, 1.0f);
    ColorManager cm(kConfig);
    TextureAccess tex(cm);
    const std::string missing =
        test::message_of([&] { tex.open(scratch("exposure.exr"), "raw"); });
    EXPECT_NE(missing.find("file not found, but its UDIM tiles are"), std::string::npos)
        << missing;
    EXPECT_NE(missing.find("exposure.<UDIM>.exr"), std::string::npos) << missing;
    const std::string none =
        test::message_of([&] { tex.open(scratch("nothing.<UDIM>.exr"), "raw"); });
    EXPECT_NE(none.find("no UDIM tile of it exists"), std::string::npos) << none;
    // Colour tiles that would need converting are refused, naming the colour space.
    const std::string colour =
        test::message_of([&] { tex.open(scratch("exposure.<UDIM>.exr"), "srgb_texture"); });
    EXPECT_NE(colour.find("are not converted"), std::string::npos) << colour;
}

}  // namespace patina
