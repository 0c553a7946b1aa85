#include "texgen/patina/layer_stack.h"
#include "texgen/patina/operators.h"

#include "ops_test_util.h"

#include <gtest/gtest.h>

namespace patina::texgen {
namespace {

    LayerStack two_layers()
    {
        // Texel 0: both layers; texel 1: only the lower; texel 2: only the upper; texel 3:
        // neither (base shows).
        LayerStack s = new_stack(7, 4);
        s.layers.push_back({3, {1.0f, 2.0f, 0.0f, 0.0f}});
        s.layers.push_back({5, {0.5f, 0.0f, 0.25f, 0.0f}});
        return s;
    }

    TEST(LayerStack, NewStackIsTheBaseAlone)
    {
        const LayerStack s = new_stack(4, 3);
        EXPECT_EQ(s.base_material, 4);
        EXPECT_EQ(s.texel_count, 3u);
        EXPECT_TRUE(s.layers.empty());
        for (size_t i = 0; i < 3; ++i) {
            EXPECT_EQ(s.total_height(i), 0.0f);
            EXPECT_EQ(s.exposed_layer(i), -1);
            EXPECT_EQ(s.exposed_material(i), 4);
        }
    }

    TEST(LayerStack, TotalHeightAndExposedLayer)
    {
        const LayerStack s = two_layers();
        const std::vector<float> expected = {1.5f, 2.0f, 0.25f, 0.0f};
        EXPECT_EQ(s.total_heights(), expected);
        for (size_t i = 0; i < 4; ++i) {
            EXPECT_EQ(s.total_height(i), expected[i]);
        }
        EXPECT_EQ(s.exposed_layer(0), 1);
        EXPECT_EQ(s.exposed_layer(1), 0);
        EXPECT_EQ(s.exposed_layer(2), 1);
        EXPECT_EQ(s.exposed_layer(3), -1);
        EXPECT_EQ(s.exposed_material(0), 5);
        EXPECT_EQ(s.exposed_material(1), 3);
        EXPECT_EQ(s.exposed_material(3), 7);
    }

    TEST(LayerStack, TotalHeightsHasTheBitsOfTotalHeight)
    {
        const LayerStack s = test::random_stack(50000, 6, 11);
        const std::vector<float> totals = s.total_heights();
        for (size_t i = 0; i < s.texel_count; ++i) {
            ASSERT_EQ(totals[i], s.total_height(i)) << "texel " << i;
        }
    }

    TEST(LayerStack, DropEmptyLayersKeepsTheOthersInOrder)
    {
        LayerStack s = two_layers();
        s.layers.insert(s.layers.begin() + 1, Layer{9, {0.0f, 0.0f, 0.0f, 0.0f}});
        s.layers.push_back({8, {0.0f, 0.0f, 0.0f, 0.0f}});
        EXPECT_EQ(drop_empty_layers(s), 2u);
        ASSERT_EQ(s.layers.size(), 2u);
        EXPECT_EQ(s.layers[0].material, 3);
        EXPECT_EQ(s.layers[1].material, 5);
        EXPECT_EQ(drop_empty_layers(s), 0u);
    }

}  // namespace
}  // namespace patina::texgen
