#include "texgen/patina/operators.h"

#include "ops_test_util.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace patina::texgen {
namespace {

    using test::message_of;
    using test::random_stack;
    using test::random_values;
    using test::same_bits;

    constexpr size_t kTexels = 20000;

    float next_up(float x)
    {
        return std::nextafter(x, std::numeric_limits<float>::infinity());
    }

    TEST(Coat, AddsThicknessTimesTheMapOnTop)
    {
        LayerStack s = new_stack(0, 4);
        coat(s, 2, 1.5f, std::vector<float>{0.0f, 1.0f, 2.0f, -3.0f});
        coat(s, 3, 0.25f);
        ASSERT_EQ(s.layers.size(), 2u);
        EXPECT_EQ(s.layers[0].material, 2);
        EXPECT_EQ(s.layers[0].thickness_um, (std::vector<float>{0.0f, 1.5f, 3.0f, 0.0f}))
            << "negative map values count as 0";
        EXPECT_EQ(s.layers[1].thickness_um, (std::vector<float>(4, 0.25f)));
        EXPECT_EQ(s.exposed_material(0), 3);
    }

    // Bitwise: erode removes the same float product thickness * map[i] that coat put in the
    // top layer, and x - x == 0 exactly in IEEE arithmetic; it stops there, so the layers
    // below are untouched, and adding the emptied layer's +0 to the total changes no bit.
    TEST(Erode, UndoesACoatOfTheSameMapBitForBit)
    {
        LayerStack s = random_stack(kTexels, 5, 3);
        const LayerStack before = s;
        const std::vector<float> totals = s.total_heights();
        const std::vector<float> map = random_values(kTexels, -0.5f, 3.0f, 99);
        coat(s, 9, 1.37f, map);
        erode(s, 1.37f, map);
        ASSERT_EQ(s.layers.size(), before.layers.size() + 1);
        for (size_t k = 0; k < before.layers.size(); ++k) {
            EXPECT_TRUE(same_bits(s.layers[k].thickness_um, before.layers[k].thickness_um))
                << "layer " << k;
            EXPECT_EQ(s.layers[k].material, before.layers[k].material);
        }
        EXPECT_TRUE(same_bits(s.layers.back().thickness_um, std::vector<float>(kTexels, 0.0f)));
        EXPECT_TRUE(same_bits(s.total_heights(), totals));
        for (size_t i = 0; i < kTexels; i += 97) {
            EXPECT_EQ(s.exposed_material(i), before.exposed_material(i));
        }
    }

    TEST(Erode, CutsThroughTheTopLayerAndExposesTheNext)
    {
        LayerStack s = new_stack(0, 4);
        coat(s, 1, 1.0f);  // lower: 1 µm everywhere
        coat(s, 2, 0.5f);  // upper: 0.5 µm everywhere
        erode(s, 0.75f, std::vector<float>{0.0f, 0.5f, 1.0f, 2.0f});
        // Removed 0, 0.375, 0.75, 1.5 µm (values exact in binary).
        EXPECT_EQ(s.layers[1].thickness_um, (std::vector<float>{0.5f, 0.125f, 0.0f, 0.0f}));
        EXPECT_EQ(s.layers[0].thickness_um, (std::vector<float>{1.0f, 1.0f, 0.75f, 0.0f}));
        EXPECT_EQ(s.exposed_material(0), 2);
        EXPECT_EQ(s.exposed_material(1), 2);
        EXPECT_EQ(s.exposed_material(2), 1) << "eroded through the top layer";
        EXPECT_EQ(s.exposed_material(3), 0) << "eroded through both layers";
    }

    TEST(Erode, NeverCutsIntoTheBase)
    {
        LayerStack s = random_stack(kTexels, 4, 5);
        const std::vector<float> map = random_values(kTexels, 0.0f, 1.0f, 6);
        erode(s, 6.0f, map);  // up to 6 µm: through every layer in places, not everywhere
        for (const Layer& layer : s.layers) {
            for (float t : layer.thickness_um) {
                ASSERT_GE(t, 0.0f);
            }
        }
        erode(s, 1e6f);
        for (size_t i = 0; i < kTexels; ++i) {
            ASSERT_EQ(s.total_height(i), 0.0f);
            ASSERT_EQ(s.exposed_layer(i), -1);
        }
        EXPECT_EQ(s.base_material, 0);
        EXPECT_EQ(s.layers.size(), 4u) << "emptied layers keep their place";
    }

    TEST(Fill, ReachesTheHeightEverywhereAndLeavesPeaks)
    {
        LayerStack s = random_stack(kTexels, 4, 7);
        const LayerStack before = s;
        const std::vector<float> totals = s.total_heights();
        const std::vector<float> map = random_values(kTexels, 0.5f, 1.5f, 8);
        const float height = 3.3f;
        fill(s, 6, height, map);
        ASSERT_EQ(s.layers.size(), before.layers.size() + 1);
        EXPECT_EQ(s.layers.back().material, 6);
        size_t peaks = 0;
        size_t valleys = 0;
        for (size_t i = 0; i < kTexels; ++i) {
            const float h = height * map[i];
            const float after = s.total_height(i);
            ASSERT_GE(after, h) << "texel " << i;
            if (totals[i] >= h) {
                ++peaks;
                ASSERT_EQ(s.layers.back().thickness_um[i], 0.0f);
                ASSERT_EQ(after, totals[i]);
            } else {
                ++valleys;
                // Levelled to h, rounded up by at most one ulp.
                ASSERT_LE(after, next_up(h)) << "texel " << i;
            }
            for (size_t k = 0; k < before.layers.size(); ++k) {
                ASSERT_EQ(s.layers[k].thickness_um[i], before.layers[k].thickness_um[i]);
            }
        }
        EXPECT_GT(peaks, kTexels / 20) << "the test needs peaks above the fill";
        EXPECT_GT(valleys, kTexels / 20) << "the test needs valleys below the fill";
    }

    TEST(Polish, CutsToTheHeightAndLeavesLowerTexels)
    {
        LayerStack s = random_stack(kTexels, 5, 9);
        const LayerStack before = s;
        const std::vector<float> totals = s.total_heights();
        const std::vector<float> map = random_values(kTexels, 0.5f, 1.5f, 10);
        const float height = 3.7f;
        polish(s, height, map);
        size_t cut = 0;
        for (size_t i = 0; i < kTexels; ++i) {
            const float h = height * map[i];
            const float after = s.total_height(i);
            ASSERT_LE(after, h) << "texel " << i;
            if (totals[i] <= h) {
                for (size_t k = 0; k < s.layers.size(); ++k) {
                    ASSERT_EQ(s.layers[k].thickness_um[i], before.layers[k].thickness_um[i]);
                }
            } else {
                ++cut;
                ASSERT_GE(next_up(after), h) << "cut to h, within one ulp, texel " << i;
                // Material goes from the top: every layer is at most what it was, and the
                // layers under the cut keep all of theirs.
                float z = 0.0f;
                for (size_t k = 0; k < s.layers.size(); ++k) {
                    const float was = before.layers[k].thickness_um[i];
                    ASSERT_LE(s.layers[k].thickness_um[i], was);
                    if (z + was <= h) {
                        ASSERT_EQ(s.layers[k].thickness_um[i], was);
                    }
                    z += was;
                }
            }
        }
        EXPECT_GT(cut, kTexels / 20);
        EXPECT_LT(cut, kTexels - kTexels / 20);
    }

    TEST(Polish, RemovesTheTopLayerFirst)
    {
        LayerStack s = new_stack(0, 1);
        coat(s, 1, 1.0f);
        coat(s, 2, 1.0f);
        coat(s, 3, 1.0f);
        polish(s, 1.5f);
        EXPECT_EQ(s.layers[0].thickness_um[0], 1.0f);
        EXPECT_EQ(s.layers[1].thickness_um[0], 0.5f);
        EXPECT_EQ(s.layers[2].thickness_um[0], 0.0f);
        EXPECT_EQ(s.exposed_material(0), 2);
    }

    // The cut plateau covers the asked fraction of the area: the texels at or above the
    // height hold at least that fraction, and those strictly above it less, so the
    // plateau's area exceeds the fraction by at most the share of one texel (the one at
    // the height; the random heights have no ties).
    TEST(PolishUntilExposed, CutsTheAskedFractionOfTheArea)
    {
        for (const float fraction : {0.1f, 0.3f, 0.5f, 0.85f}) {
            LayerStack s = random_stack(kTexels, 4, 11);
            const std::vector<float> totals = s.total_heights();
            const float h = polish_until_exposed(s, fraction);
            size_t at_or_above = 0;
            size_t plateau = 0;
            for (size_t i = 0; i < kTexels; ++i) {
                at_or_above += totals[i] >= h;
                const float after = s.total_height(i);
                ASSERT_LE(after, h);
                if (totals[i] >= h) {
                    plateau += next_up(after) >= h;
                } else {
                    ASSERT_EQ(after, totals[i]);
                }
            }
            EXPECT_EQ(plateau, at_or_above);
            const double area = double(at_or_above) / kTexels;
            EXPECT_GE(area, fraction) << "fraction " << fraction;
            EXPECT_LE(area, fraction + 1.0 / kTexels) << "fraction " << fraction;
        }
    }

    TEST(PolishUntilExposed, WeighsTexelsByArea)
    {
        LayerStack s = random_stack(kTexels, 4, 12);
        const std::vector<float> totals = s.total_heights();
        std::vector<float> weights = random_values(kTexels, 0.0f, 4.0f, 13);
        weights[5] = 0.0f;  // an uncovered texel does not count
        double total_weight = 0.0;
        double max_weight = 0.0;
        for (float w : weights) {
            total_weight += w;
            max_weight = std::max(max_weight, double(w));
        }
        const float fraction = 0.4f;
        const float h = polish_until_exposed(s, fraction, weights);
        double cut = 0.0;
        for (size_t i = 0; i < kTexels; ++i) {
            cut += totals[i] >= h ? weights[i] : 0.0;
        }
        EXPECT_GE(cut / total_weight, fraction - 1e-6);
        EXPECT_LE(cut / total_weight, fraction + max_weight / total_weight);
        // Uniform weights would give another height: the weights are used.
        EXPECT_NE(h, bearing_height(totals, fraction));
    }

    TEST(PolishUntilExposed, FractionZeroKeepsEverythingAndOneLevelsEverything)
    {
        LayerStack s = random_stack(kTexels, 3, 14);
        const std::vector<float> totals = s.total_heights();
        const float top = polish_until_exposed(s, 0.0f);
        EXPECT_EQ(top, *std::max_element(totals.begin(), totals.end()));
        EXPECT_TRUE(same_bits(s.total_heights(), totals));
        const float bottom = polish_until_exposed(s, 1.0f);
        EXPECT_EQ(bottom, *std::min_element(totals.begin(), totals.end()));
        for (size_t i = 0; i < kTexels; ++i) {
            ASSERT_LE(s.total_height(i), bottom);
        }
    }

    TEST(Offset, AddsTheGivenFillAsALayer)
    {
        LayerStack s = new_stack(0, 3);
        coat(s, 1, 1.0f);
        offset(s, 4, std::vector<float>{0.0f, 0.5f, 2.0f});
        ASSERT_EQ(s.layers.size(), 2u);
        EXPECT_EQ(s.layers[1].material, 4);
        EXPECT_EQ(s.total_heights(), (std::vector<float>{1.0f, 1.5f, 3.0f}));
        EXPECT_EQ(s.exposed_material(0), 1);
        EXPECT_EQ(s.exposed_material(1), 4);
    }

    TEST(Operators, ZeroAmountsDoWhatTheyDocument)
    {
        LayerStack s = random_stack(1000, 3, 15);
        const std::vector<float> totals = s.total_heights();
        coat(s, 5, 0.0f);
        ASSERT_EQ(s.layers.size(), 4u) << "a zero coat is an empty layer";
        EXPECT_TRUE(same_bits(s.layers.back().thickness_um, std::vector<float>(1000, 0.0f)));
        erode(s, 0.0f);
        fill(s, 6, 0.0f);
        ASSERT_EQ(s.layers.size(), 5u);
        EXPECT_TRUE(same_bits(s.total_heights(), totals)) << "erode 0 and fill 0 change nothing";
        polish(s, 0.0f);
        for (size_t i = 0; i < 1000; ++i) {
            ASSERT_EQ(s.total_height(i), 0.0f);
            ASSERT_EQ(s.exposed_material(i), 0) << "polish 0 exposes the base";
        }
    }

    TEST(Operators, RejectNegativeAndBadArgumentsNamingTheOperator)
    {
        LayerStack s = random_stack(10, 2, 16);
        const auto msg = [](auto f) { return message_of<std::invalid_argument>(f); };
        EXPECT_NE(msg([&] { coat(s, 1, -0.5f); }).find("coat: negative thickness"),
                  std::string::npos);
        EXPECT_NE(msg([&] { erode(s, -1.0f); }).find("erode: negative thickness"),
                  std::string::npos);
        EXPECT_NE(msg([&] { fill(s, 1, -2.0f); }).find("fill: negative height"), std::string::npos);
        EXPECT_NE(msg([&] { polish(s, -2.0f); }).find("polish: negative height"),
                  std::string::npos);
        EXPECT_NE(msg([&] { polish_until_exposed(s, 1.5f); }).find("polish until exposed"),
                  std::string::npos);
        EXPECT_NE(msg([&] { polish_until_exposed(s, -0.1f); }).find("polish until exposed"),
                  std::string::npos);
        EXPECT_NE(msg([&] { offset(s, 1, std::vector<float>(10, -1.0f)); }).find("offset:"),
                  std::string::npos);
        EXPECT_NE(
            msg([&] { coat(s, 1, std::nanf("")); }).find("coat: thickness is not a finite number"),
            std::string::npos);
        EXPECT_NE(msg([&] {
                      coat(s, 1, 1.0f, std::vector<float>(9, 1.0f));
                  }).find("coat: the map has 9 texels, the stack 10"),
                  std::string::npos);
        EXPECT_NE(msg([&] {
                      erode(s, 1.0f, std::vector<float>(10, std::nanf("")));
                  }).find("erode: map value nan at texel 0"),
                  std::string::npos);
        EXPECT_NE(msg([&] { coat(s, -1, 1.0f); }).find("coat: material id -1"), std::string::npos);
        EXPECT_NE(msg([&] {
                      polish_until_exposed(s, 0.5f, std::vector<float>(10, 0.0f));
                  }).find("no texel has a positive area weight"),
                  std::string::npos);
        EXPECT_EQ(s.layers.size(), 2u) << "a rejected operator leaves the stack as it was";
    }

    TEST(Operators, SameBitsForAnyThreadCount)
    {
        const auto run = [] {
            LayerStack s = random_stack(200000, 4, 17);
            const std::vector<float> map = random_values(200000, 0.0f, 1.0f, 18);
            erode(s, 1.1f, map);
            fill(s, 5, 2.5f, map);
            polish(s, 3.0f, map);
            polish_until_exposed(s, 0.3f);
            return s;
        };
        const LayerStack one = test::with_threads(1, run);
        const LayerStack two = test::with_threads(2, run);
        ASSERT_EQ(one.layers.size(), two.layers.size());
        for (size_t k = 0; k < one.layers.size(); ++k) {
            EXPECT_TRUE(same_bits(one.layers[k].thickness_um, two.layers[k].thickness_um));
        }
    }

}  // namespace
}  // namespace patina::texgen
