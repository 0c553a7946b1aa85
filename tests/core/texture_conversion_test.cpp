// Colour textures are converted once, at load, into a cached working-space texture.
#include "core/color_management.h"
#include "core/image_io.h"
#include "core/texture_conversion.h"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <limits>
#include <thread>
#include <vector>

namespace fs = std::filesystem;

TEST(TextureConversion, ConvertsOnceAndRemakesWhenTheSourceChanges)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "texture_conversion";
    fs::remove_all(dir);
    fs::create_directories(dir);
    setenv("PATINA_TEXTURE_CACHE", (dir / "cache").c_str(), 1);
    const patina::ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio" / "config.ocio");
    const fs::path src = dir / "grey.png";
    const float half_grey[3] = {0.5f, 0.5f, 0.5f};
    patina::write_image_atomic(src, half_grey, 1, 1, 3, {}, OIIO::TypeDesc::UINT8);

    const fs::path a = patina::converted_texture(src, "srgb_texture", colors);
    EXPECT_EQ(a.parent_path(), dir / "cache");
    const auto written = fs::last_write_time(a);
    // sRGB-encoded 128/255 is linear 0.21586 (IEC 61966-2-1); a grey keeps R = G = B in
    // ACEScg (same white after Bradford adaptation).
    const patina::ImageData img = patina::read_image(a);
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(img.at(0, 0, c), 0.215861f, 2e-5f);

    // The second open reuses the cache entry untouched.
    EXPECT_EQ(patina::converted_texture(src, "srgb_texture", colors), a);
    EXPECT_EQ(fs::last_write_time(a), written);
    // Another colour space, or a changed source, is another entry.
    EXPECT_NE(patina::converted_texture(src, "lin_rec709", colors), a);
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    const float white[3] = {1.0f, 1.0f, 1.0f};
    patina::write_image_atomic(src, white, 1, 1, 3, {}, OIIO::TypeDesc::UINT8);
    const fs::path b = patina::converted_texture(src, "srgb_texture", colors);
    EXPECT_NE(b, a);
    EXPECT_NEAR(patina::read_image(b).at(0, 0, 0), 1.0f, 1e-4f);
    unsetenv("PATINA_TEXTURE_CACHE");
}

// A NaN texel in a texture is refused when it is opened, naming the file and the texel.
TEST(TextureConversion, NonFiniteTexelIsNamed)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "texture_nan";
    fs::create_directories(dir);
    const fs::path file = dir / "thickness.exr";
    std::vector<float> pixels(4 * 3, 0.25f);
    pixels[(1 * 2 + 0) * 1 + 0] = std::numeric_limits<float>::quiet_NaN();  // texel (0, 1)
    patina::write_image_atomic(file, pixels.data(), 2, 3, 1, {"Y"}, OIIO::TypeDesc::FLOAT);
    try {
        patina::check_finite_texels(file);
        FAIL() << "a NaN texel was accepted";
    } catch (const std::runtime_error& e) {
        const std::string msg = e.what();
        EXPECT_NE(msg.find("thickness.exr"), std::string::npos) << msg;
        EXPECT_NE(msg.find("texel (0, 1)"), std::string::npos) << msg;
        EXPECT_NE(msg.find("NaN"), std::string::npos) << msg;
    }
    const float fine[4] = {0.1f, 0.2f, 0.3f, 0.4f};
    patina::write_image_atomic(dir / "fine.exr", fine, 2, 2, 1, {"Y"}, OIIO::TypeDesc::FLOAT);
    EXPECT_NO_THROW(patina::check_finite_texels(dir / "fine.exr"));
}

TEST(TextureConversion, AGreyMapKeepsItsSecondChannel)
{
    // A baked map is its value and a coverage channel: converting the grey value must leave
    // the coverage as it was (it is no colour).
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "texture_conversion_grey";
    fs::remove_all(dir);
    fs::create_directories(dir);
    setenv("PATINA_TEXTURE_CACHE", (dir / "cache").c_str(), 1);
    const patina::ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio" / "config.ocio");
    const fs::path src = dir / "ao.exr";
    const float texel[2] = {0.5f, 0.25f};
    patina::write_image_atomic(src, texel, 1, 1, 2, {"ao", "coverage.A"}, OIIO::TypeDesc::FLOAT);
    const patina::ImageData img =
        patina::read_image(patina::converted_texture(src, "srgb_texture", colors));
    ASSERT_EQ(img.channels, 2);
    // sRGB 0.5 is linear 0.214041 (IEC 61966-2-1), a grey in any RGB working space.
    EXPECT_NEAR(img.at(0, 0, 0), 0.214041f, 2e-5f);
    EXPECT_EQ(img.at(0, 0, img.channel("coverage.A")), 0.25f);
    unsetenv("PATINA_TEXTURE_CACHE");
}
