#include "core/color_management.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <cstdlib>
#include <filesystem>
#include <cmath>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

namespace patina {
namespace {

    const std::filesystem::path kConfig = PATINA_SOURCE_DIR "/ocio/config.ocio";

    using patina::test::message_of;

    /// Sets or unsets $OCIO for one scope.
    class ScopedOcioEnv {
    public:
        explicit ScopedOcioEnv(const char* value)
        {
            if (const char* old = std::getenv("OCIO"))
                old_ = old;
            if (value)
                ::setenv("OCIO", value, 1);
            else
                ::unsetenv("OCIO");
        }
        ~ScopedOcioEnv()
        {
            if (old_)
                ::setenv("OCIO", old_->c_str(), 1);
            else
                ::unsetenv("OCIO");
        }

    private:
        std::optional<std::string> old_;
    };

}  // namespace

TEST(ColorManagement, LoadsShippedConfig)
{
    ColorManager cm(kConfig);
    EXPECT_EQ(cm.working_space(), "ACEScg");
    EXPECT_EQ(cm.config_path(), kConfig);
    for (const char* name : {"ACEScg", "ACES2065-1", "lin_rec709", "Linear Rec.709 (sRGB)",
                             "srgb_texture", "sRGB", "raw", "CIE-XYZ-D65", "scene_linear", "data"})
        EXPECT_TRUE(cm.has_colorspace(name)) << name;
    EXPECT_FALSE(cm.has_colorspace("no_such_space"));
    EXPECT_TRUE(cm.is_data("raw"));
    EXPECT_FALSE(cm.is_data("srgb_texture"));
}

// Spot values verified with OCIO 2.1.2 (shared/notes/dependencies.md).
TEST(ColorManagement, AcescgRedToLinearRec709)
{
    ColorManager cm(kConfig);
    float rgb[3] = {1.0f, 0.0f, 0.0f};
    cm.convert("ACEScg", "lin_rec709", rgb, 1);
    EXPECT_NEAR(rgb[0], 1.70505f, 1e-4f);
    EXPECT_NEAR(rgb[1], -0.13026f, 1e-4f);
    EXPECT_NEAR(rgb[2], -0.02400f, 1e-4f);
}

TEST(ColorManagement, LinearGreyToSrgbTexture)
{
    ColorManager cm(kConfig);
    float rgb[6] = {0.18f, 0.18f, 0.18f, 0.18f, 0.18f, 0.18f};
    cm.convert("lin_rec709", "srgb_texture", rgb, 2);
    for (float v : rgb)
        EXPECT_NEAR(v, 0.46136f, 1e-4f);
    // And back, through the aliases.
    cm.convert("sRGB", "Linear Rec.709 (sRGB)", rgb, 2);
    for (float v : rgb)
        EXPECT_NEAR(v, 0.18f, 1e-5f);
}

TEST(ColorManagement, AcesSdrVideoViewOfMidGrey)
{
    ColorManager cm(kConfig);
    float rgb[3] = {0.18f, 0.18f, 0.18f};
    cm.convert_display("ACEScg", "sRGB", "ACES 1.0 - SDR Video", rgb, 1);
    for (float v : rgb)
        EXPECT_NEAR(v, 0.35595f, 1e-4f);
    // Un-tone-mapped is the plain sRGB curve (a neutral stays neutral in every space).
    float grey[3] = {0.18f, 0.18f, 0.18f};
    cm.convert_display("scene_linear", "sRGB", "Un-tone-mapped", grey, 1);
    EXPECT_NEAR(grey[0], 0.46136f, 1e-4f);
    float data[3] = {0.3f, 7.0f, -2.0f};
    cm.convert_display("raw", "sRGB", "Raw", data, 1);
    EXPECT_EQ(data[1], 7.0f);
}

TEST(ColorManagement, RawIsNeverConverted)
{
    ColorManager cm(kConfig);
    float v[3] = {0.25f, 3.0f, -1.0f};
    cm.convert("raw", "ACEScg", v, 1);
    EXPECT_EQ(v[0], 0.25f);
    EXPECT_EQ(v[1], 3.0f);
    EXPECT_EQ(v[2], -1.0f);
    EXPECT_TRUE(cm.conversion("ACEScg", "scene_linear").is_identity());
}

TEST(ColorManagement, UnknownColourSpaceNamesItAndListsKnown)
{
    ColorManager cm(kConfig);
    float rgb[3] = {};
    const std::string msg = message_of([&] { cm.convert("ACEScg", "Rec.2020-ish", rgb, 1); });
    EXPECT_NE(msg.find("unknown colour space 'Rec.2020-ish'"), std::string::npos) << msg;
    EXPECT_NE(msg.find(kConfig.string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("known: "), std::string::npos) << msg;
    EXPECT_NE(msg.find("srgb_texture"), std::string::npos) << msg;
    const std::string view = message_of([&] { cm.convert_display("ACEScg", "sRGB", "Filmic", rgb, 1); });
    EXPECT_NE(view.find("unknown view 'Filmic'"), std::string::npos) << view;
    EXPECT_NE(view.find("Un-tone-mapped"), std::string::npos) << view;
}

TEST(ColorManagement, WorkingRgbToXyzMapsWhiteToD65)
{
    ColorManager cm(kConfig);
    const Matrix3 m = cm.working_rgb_to_xyz();
    const float white[3] = {m[0] + m[1] + m[2], m[3] + m[4] + m[5], m[6] + m[7] + m[8]};
    // D65 white point, CIE 1931 2 deg, Y = 1: (0.9505, 1.0, 1.089).
    EXPECT_NEAR(white[0], 0.9505f, 1e-3f);
    EXPECT_NEAR(white[1], 1.0f, 1e-3f);
    EXPECT_NEAR(white[2], 1.089f, 1e-3f);
    // Luminance (the Y row) of AP1 primaries: green carries most, then red, then blue
    // (S-2014-004 gives 0.2722, 0.6741, 0.0537 at the ACES white; Bradford to D65 shifts
    // them by a few thousandths).
    EXPECT_GT(m[4], 0.6f);
    EXPECT_GT(m[3], m[5]);
    EXPECT_NEAR(m[3], 0.2722f, 1e-2f);
    EXPECT_NEAR(m[5], 0.0537f, 1e-2f);
}

TEST(ColorManagement, CacheIsThreadSafe)
{
    ColorManager cm(kConfig);
    const char* spaces[] = {"ACEScg", "lin_rec709", "srgb_texture", "ACES2065-1", "CIE-XYZ-D65"};
    std::vector<std::thread> threads;
    std::vector<int> bad(8, 0);
    for (int k = 0; k < 8; ++k)
        threads.emplace_back([&, k] {
            for (int i = 0; i < 200; ++i) {
                const char* a = spaces[(i + k) % 5];
                const char* b = spaces[(i * 3 + k) % 5];
                float v[3] = {0.18f, 0.18f, 0.18f};
                cm.convert(a, b, v, 1);
                cm.convert(b, a, v, 1);
                if (std::abs(v[0] - 0.18f) > 1e-4f)
                    ++bad[k];
                if (i % 50 == 0) {
                    float d[3] = {0.18f, 0.18f, 0.18f};
                    cm.convert_display("ACEScg", "sRGB", "ACES 1.0 - SDR Video", d, 1);
                    if (std::abs(d[0] - 0.35595f) > 1e-4f)
                        ++bad[k];
                }
            }
        });
    for (auto& t : threads)
        t.join();
    for (int k = 0; k < 8; ++k)
        EXPECT_EQ(bad[k], 0) << "thread " << k;
}

TEST(ColorManagement, MissingConfigFileIsNamed)
{
    const std::string msg = message_of([] { ColorManager cm("/nonexistent/config.ocio"); });
    EXPECT_NE(msg.find("/nonexistent/config.ocio"), std::string::npos) << msg;
}

TEST(ColorManagement, UserConfigWithoutXyzSpaceIsAClearError)
{
    const std::filesystem::path dir = PATINA_TEST_BUILD_DIR "/color_management_test";
    std::filesystem::create_directories(dir);
    const std::filesystem::path file = dir / "no_xyz.ocio";
    std::ofstream(file) << R"(ocio_profile_version: 2.1
roles:
  default: lin
  scene_linear: lin
  reference: lin
displays:
  sRGB:
    - !<View> {name: Raw, colorspace: lin}
colorspaces:
  - !<ColorSpace>
    name: lin
    isdata: false
)";
    ColorManager cm(file);
    EXPECT_EQ(cm.working_space(), "lin");
    const std::string msg = message_of([&] { (void)cm.working_rgb_to_xyz(); });
    EXPECT_NE(msg.find("CIE-XYZ-D65"), std::string::npos) << msg;
    EXPECT_NE(msg.find(file.string()), std::string::npos) << msg;
}

TEST(ColorManagement, DefaultConfigPathHonoursOcioThenShippedCopy)
{
    {
        ScopedOcioEnv env("/some/studio/config.ocio");
        EXPECT_EQ(ColorManager::default_config_path(), "/some/studio/config.ocio");
    }
    {
        // The test runs from <build>/bin; CMake copies ocio/ to <build>/share/patina/ocio.
        ScopedOcioEnv env("");
        const std::filesystem::path p = ColorManager::default_config_path();
        EXPECT_EQ(p.filename(), "config.ocio");
        EXPECT_TRUE(std::filesystem::exists(p)) << p;
        EXPECT_NE(p.string().find("share/patina/ocio"), std::string::npos) << p;
    }
}

}  // namespace patina
