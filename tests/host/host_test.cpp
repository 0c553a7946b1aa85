// The host services table plugins see (abi.h PatinaHost), exercised through the C table.
#include "host/host.h"

#include "core/spectrum.h"

#include <gtest/gtest.h>

#include <OpenImageIO/imageio.h>

#include <cstring>
#include <string>
#include <vector>

namespace {

const PatinaHost& host() { return *patina::default_host().c_host(); }

}  // namespace

TEST(Host, TableDescribesItself)
{
    EXPECT_EQ(host().size, sizeof(PatinaHost));
    EXPECT_EQ(host().abi_version, PATINA_ABI_VERSION);
    EXPECT_STREQ(host().working_space, "ACEScg");
    EXPECT_EQ(patina::Host::from_c(&host()), &patina::default_host());
    PatinaHost foreign = host();
    foreign.error = nullptr;  // a table not made by patina::Host
    EXPECT_EQ(patina::Host::from_c(&foreign), nullptr);
}

TEST(Host, GreyUpliftIsExactlyConstant)
{
    const float grey[3] = {0.37f, 0.37f, 0.37f};
    PatinaRgbSpectrum s{};
    host().rgb_to_spectrum(&host(), grey, 0, &s);
    const PatinaWavelengths wl{8, {360, 400, 450, 500, 560, 620, 700, 830}};
    float v[PATINA_MAX_WAVELENGTHS];
    host().eval_rgb_spectrum(&host(), &s, &wl, v);
    for (int i = 0; i < wl.count; ++i)
        EXPECT_EQ(v[i], 0.37f) << wl.lambda_nm[i];
}

// An emission colour (1, 1, 1) is D65 with luminance 1 (abi.h PatinaRgbSpectrum).
TEST(Host, WhiteEmissionHasUnitLuminance)
{
    const float white[3] = {1.0f, 1.0f, 1.0f};
    PatinaRgbSpectrum s{};
    host().rgb_to_spectrum(&host(), white, 1, &s);
    EXPECT_EQ(s.illuminant, 1);
    const patina::Xyz xyz = patina::emission_to_xyz([&](double l) {
        PatinaWavelengths wl{1, {static_cast<float>(l)}};
        float v[PATINA_MAX_WAVELENGTHS];
        host().eval_rgb_spectrum(&host(), &s, &wl, v);
        return static_cast<double>(v[0]);
    });
    EXPECT_NEAR(xyz[1], 1.0, 1e-4);
    // D65's chromaticity (CIE 15:2004 Table T.3: x = 0.31272, y = 0.32903).
    const double sum = xyz[0] + xyz[1] + xyz[2];
    EXPECT_NEAR(xyz[0] / sum, 0.31272, 2e-4);
    EXPECT_NEAR(xyz[1] / sum, 0.32903, 2e-4);
}

TEST(Host, AttributesByName)
{
    PatinaShadingContext ctx{};
    ctx.P = {1, 2, 3};
    ctx.uv = {0.25f, 0.75f};
    ctx.primitive_id = 42;
    float out[3] = {};
    EXPECT_EQ(host().attribute(&host(), &ctx, "P", 3, out), 3);
    EXPECT_EQ(out[2], 3.0f);
    EXPECT_EQ(host().attribute(&host(), &ctx, "uv", 3, out), 2);
    EXPECT_EQ(out[1], 0.75f);
    EXPECT_EQ(host().attribute(&host(), &ctx, "primitive_id", 1, out), 1);
    EXPECT_EQ(out[0], 42.0f);
    EXPECT_EQ(host().attribute(&host(), &ctx, "P", 2, out), 0);  // too small a buffer
    EXPECT_EQ(host().attribute(&host(), &ctx, "no_such_attribute", 3, out), 0);
}

TEST(Host, LookupWithoutTextureFillsZeros)
{
    float out[2] = {5.0f, 5.0f};
    EXPECT_EQ(host().texture_lookup(&host(), nullptr, nullptr, 0.5f, 0.5f, 0, 2, out), 0);
    EXPECT_EQ(out[0], 0.0f);
    EXPECT_EQ(out[1], 0.0f);
}

TEST(Host, ErrorsAreCollectedPerThread)
{
    patina::default_host().take_errors();
    host().error(&host(), "probe", "first");
    host().error(&host(), "probe", "second");
    const auto errors = patina::default_host().take_errors();
    ASSERT_EQ(errors.size(), 2u);
    EXPECT_EQ(errors[0], "first");
    EXPECT_TRUE(patina::default_host().take_errors().empty());
}

TEST(Host, ReadImageGivesRawFloatsOfOneSubimage)
{
    // A two-part EXR: part 0 is 3x2 RGB, part 1 is 2x1 with one channel.
    const std::string path = std::string(PATINA_TEST_BUILD_DIR) + "/host_read_image.exr";
    {
        auto out = OIIO::ImageOutput::create(path);
        ASSERT_TRUE(out);
        OIIO::ImageSpec specs[2] = {OIIO::ImageSpec(3, 2, 3, OIIO::TypeDesc::FLOAT),
                                    OIIO::ImageSpec(2, 1, 1, OIIO::TypeDesc::FLOAT)};
        specs[1].channelnames = {"density"};
        specs[0].attribute("oiio:subimagename", "colour");  // EXR parts need names
        specs[1].attribute("oiio:subimagename", "voxels");
        specs[1].full_width = 3;  // every part of an EXR shares one display window
        specs[1].full_height = 2;
        ASSERT_TRUE(out->open(path, 2, specs)) << out->geterror();
        std::vector<float> a(18);
        for (size_t i = 0; i < a.size(); ++i)
            a[i] = 0.5f * static_cast<float>(i) + 2.0f;  // beyond [0,1]: no clamping, no colour
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, a.data()));
        ASSERT_TRUE(out->open(path, specs[1], OIIO::ImageOutput::AppendSubimage));
        const float b[2] = {-1.0f, 7.0f};
        ASSERT_TRUE(out->write_image(OIIO::TypeDesc::FLOAT, b));
        ASSERT_TRUE(out->close());
    }
    int dims[3] = {0, 0, 0};
    ASSERT_EQ(host().read_image(&host(), path.c_str(), 1, dims, nullptr, 0), 1);
    EXPECT_EQ(dims[0], 2);
    EXPECT_EQ(dims[1], 1);
    EXPECT_EQ(dims[2], 1);
    float b[2];
    ASSERT_EQ(host().read_image(&host(), path.c_str(), 1, dims, b, 2), 1);
    EXPECT_EQ(b[0], -1.0f);
    EXPECT_EQ(b[1], 7.0f);
    std::vector<float> a(18);
    ASSERT_EQ(host().read_image(&host(), path.c_str(), 0, dims, a.data(), a.size()), 1);
    EXPECT_EQ(dims[2], 3);
    EXPECT_EQ(a[17], 0.5f * 17 + 2.0f);

    patina::default_host().take_errors();
    EXPECT_EQ(host().read_image(&host(), path.c_str(), 0, dims, a.data(), 5), 0);  // too small
    EXPECT_EQ(host().read_image(&host(), path.c_str(), 2, dims, nullptr, 0), 0);   // no part 2
    EXPECT_EQ(host().read_image(&host(), "/nonexistent/x.exr", 0, dims, nullptr, 0), 0);
    const auto errors = patina::default_host().take_errors();
    ASSERT_EQ(errors.size(), 3u);
    EXPECT_NE(errors[1].find("cannot read part 2 of"), std::string::npos) << errors[1];
    EXPECT_NE(errors[1].find("the file has 2 readable parts"), std::string::npos) << errors[1];
    EXPECT_NE(errors[2].find("/nonexistent/x.exr"), std::string::npos) << errors[2];
}

TEST(Host, OpenTextureReportsAMissingFile)
{
    EXPECT_TRUE(PATINA_HOST_HAS_READ_IMAGE(&host()));
    patina::default_host().take_errors();
    EXPECT_EQ(host().open_texture(&host(), "/nonexistent/thickness.exr", "raw"), nullptr);
    const auto errors = patina::default_host().take_errors();
    ASSERT_EQ(errors.size(), 1u);
    EXPECT_NE(errors[0].find("/nonexistent/thickness.exr"), std::string::npos) << errors[0];
}
