// The host services table plugins see (abi.h PatinaHost), exercised through the C table.
#include "core/host.h"

#include "core/spectrum.h"

#include <gtest/gtest.h>

#include <cstring>

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
