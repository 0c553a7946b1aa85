// Kubelka-Munk layers and compositing (include/patina/shading/kubelka_munk.h, in double)
// against closed forms.
#include <patina/shading/kubelka_munk.h>

#include <gtest/gtest.h>

#include <cmath>
#include <span>
#include <vector>

namespace patina {
namespace {

    using shading::km_k_over_s;
    using shading::km_r_infinity;

    /// A homogeneous layer or a stack seen from above: R and T.
    struct KmLayer {
        double R = 0.0, T = 1.0;
    };

    KmLayer km_layer(double K, double S, double d)
    {
        const shading::KmLayers<double> l = shading::km_layer(K, S, d);
        return {l.r_top, l.t};
    }

    /// `top` (homogeneous) over `bottom`, seen from above (§4.2).
    KmLayer km_composite(const KmLayer& top, const KmLayer& bottom)
    {
        const shading::KmLayers<double> l = shading::km_composite<double>(
            {top.R, top.R, top.T}, {bottom.R, bottom.R, bottom.T});
        return {l.r_top, l.t};
    }

    /// Layers top to bottom folded from the bottom up.
    KmLayer km_composite_stack(std::span<const KmLayer> top_to_bottom)
    {
        KmLayer acc;
        for (auto it = top_to_bottom.rbegin(); it != top_to_bottom.rend(); ++it)
            acc = km_composite(*it, acc);
        return acc;
    }

    double km_reflectance_over(std::span<const KmLayer> top_to_bottom, double base_R)
    {
        KmLayer acc{base_R, 0.0};
        for (auto it = top_to_bottom.rbegin(); it != top_to_bottom.rend(); ++it)
            acc = km_composite(*it, acc);
        return acc.R;
    }

    // D&H 1996 §4.1 exactly as printed, in double, for moderate arguments.
    KmLayer reference_layer(double K, double S, double d)
    {
        const double a = (S + K) / S, b = std::sqrt(a * a - 1.0);
        const double den = a * std::sinh(b * S * d) + b * std::cosh(b * S * d);
        return {std::sinh(b * S * d) / den, b / den};
    }

    TEST(KubelkaMunkTest, LayerMatchesPaperFormula)
    {
        for (double K : {0.05, 0.5, 3.0})
            for (double S : {0.1, 1.0, 7.0})
                for (double d : {0.01, 0.3, 2.0}) {
                    const KmLayer r = reference_layer(K, S, d), l = km_layer(K, S, d);
                    EXPECT_NEAR(l.R, r.R, 1e-6) << K << " " << S << " " << d;
                    EXPECT_NEAR(l.T, r.T, 1e-6) << K << " " << S << " " << d;
                }
    }

    TEST(KubelkaMunkTest, RInfinityFromKOverS)
    {
        // D&H 1996 §4.1 with the minus sign (DESIGN.md): K/S = 1 gives 1 + 1 - sqrt(3).
        EXPECT_NEAR(km_r_infinity(1.0f), 2.0 - std::sqrt(3.0), 1e-7);
        EXPECT_EQ(km_r_infinity(0.0), 1.0); // no absorption: all light comes back
        EXPECT_NEAR(km_r_infinity(1e6f), 0.0f, 1e-6);
        // Round trip with the inverse (1 - R)^2 / (2R).
        for (float r : {0.01f, 0.2f, 0.5f, 0.9f, 0.999f})
            EXPECT_NEAR(km_r_infinity(km_k_over_s(r)), r, 2e-6 * std::max(1.0f, 1.0f / r));
        EXPECT_DOUBLE_EQ(km_k_over_s(0.5), 0.25);
    }

    TEST(KubelkaMunkTest, ThickLayerTendsToRInfinity)
    {
        for (float K : {0.1f, 1.0f, 5.0f})
            for (float S : {0.2f, 2.0f}) {
                const KmLayer thick = km_layer(K, S, 1e4f);
                EXPECT_NEAR(thick.R, km_r_infinity(K / S), 1e-6);
                EXPECT_EQ(thick.T, 0.0f);
                // No overflow for absurd thickness or coefficients, and the infinite limit.
                const KmLayer huge = km_layer(K * 1e20f, S * 1e20f, 1e30f);
                EXPECT_NEAR(huge.R, km_r_infinity(K / S), 1e-6);
                EXPECT_NEAR(km_layer(K, S, INFINITY).R, km_r_infinity(K / S), 1e-7);
            }
    }

    TEST(KubelkaMunkTest, ZeroThicknessAndLimits)
    {
        const KmLayer zero = km_layer(2.0f, 3.0f, 0.0f);
        EXPECT_EQ(zero.R, 0.0f);
        EXPECT_EQ(zero.T, 1.0f);
        // Pure absorber (S = 0): Beer-Lambert, nothing reflected.
        const KmLayer absorber = km_layer(2.0f, 0.0f, 0.7f);
        EXPECT_EQ(absorber.R, 0.0f);
        EXPECT_NEAR(absorber.T, std::exp(-1.4), 1e-7);
        // Pure scatterer (K = 0): R = Sd / (1 + Sd), T = 1 / (1 + Sd) (the b -> 0 limit).
        const KmLayer scatterer = km_layer(0.0f, 4.0f, 0.5f);
        EXPECT_NEAR(scatterer.R, 2.0 / 3.0, 1e-7);
        EXPECT_NEAR(scatterer.T, 1.0 / 3.0, 1e-7);
        // Continuity towards both limits.
        EXPECT_NEAR(km_layer(1e-7f, 4.0f, 0.5f).R, 2.0 / 3.0, 1e-6);
        EXPECT_NEAR(km_layer(2.0f, 1e-7f, 0.7f).T, std::exp(-1.4), 1e-6);
        const KmLayer nothing = km_layer(0.0f, 0.0f, 1.0f);
        EXPECT_EQ(nothing.R, 0.0f);
        EXPECT_EQ(nothing.T, 1.0f);
    }

    TEST(KubelkaMunkTest, EnergyConservation)
    {
        for (float K : {0.0f, 0.01f, 1.0f, 10.0f})
            for (float S : {0.0f, 0.5f, 5.0f})
                for (float d : {0.0f, 0.1f, 1.0f, 10.0f}) {
                    const KmLayer l = km_layer(K, S, d);
                    EXPECT_GE(l.R, 0.0f);
                    EXPECT_GE(l.T, 0.0f);
                    if (K == 0.0f) {
                        EXPECT_NEAR(l.R + l.T, 1.0f, 1e-6) << S << " " << d;
                    } else if (d > 0.0f) {
                        EXPECT_LT(l.R + l.T, 1.0f) << K << " " << S << " " << d;
                    }
                }
    }

    TEST(KubelkaMunkTest, HalfLayersCompositeToWholeLayer)
    {
        // The KM solution is a semigroup in thickness: d/2 over d/2 is d (D&H 1996 §4.2 applied
        // to §4.1); also for unequal splits through the stack helper.
        for (float K : {0.0f, 0.3f, 2.0f})
            for (float S : {0.5f, 3.0f})
                for (float d : {0.1f, 1.0f, 4.0f}) {
                    const KmLayer half = km_layer(K, S, 0.5f * d);
                    const KmLayer whole = km_layer(K, S, d);
                    const KmLayer c = km_composite(half, half);
                    EXPECT_NEAR(c.R, whole.R, 2e-6);
                    EXPECT_NEAR(c.T, whole.T, 2e-6);
                    const std::vector<KmLayer> parts = {km_layer(K, S, 0.2f * d),
                                                        km_layer(K, S, 0.5f * d),
                                                        km_layer(K, S, 0.3f * d)};
                    const KmLayer s = km_composite_stack(parts);
                    EXPECT_NEAR(s.R, whole.R, 3e-6);
                    EXPECT_NEAR(s.T, whole.T, 3e-6);
                }
    }

    TEST(KubelkaMunkTest, OpaqueBaseMatchesKubelkaFormula)
    {
        // Kubelka & Munk 1931 reflectance of a layer over a background Rb:
        // R = (1/Ri (Rb - Ri) - Ri (Rb - 1/Ri) e^{Sd (1/Ri - Ri)})
        //     / ((Rb - Ri) - (Rb - 1/Ri) e^{Sd (1/Ri - Ri)}),  Ri = R_inf(K/S).
        for (double K : {0.1, 1.0})
            for (double S : {0.5, 2.0})
                for (double d : {0.05, 0.5, 2.0})
                    for (double rb : {0.0, 0.3, 0.9}) {
                        const double ri = km_r_infinity(K / S);
                        const double e = std::exp(S * d * (1.0 / ri - ri));
                        const double expected = ((rb - ri) / ri - ri * (rb - 1.0 / ri) * e) /
                                                ((rb - ri) - (rb - 1.0 / ri) * e);
                        const KmLayer layer = km_layer(K, S, d);
                        const KmLayer over = km_composite(layer, {rb, 0.0});
                        EXPECT_NEAR(over.R, expected, 2e-6)
                            << K << " " << S << " " << d << " " << rb;
                        EXPECT_EQ(over.T, 0.0f);
                        EXPECT_FLOAT_EQ(km_reflectance_over(std::span(&layer, 1), rb), over.R);
                    }
    }

    TEST(KubelkaMunkTest, StackOrderIsTopToBottom)
    {
        // A dark absorber on top hides a white scatterer; the other way round it does not.
        const KmLayer dark = km_layer(5.0f, 0.1f, 1.0f), white = km_layer(0.0f, 50.0f, 1.0f);
        const std::vector<KmLayer> dark_on_top = {dark, white}, white_on_top = {white, dark};
        EXPECT_LT(km_composite_stack(dark_on_top).R, 0.05f);
        EXPECT_GT(km_composite_stack(white_on_top).R, 0.95f);
        EXPECT_FLOAT_EQ(km_composite_stack(dark_on_top).T, km_composite_stack(white_on_top).T);
        // Explicit fold: top over (middle over bottom).
        const KmLayer mid = km_layer(0.4f, 1.0f, 0.3f);
        const std::vector<KmLayer> three = {dark, mid, white};
        const KmLayer manual = km_composite(dark, km_composite(mid, white));
        EXPECT_FLOAT_EQ(km_composite_stack(three).R, manual.R);
        EXPECT_FLOAT_EQ(km_reflectance_over(three, 0.5f),
                        km_composite(dark, km_composite(mid, km_composite(white, {0.5f, 0.0f}))).R);
        EXPECT_EQ(km_composite_stack(std::span<const KmLayer>{}).R, 0.0f);
        EXPECT_EQ(km_composite_stack(std::span<const KmLayer>{}).T, 1.0f);
    }

} // namespace
} // namespace patina
