// normal_map_from_height: flat and tilted planes against their exact normals.
#include "texgen/flatten/normal_map.h"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

namespace patina::texgen {
namespace {

TEST(NormalMap, PlanarHeightGivesZZeroOne)
{
    const int w = 9, h = 7;
    const std::vector<float> height(w * h, 3.5f);
    const std::vector<float> n = normal_map_from_height(height, w, h, 100.0, 1.0);
    for (size_t i = 0; i < n.size(); i += 3) {
        EXPECT_EQ(decode_normal_component(n[i]), 0.0f);
        EXPECT_EQ(decode_normal_component(n[i + 1]), 0.0f);
        EXPECT_EQ(decode_normal_component(n[i + 2]), 1.0f);
    }
}

TEST(NormalMap, TiltedPlanesFollowTheOpenGLConvention)
{
    const int w = 8, h = 8;
    const double texel = 10.0, slope = 0.5;  // 5 µm of rise per 10 µm texel
    // Rising along +u (to the right): the normal leans to -X.
    std::vector<float> along_u(w * h), along_v(w * h);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            along_u[y * w + x] = static_cast<float>(slope * texel * x);
            // Rising along +v: up in the image, towards row 0.
            along_v[y * w + x] = static_cast<float>(slope * texel * (h - 1 - y));
        }
    const double len = std::sqrt(1.0 + slope * slope);
    const std::vector<float> nu = normal_map_from_height(along_u, w, h, texel, 1.0);
    const std::vector<float> nv = normal_map_from_height(along_v, w, h, texel, 1.0);
    for (int i = 0; i < w * h; ++i) {
        EXPECT_NEAR(decode_normal_component(nu[3 * i]), -slope / len, 1e-6);
        EXPECT_NEAR(decode_normal_component(nu[3 * i + 1]), 0.0, 1e-6);
        EXPECT_NEAR(decode_normal_component(nu[3 * i + 2]), 1.0 / len, 1e-6);
        // OpenGL (+Y up, "green up"): a surface rising towards +v leans to -Y.
        EXPECT_NEAR(decode_normal_component(nv[3 * i]), 0.0, 1e-6);
        EXPECT_NEAR(decode_normal_component(nv[3 * i + 1]), -slope / len, 1e-6);
    }
    // The scale multiplies the slope.
    const std::vector<float> n2 = normal_map_from_height(along_u, w, h, texel, 2.0);
    EXPECT_NEAR(decode_normal_component(n2[0]), -1.0 / std::sqrt(2.0), 1e-6);
}

TEST(NormalMap, BadSizesThrow)
{
    const std::vector<float> height(10, 0.0f);
    EXPECT_THROW(normal_map_from_height(height, 3, 3, 1.0, 1.0), std::invalid_argument);
    EXPECT_THROW(normal_map_from_height(height, 5, 2, 0.0, 1.0), std::invalid_argument);
}

}  // namespace
}  // namespace patina::texgen
