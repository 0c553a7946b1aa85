// flatten_texel against the closed forms of Dorsey & Hanrahan 1996 §4.1-4.3.
#include "flatten_test_materials.h"

#include "texgen/flatten/flat_texel.h"
#include "texgen/patina/stack_preview.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace patina::texgen {
namespace {

using test::brown_material;
using test::copper_material;
using test::green_material;
using test::stone_material;

/// §4.1, written out in double from the paper (independent of core/kubelka_munk):
/// R = sinh(bSd) / (a sinh(bSd) + b cosh(bSd)), T = b / (a sinh(bSd) + b cosh(bSd)),
/// a = (S + K) / S, b = sqrt(a^2 - 1).
struct RT {
    double R, T;
};
RT paper_layer(double K, double S, double d)
{
    const double a = (S + K) / S, b = std::sqrt(a * a - 1.0);
    const double den = a * std::sinh(b * S * d) + b * std::cosh(b * S * d);
    return {std::sinh(b * S * d) / den, b / den};
}

FlatTexel flatten(const PatinaMaterial& base, std::vector<const PatinaMaterial*> layers,
                  std::vector<float> d)
{
    return flatten_texel(base, layers, d);
}

TEST(FlatTexel, ZeroThicknessLayersGiveTheBase)
{
    const PatinaMaterial stone = stone_material(), green = green_material(),
                         brown = brown_material();
    const FlatTexel f = flatten(stone, {&brown, &green}, {0.0f, 0.0f});
    for (int c = 0; c < 3; ++c) {
        // The base's albedo exactly, its own lobe unattenuated, no other lobe.
        EXPECT_EQ(f.diffuse[c], stone.color[c]);
        EXPECT_EQ(f.interfaces[0].specular[c], stone.specular[c]);
        EXPECT_EQ(f.interfaces[1].specular[c], 0.0f);
        EXPECT_EQ(f.interfaces[2].specular[c], 0.0f);
    }
    EXPECT_EQ(f.height_um, 0.0f);
    EXPECT_EQ(f.two_lobe.coat_weight, 0.0f);
    EXPECT_EQ(f.two_lobe.metallic, 0.0f);  // a dielectric base
    EXPECT_FLOAT_EQ(f.two_lobe.roughness, stone.roughness);
}

TEST(FlatTexel, BareMetalIsAllSpecular)
{
    const PatinaMaterial copper = copper_material(), green = green_material();
    const FlatTexel f = flatten(copper, {&green}, {0.0f});
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(f.diffuse[c], 0.0f);
        EXPECT_EQ(f.interfaces[0].specular[c], copper.color[c]);
        EXPECT_FLOAT_EQ(f.two_lobe.base_color[c], copper.color[c]);
    }
    EXPECT_EQ(f.two_lobe.metallic, 1.0f);
    EXPECT_EQ(f.two_lobe.coat_weight, 0.0f);
    EXPECT_FLOAT_EQ(f.two_lobe.roughness, copper.roughness);
}

TEST(FlatTexel, ThickOpaqueTopGivesItsRInfinity)
{
    const PatinaMaterial copper = copper_material(), green = green_material(),
                         brown = brown_material();
    // 2000 µm of green (S = 0.35/µm): T = O(e^-200), so the stack is its R_inf.
    const FlatTexel f = flatten(copper, {&brown, &green}, {1.0f, 2000.0f});
    for (int c = 0; c < 3; ++c) {
        // R_inf = 1 + K/S - sqrt((K/S)^2 + 2 K/S) (§4.1) is the material's colour.
        const double q = green.absorption[c] / green.scattering[c];
        const double r_inf = 1.0 + q - std::sqrt(q * q + 2.0 * q);
        EXPECT_NEAR(f.diffuse[c], r_inf, 1e-5);
        EXPECT_NEAR(f.diffuse[c], green.color[c], 1e-5);
        // §4.3: "If the final specular color of one of the glossy terms is 0, that usually
        // implies that it has been covered by an opaque material."
        EXPECT_LT(f.interfaces[0].specular[c], 1e-20f);
        EXPECT_LT(f.interfaces[1].specular[c], 1e-20f);
        EXPECT_EQ(f.interfaces[2].specular[c], green.specular[c]);
        EXPECT_NEAR(f.two_lobe.base_color[c], green.color[c], 1e-5);
    }
    EXPECT_EQ(f.two_lobe.coat_weight, 1.0f);
    EXPECT_EQ(f.two_lobe.coat_roughness, green.roughness);
    EXPECT_LT(f.two_lobe.metallic, 1e-6f);
    EXPECT_FLOAT_EQ(f.height_um, 2001.0f);
}

TEST(FlatTexel, OneLayerMatchesThePaperClosedForms)
{
    const PatinaMaterial stone = stone_material(), green = green_material();
    const float d = 1.5f;
    const FlatTexel f = flatten(stone, {&green}, {d});
    for (int c = 0; c < 3; ++c) {
        const RT l = paper_layer(green.absorption[c], green.scattering[c], d);
        // §4.2 over the opaque base: R = R1 + T1^2 R2 / (1 - R1 R2).
        const double rb = stone.color[c];
        EXPECT_NEAR(f.diffuse[c], l.R + l.T * l.T * rb / (1.0 - l.R * rb), 2e-6);
        // §4.3: the base's specular colour "multiplied twice by diffuse transmittance".
        EXPECT_NEAR(f.interfaces[0].specular[c], stone.specular[c] * l.T * l.T, 1e-7);
        EXPECT_EQ(f.interfaces[1].specular[c], green.specular[c]);
    }
    // Rough check that the stack is translucent here (not a vacuous test).
    EXPECT_GT(f.interfaces[0].specular.y, 0.1f * stone.specular.y);
}

TEST(FlatTexel, MetalBaseDiffuseExcludesTheMetalsOwnReflection)
{
    const PatinaMaterial copper = copper_material(), brown = brown_material();
    const float d = 0.6f;
    const FlatTexel f = flatten(copper, {&brown}, {d});
    for (int c = 0; c < 3; ++c) {
        const RT l = paper_layer(brown.absorption[c], brown.scattering[c], d);
        const double rb = copper.color[c];
        const double km = l.R + l.T * l.T * rb / (1.0 - l.R * rb);
        EXPECT_NEAR(f.diffuse[c], km - l.T * l.T * rb, 2e-6);
        EXPECT_NEAR(f.interfaces[0].specular[c], rb * l.T * l.T, 1e-6);
        EXPECT_GE(f.diffuse[c], l.R - 1e-6);
    }
    // The two-lobe base keeps both parts' luminance: diffuse + attenuated copper.
    const float lum_metal = luminance(f.interfaces[0].specular);
    EXPECT_NEAR(f.two_lobe.metallic, lum_metal / (lum_metal + luminance(f.diffuse)), 1e-6);
    EXPECT_GT(f.two_lobe.metallic, 0.05f);
    EXPECT_LT(f.two_lobe.metallic, 0.95f);
    EXPECT_EQ(f.two_lobe.coat_weight, 1.0f);  // brown's specular 0.08 > glTF's 0.04
}

TEST(FlatTexel, TwoHalfLayersEqualOneLayer)
{
    // An identity of the KM equations (issue 6): d/2 + d/2 of one material = d.
    const PatinaMaterial stone = stone_material(), green = green_material();
    const FlatTexel one = flatten(stone, {&green}, {3.0f});
    const FlatTexel two = flatten(stone, {&green, &green}, {1.5f, 1.5f});
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(one.diffuse[c], two.diffuse[c], 2e-6);
        EXPECT_NEAR(one.interfaces[0].specular[c], two.interfaces[0].specular[c], 1e-6);
    }
}

TEST(FlatTexel, ALayerOfTheMaterialAboveItHasNoInterface)
{
    // One material has no boundary with itself (patina/shading/layer_stack.h), as in
    // layered_km: 1.5 + 1.5 um of green shows the lobe of its top only, and the base's
    // lobe sees the same layers as under one 3 um layer.
    const PatinaMaterial stone = stone_material(), green = green_material();
    const FlatTexel one = flatten(stone, {&green}, {3.0f});
    const FlatTexel two = flatten(stone, {&green, &green}, {1.5f, 1.5f});
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(two.interfaces[1].specular[c], 0.0f);
        EXPECT_EQ(two.interfaces[2].specular[c], green.specular[c]);
        EXPECT_EQ(one.interfaces[1].specular[c], green.specular[c]);
    }
    // An absent layer between two of one material does not separate them.
    const FlatTexel gap = flatten(stone, {&green, &stone, &green}, {1.5f, 0.0f, 1.5f});
    EXPECT_EQ(gap.interfaces[1].specular.x, 0.0f);
    EXPECT_EQ(gap.interfaces[2].specular.x, 0.0f);
}

TEST(FlatTexel, FlattenAndThePreviewComputeOneModel)
{
    // The stack model has one home (patina/shading/layer_stack.h): the preview's colour is
    // flatten's diffuse albedo over a dielectric base, bit for bit.
    const PatinaMaterial stone = stone_material(), green = green_material(),
                         brown = brown_material();
    const std::vector<float> brown_d{0.0f, 0.4f, 2.0f, 0.02f}, green_d{1.2f, 0.0f, 0.7f, 5.0f};
    const std::vector<PreviewLayer> preview{{&brown, brown_d}, {&green, green_d}};
    const std::vector<Imath::V3f> colours = stack_diffuse_color(stone, preview, brown_d.size());
    for (size_t i = 0; i < brown_d.size(); ++i) {
        const FlatTexel f = flatten(stone, {&brown, &green}, {brown_d[i], green_d[i]});
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(colours[i][c], f.diffuse[c]) << "texel " << i << " channel " << c;
    }
}

TEST(FlatTexel, AttenuationUsesTheCompositeTransmittanceOfTheLayersAbove)
{
    const PatinaMaterial copper = copper_material(), green = green_material(),
                         brown = brown_material();
    const FlatTexel f = flatten(copper, {&brown, &green}, {0.4f, 1.2f});
    for (int c = 0; c < 3; ++c) {
        const RT b = paper_layer(brown.absorption[c], brown.scattering[c], 0.4);
        const RT g = paper_layer(green.absorption[c], green.scattering[c], 1.2);
        // §4.2: T = T1 T2 / (1 - R1 R2) for green over brown.
        const double t = g.T * b.T / (1.0 - g.R * b.R);
        EXPECT_NEAR(f.interfaces[0].specular[c], copper.specular[c] * t * t, 1e-6);
        EXPECT_NEAR(f.interfaces[1].specular[c], brown.specular[c] * g.T * g.T, 1e-7);
        EXPECT_EQ(f.interfaces[2].specular[c], green.specular[c]);
    }
    EXPECT_FLOAT_EQ(f.interfaces[1].roughness, brown.roughness);
    // The base lobe of the two-lobe reduction: F0-weighted mean alpha of copper and brown.
    const double w0 = luminance(f.interfaces[0].specular), w1 = luminance(f.interfaces[1].specular);
    const double alpha = (w0 * 0.15 * 0.15 + w1 * 0.25 * 0.25) / (w0 + w1);
    EXPECT_NEAR(f.two_lobe.roughness, std::sqrt(alpha), 1e-6);
}

TEST(FlatTexel, ThinFilmsFadeTheirInterfaceIn)
{
    // As layered_km: a layer of 0.02 µm shows 0.02 / 0.05 of its interface's lobe.
    const PatinaMaterial copper = copper_material(), brown = brown_material();
    const FlatTexel f = flatten(copper, {&brown}, {0.02f});
    EXPECT_NEAR(f.interfaces[1].specular.x, 0.4f * brown.specular.x, 1e-7);
    EXPECT_NEAR(f.two_lobe.coat_weight, 0.4f * 0.08f / kClearcoatF0, 1e-6);
}

TEST(FlatTexel, LayerCountMustMatch)
{
    const PatinaMaterial stone = stone_material(), green = green_material();
    EXPECT_THROW(flatten(stone, {&green}, {1.0f, 2.0f}), std::invalid_argument);
}

}  // namespace
}  // namespace patina::texgen
