// flatten_texel against the closed forms of Dorsey & Hanrahan 1996 §4.1-4.3, wavelength by
// wavelength at the bands, on optics as a stack records them.
#include "flatten_test_materials.h"

#include "texgen/flatten/flat_texel.h"
#include "texgen/patina/stack_preview.h"

#include <patina/shading/fresnel.h>

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace patina::texgen {
namespace {

using test::copper_optics;
using test::kBrown;
using test::kGreen;
using test::kStone;
using test::layer_optics;
using test::linear_at;
using test::LinearLayer;
using test::test_stack;

/// §4.1, written out in double from the paper (independent of patina/shading/kubelka_munk):
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

/// K, S of a test layer at band node i.
double K_at(const LinearLayer& l, int i) { return linear_at(l.K_360, l.K_830, band_wavelength(i)); }
double S_at(const LinearLayer& l, int i) { return linear_at(l.S_360, l.S_830, band_wavelength(i)); }
RT layer_at(const LinearLayer& l, int i, double d) { return paper_layer(K_at(l, i), S_at(l, i), d); }

/// R∞ = 1 + K/S − sqrt((K/S)² + 2 K/S) (§4.1).
double r_infinity(const LinearLayer& l, int i)
{
    const double q = K_at(l, i) / S_at(l, i);
    return 1.0 + q - std::sqrt(q * q + 2.0 * q);
}

float& at(Bands& b, int i) { return b[i / 4][i % 4]; }
float at(const Bands& b, int i) { return b[i / 4][i % 4]; }

/// A spectrum given per node, as a colour through `to_rgb`.
template <class F>
Imath::V3f colour_of(const BandsToRgb& to_rgb, F value_at_node)
{
    Bands b{};
    for (int i = 0; i < kBandCount; ++i)
        at(b, i) = static_cast<float>(value_at_node(i));
    return to_rgb(b);
}

/// Copper's hemispherical reflectance 2 ∫ F(μ) μ dμ with the real-arithmetic Fresnel
/// (Lagarde 2013) on 4000 midpoints: independent of the base_reflectance_metal quadrature.
double copper_hemispherical()
{
    double sum = 0.0;
    for (int q = 0; q < 4000; ++q) {
        const double mu = (q + 0.5) / 4000.0;
        sum += shading::fresnel_conductor_real(static_cast<float>(mu), 0.25f, 3.42f) * mu;
    }
    return 2.0 * sum / 4000.0;
}

class FlatTexelTest : public ::testing::Test {
protected:
    FlatTexel flatten(const BandStack& stack, std::vector<float> d) const
    {
        return flatten_texel(stack, d, to_rgb_);
    }
    ColorManager colors_{std::filesystem::path(PATINA_SOURCE_DIR) / "ocio/config.ocio"};
    BandsToRgb to_rgb_{colors_};
    formats::MaterialOptics stone_ = layer_optics(kStone), green_ = layer_optics(kGreen),
                            brown_ = layer_optics(kBrown), copper_ = copper_optics();
};

TEST_F(FlatTexelTest, AWhiteReflectorIsWhite)
{
    // The weights are normalised so that a perfect white reflector is (1, 1, 1) (band_optics.h).
    const Imath::V3f white = to_rgb_(constant_bands(1.0f));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(white[c], 1.0f, 1e-6f);
    // A 600 nm-only reflectance is red: the CIE observer, not a grey.
    const Imath::V3f red = colour_of(to_rgb_, [](int i) { return band_wavelength(i) == 600.0f; });
    EXPECT_GT(red.x, 5.0f * std::abs(red.y));
    EXPECT_GT(red.x, 5.0f * std::abs(red.z));
}

TEST_F(FlatTexelTest, ZeroThicknessLayersGiveTheBase)
{
    const BandStack stack = test_stack(stone_, {brown_, green_});
    const FlatTexel f = flatten(stack, {0.0f, 0.0f});
    const Imath::V3f r_inf = colour_of(to_rgb_, [](int i) { return r_infinity(kStone, i); });
    for (int c = 0; c < 3; ++c) {
        // The base's R∞ exactly (to float), its own lobe unattenuated, no other lobe.
        EXPECT_NEAR(f.diffuse[c], r_inf[c], 2e-6);
        EXPECT_NEAR(f.interfaces[0].specular[c], 0.04f, 1e-7);
        EXPECT_EQ(f.interfaces[1].specular[c], 0.0f);
        EXPECT_EQ(f.interfaces[2].specular[c], 0.0f);
    }
    EXPECT_GT(r_inf.x, r_inf.z + 0.05f);  // a yellowish stone: the bands see K vary
    EXPECT_EQ(f.height_um, 0.0f);
    EXPECT_EQ(f.two_lobe.coat_weight, 0.0f);
    EXPECT_EQ(f.two_lobe.metallic, 0.0f);  // a dielectric base
    EXPECT_FLOAT_EQ(f.two_lobe.roughness, 0.6f);
}

TEST_F(FlatTexelTest, BareMetalIsAllSpecular)
{
    const BandStack stack = test_stack(copper_, {green_});
    const FlatTexel f = flatten(stack, {0.0f});
    // Normal incidence on n + ik: ((n − 1)² + k²) / ((n + 1)² + k²) (Born & Wolf §14.2).
    const double f0 = (0.75 * 0.75 + 3.42 * 3.42) / (1.25 * 1.25 + 3.42 * 3.42);
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(f.diffuse[c], 0.0f);
        EXPECT_NEAR(f.interfaces[0].specular[c], f0, 1e-6);
        EXPECT_NEAR(f.two_lobe.base_color[c], f0, 1e-6);
    }
    EXPECT_EQ(f.two_lobe.metallic, 1.0f);
    EXPECT_EQ(f.two_lobe.coat_weight, 0.0f);
    EXPECT_FLOAT_EQ(f.two_lobe.roughness, 0.15f);
}

TEST_F(FlatTexelTest, ThickOpaqueTopGivesItsRInfinity)
{
    const BandStack stack = test_stack(copper_, {brown_, green_});
    // 2000 µm of green (S >= 0.3/µm): T = O(e^-100), so the stack is its R∞ at every band.
    const std::vector<float> d{1.0f, 2000.0f};
    const Bands diffuse = stack_diffuse(stack, d, false);
    for (int i = 0; i < kBandCount; ++i)
        EXPECT_NEAR(at(diffuse, i), r_infinity(kGreen, i), 1e-6) << band_wavelength(i);
    const FlatTexel f = flatten(stack, d);
    const Imath::V3f r_inf = colour_of(to_rgb_, [](int i) { return r_infinity(kGreen, i); });
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(f.diffuse[c], r_inf[c], 1e-5);
        // §4.3: "If the final specular color of one of the glossy terms is 0, that usually
        // implies that it has been covered by an opaque material."
        EXPECT_LT(f.interfaces[0].specular[c], 1e-20f);
        EXPECT_LT(f.interfaces[1].specular[c], 1e-20f);
        EXPECT_NEAR(f.interfaces[2].specular[c], 0.04f, 1e-7);
        EXPECT_NEAR(f.two_lobe.base_color[c], r_inf[c], 1e-5);
    }
    EXPECT_EQ(f.two_lobe.coat_weight, 1.0f);
    EXPECT_FLOAT_EQ(f.two_lobe.coat_roughness, 0.5f);
    EXPECT_LT(f.two_lobe.metallic, 1e-6f);
    EXPECT_FLOAT_EQ(f.height_um, 2001.0f);
}

TEST_F(FlatTexelTest, OneLayerMatchesThePaperClosedForms)
{
    const BandStack stack = test_stack(stone_, {green_});
    const float d = 1.5f;
    const Bands diffuse = stack_diffuse(stack, std::vector<float>{d}, false);
    for (int i = 0; i < kBandCount; ++i) {
        const RT l = layer_at(kGreen, i, d);
        // §4.2 over the opaque base: R = R1 + T1² R2 / (1 − R1 R2).
        const double rb = r_infinity(kStone, i);
        EXPECT_NEAR(at(diffuse, i), l.R + l.T * l.T * rb / (1.0 - l.R * rb), 2e-6)
            << band_wavelength(i);
    }
    const FlatTexel f = flatten(stack, {d});
    // §4.3: the base's specular colour "multiplied twice by diffuse transmittance".
    const Imath::V3f base_lobe = colour_of(to_rgb_, [&](int i) {
        const RT l = layer_at(kGreen, i, d);
        return 0.04 * l.T * l.T;
    });
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(f.interfaces[0].specular[c], base_lobe[c], 1e-7);
        EXPECT_NEAR(f.interfaces[1].specular[c], 0.04f, 1e-7);
    }
    // The stack is translucent here (not a vacuous test).
    EXPECT_GT(f.interfaces[0].specular.y, 0.1f * 0.04f);
}

TEST_F(FlatTexelTest, MetalBaseDiffuseExcludesTheMetalsOwnReflection)
{
    const BandStack stack = test_stack(copper_, {brown_});
    const float d = 0.6f;
    const double rb = copper_hemispherical();
    const Bands diffuse = stack_diffuse(stack, std::vector<float>{d}, false);
    const Bands whole = stack_diffuse(stack, std::vector<float>{d}, true);
    for (int i = 0; i < kBandCount; ++i) {
        const RT l = layer_at(kBrown, i, d);
        const double km = l.R + l.T * l.T * rb / (1.0 - l.R * rb);
        // The quadratures of the hemispherical reflectance agree to 1e-5 (64 against 4000 nodes).
        EXPECT_NEAR(at(whole, i), km, 2e-5) << band_wavelength(i);
        EXPECT_NEAR(at(diffuse, i), km - l.T * l.T * rb, 2e-5) << band_wavelength(i);
        EXPECT_GE(at(diffuse, i), l.R - 1e-6);
    }
    const FlatTexel f = flatten(stack, {d});
    const double f0 = (0.75 * 0.75 + 3.42 * 3.42) / (1.25 * 1.25 + 3.42 * 3.42);
    const Imath::V3f base_lobe = colour_of(to_rgb_, [&](int i) {
        const RT l = layer_at(kBrown, i, d);
        return f0 * l.T * l.T;
    });
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(f.interfaces[0].specular[c], base_lobe[c], 1e-6);
    // The two-lobe base keeps both parts' luminance: diffuse + attenuated copper.
    const float lum_metal = luminance(f.interfaces[0].specular);
    EXPECT_NEAR(f.two_lobe.metallic, lum_metal / (lum_metal + luminance(f.diffuse)), 1e-6);
    EXPECT_GT(f.two_lobe.metallic, 0.05f);
    EXPECT_LT(f.two_lobe.metallic, 0.95f);
    EXPECT_EQ(f.two_lobe.coat_weight, 1.0f);  // brown's specular 0.08 > glTF's 0.04
}

TEST_F(FlatTexelTest, TwoHalfLayersEqualOneLayer)
{
    // An identity of the KM equations: d/2 + d/2 of one material = d.
    const FlatTexel one = flatten(test_stack(stone_, {green_}), {3.0f});
    const FlatTexel two = flatten(test_stack(stone_, {green_, green_}), {1.5f, 1.5f});
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(one.diffuse[c], two.diffuse[c], 2e-6);
        EXPECT_NEAR(one.interfaces[0].specular[c], two.interfaces[0].specular[c], 1e-6);
    }
}

TEST_F(FlatTexelTest, ALayerOfTheMaterialAboveItHasNoInterface)
{
    // One material has no boundary with itself (patina/shading/layer_stack.h), as in
    // layered_km: 1.5 + 1.5 µm of green shows the lobe of its top only.
    const FlatTexel one = flatten(test_stack(stone_, {green_}), {3.0f});
    const FlatTexel two = flatten(test_stack(stone_, {green_, green_}), {1.5f, 1.5f});
    for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(two.interfaces[1].specular[c], 0.0f);
        EXPECT_EQ(two.interfaces[2].specular[c], one.interfaces[1].specular[c]);
        EXPECT_NEAR(one.interfaces[1].specular[c], 0.04f, 1e-7);
    }
    // An absent layer between two of one material does not separate them.
    const FlatTexel gap =
        flatten(test_stack(stone_, {green_, brown_, green_}), {1.5f, 0.0f, 1.5f});
    EXPECT_EQ(gap.interfaces[1].specular.x, 0.0f);
    EXPECT_EQ(gap.interfaces[2].specular.x, 0.0f);
    EXPECT_GT(gap.interfaces[3].specular.x, 0.0f);
}

TEST_F(FlatTexelTest, FlattenAndThePreviewComputeOneModel)
{
    // The stack model has one home (patina/shading/layer_stack.h): the preview's colour is
    // flatten's diffuse albedo over a dielectric base, bit for bit.
    const BandStack stack = test_stack(stone_, {brown_, green_});
    const std::vector<std::vector<float>> d{{0.0f, 0.4f, 2.0f, 0.02f}, {1.2f, 0.0f, 0.7f, 5.0f}};
    const std::vector<Imath::V3f> colours = stack_diffuse_color(stack, d, 4, to_rgb_);
    for (size_t i = 0; i < 4; ++i) {
        const FlatTexel f = flatten(stack, {d[0][i], d[1][i]});
        for (int c = 0; c < 3; ++c)
            EXPECT_EQ(colours[i][c], f.diffuse[c]) << "texel " << i << " channel " << c;
    }
}

TEST_F(FlatTexelTest, AttenuationUsesTheCompositeTransmittanceOfTheLayersAbove)
{
    const BandStack stack = test_stack(copper_, {brown_, green_});
    const FlatTexel f = flatten(stack, {0.4f, 1.2f});
    const double f0 = (0.75 * 0.75 + 3.42 * 3.42) / (1.25 * 1.25 + 3.42 * 3.42);
    // §4.2: T = T1 T2 / (1 − R1 R2) for green over brown.
    const Imath::V3f base_lobe = colour_of(to_rgb_, [&](int i) {
        const RT b = layer_at(kBrown, i, 0.4), g = layer_at(kGreen, i, 1.2);
        const double t = g.T * b.T / (1.0 - g.R * b.R);
        return f0 * t * t;
    });
    const Imath::V3f brown_lobe = colour_of(to_rgb_, [&](int i) {
        const RT g = layer_at(kGreen, i, 1.2);
        return 0.08 * g.T * g.T;
    });
    for (int c = 0; c < 3; ++c) {
        EXPECT_NEAR(f.interfaces[0].specular[c], base_lobe[c], 1e-6);
        EXPECT_NEAR(f.interfaces[1].specular[c], brown_lobe[c], 1e-7);
        EXPECT_NEAR(f.interfaces[2].specular[c], 0.04f, 1e-7);
    }
    EXPECT_FLOAT_EQ(f.interfaces[1].roughness, 0.25f);
    // The base lobe of the two-lobe reduction: F0-weighted mean alpha of copper and brown.
    const double w0 = luminance(f.interfaces[0].specular), w1 = luminance(f.interfaces[1].specular);
    const double alpha = (w0 * 0.15 * 0.15 + w1 * 0.25 * 0.25) / (w0 + w1);
    EXPECT_NEAR(f.two_lobe.roughness, std::sqrt(alpha), 1e-6);
}

TEST_F(FlatTexelTest, ThinFilmsFadeTheirInterfaceIn)
{
    // As layered_km: a layer of 0.02 µm shows 0.02 / 0.05 of its interface's lobe.
    const FlatTexel f = flatten(test_stack(copper_, {brown_}), {0.02f});
    EXPECT_NEAR(f.interfaces[1].specular.x, 0.4f * 0.08f, 1e-7);
    EXPECT_NEAR(f.two_lobe.coat_weight, 0.4f * 0.08f / kClearcoatF0, 1e-5);
}

TEST_F(FlatTexelTest, LayerCountMustMatch)
{
    const BandStack stack = test_stack(stone_, {green_});
    EXPECT_THROW(flatten(stack, {1.0f, 2.0f}), std::invalid_argument);
}

TEST_F(FlatTexelTest, AMaterialWithoutOpticsIsNamed)
{
    formats::PatinaTable t;
    t.base = "stone";
    t.materials.emplace("stone", stone_);
    formats::PatinaLayer layer;
    layer.material = "verdigris";
    t.layers.push_back(layer);
    try {
        band_stack(t, "here/stack.toml");
        FAIL() << "no error";
    } catch (const std::runtime_error& e) {
        EXPECT_STREQ(e.what(), "patina stack 'here/stack.toml': layer 1 material 'verdigris' "
                               "has no optics in [patina.materials]");
    }
}

}  // namespace
}  // namespace patina::texgen

namespace patina::texgen {
namespace {

TEST_F(FlatTexelTest, TheFittedGltfMaterialReflectsWhatTheStackDoes)
{
    // The fit (gltf_fit.h) against the texel's albedo, for both renderers: the material's
    // albedo in its target's model against the stack's, as cosine-weighted RMS over the 8
    // cosines, of the whole and of the diffuse lobe; the fit against the two-lobe reduction
    // it starts from. Copper under tarnish and green, and a dielectric base under them.
    auto rms = [](auto&& error) {
        double sum = 0.0;
        for (int g = 0; g < shading::kGaussNodes; ++g)
            for (int c = 0; c < 3; ++c)
                sum += shading::kGaussMeanWeight[g] * error(g, c) * error(g, c) / 3.0;
        return std::sqrt(sum);
    };
    for (const bool metal : {true, false}) {
        BandStack stack = test_stack(metal ? copper_ : stone_, {brown_, green_});
        tabulate_lobe_albedos(stack, to_rgb_);
        for (const GltfTarget target : {GltfTarget::khronos, GltfTarget::blender}) {
            const std::vector<float> d{0.3f, 0.6f};
            const FlatTexel f = flatten_texel(stack, d, to_rgb_, {&gltf_albedo_model(), target});
            const FlatTexel reduced = flatten_texel(stack, d, to_rgb_);
            const AlbedoParts want = texel_albedo(f);
            auto whole = [&](const TwoLobe& m) {
                const auto got = gltf_albedo_of(gltf_albedo_model(), target, m);
                return rms([&](int g, int c) {
                    return got[g][c] - (want.diffuse[g][c] + want.glossy[g][c]);
                });
            };
            const double fitted = whole(f.two_lobe), before = whole(reduced.two_lobe);
            std::printf("[ fit ] %s, %s base: albedo RMS %.4f fitted, %.4f reduced\n",
                        gltf_target_name(target), metal ? "metal" : "dielectric", fitted, before);
            EXPECT_LT(fitted, before);
            EXPECT_LT(fitted, 0.06);
            EXPECT_GE(f.two_lobe.coat_weight, 0.0f);
            EXPECT_LE(f.two_lobe.coat_weight, 1.0f);
        }
    }
    EXPECT_THROW(gltf_target("maya"), std::runtime_error);
}

}  // namespace
}  // namespace patina::texgen
