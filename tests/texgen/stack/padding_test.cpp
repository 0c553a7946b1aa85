#include "texgen/stack/padding.h"

#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <limits>

namespace patina::texgen {
namespace {

    /// Deterministic pseudo-random coverage (a small LCG; the values need not be good).
    std::vector<uint8_t> random_coverage(int w, int h, uint32_t seed, int percent)
    {
        std::vector<uint8_t> covered(static_cast<size_t>(w) * h);
        uint32_t s = seed;
        for (uint8_t& c : covered) {
            s = s * 1664525u + 1013904223u;
            c = static_cast<int>((s >> 16) % 100) < percent ? 1 : 0;
        }
        return covered;
    }

    /// Coverage of the texels inside [x0, x1) x [y0, y1).
    void cover(std::vector<uint8_t>& covered, int w, int x0, int y0, int x1, int y1)
    {
        for (int y = y0; y < y1; ++y)
            for (int x = x0; x < x1; ++x)
                covered[static_cast<size_t>(y) * w + x] = 1;
    }

    TEST(DistanceToCovered, MatchesBruteForceChebyshev)
    {
        const int w = 23, h = 17, limit = 9;
        for (uint32_t seed : {1u, 2u, 3u}) {
            const std::vector<uint8_t> covered = random_coverage(w, h, seed, 3);
            const std::vector<int> d = distance_to_covered(covered, w, h, limit);
            for (int y = 0; y < h; ++y)
                for (int x = 0; x < w; ++x) {
                    int best = limit;
                    for (int v = 0; v < h; ++v)
                        for (int u = 0; u < w; ++u)
                            if (covered[static_cast<size_t>(v) * w + u])
                                best = std::min(best, std::max(std::abs(u - x), std::abs(v - y)));
                    ASSERT_EQ(d[static_cast<size_t>(y) * w + x], best)
                        << "texel (" << x << ", " << y << ") seed " << seed;
                }
        }
    }

    TEST(DistanceToCovered, NothingCoveredGivesTheLimit)
    {
        const std::vector<int> d = distance_to_covered(std::vector<uint8_t>(12, 0), 4, 3, 5);
        EXPECT_TRUE(std::all_of(d.begin(), d.end(), [](int v) { return v == 5; }));
    }

    TEST(PadTexels, CoveredTexelsKeepTheirExactBits)
    {
        const int w = 32, h = 24, nc = 3;
        const std::vector<uint8_t> covered = random_coverage(w, h, 7, 40);
        std::vector<float> input(covered.size() * nc);
        // Values whose bits a careless composite would change: -0, a denormal, huge ones.
        const float special[] = {
            -0.0f, std::numeric_limits<float>::denorm_min(), 3.0e38f, -1.0e-30f, 0.1f, 1.0f / 3.0f};
        for (size_t i = 0; i < input.size(); ++i)
            input[i] = special[i % 6] * (i % 5 == 0 ? -1.0f : 1.0f);
        for (int margin : {-1, 0, 2, 5}) {
            std::vector<float> pixels = input;
            pad_texels(pixels, w, h, nc, covered, margin);
            for (size_t t = 0; t < covered.size(); ++t)
                if (covered[t]) {
                    ASSERT_EQ(std::memcmp(&pixels[t * nc], &input[t * nc], nc * sizeof(float)), 0)
                        << "covered texel " << t << " changed with margin " << margin;
                }
        }
    }

    TEST(PadTexels, FillWithinTheMarginComesFromTheNearbyRegionAndStopsBeyondIt)
    {
        // Two islands far apart with different two-channel values; margin 4.
        const int w = 64, h = 32, nc = 2, margin = 4;
        std::vector<uint8_t> covered(static_cast<size_t>(w) * h, 0);
        cover(covered, w, 4, 8, 16, 24);                         // left island: (2, -3)
        cover(covered, w, 44, 8, 56, 24);                        // right island: (7, 0.5)
        std::vector<float> pixels(covered.size() * nc, 123.0f);  // garbage in the holes
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                const size_t t = static_cast<size_t>(y) * w + x;
                if (covered[t]) {
                    pixels[t * nc] = x < 32 ? 2.0f : 7.0f;
                    pixels[t * nc + 1] = x < 32 ? -3.0f : 0.5f;
                }
            }
        pad_texels(pixels, w, h, nc, covered, margin);
        auto value = [&](int x, int y, int c) {
            return pixels[(static_cast<size_t>(y) * w + x) * nc + c];
        };

        // One texel right of the left island and at the margin's corner: values pulled from
        // the left island, nearer its values than the right island's.
        for (auto [x, y] :
             {std::pair{16, 15}, std::pair{16 + margin - 1, 24 + margin - 1}, std::pair{3, 7}}) {
            EXPECT_NEAR(value(x, y, 0), 2.0f, 1.0f) << x << ", " << y;
            EXPECT_NEAR(value(x, y, 1), -3.0f, 1.0f) << x << ", " << y;
        }
        // Next to the right island, the right island's values.
        EXPECT_NEAR(value(43, 15, 0), 7.0f, 1.0f);
        EXPECT_NEAR(value(43, 15, 1), 0.5f, 1.0f);
        // At Chebyshev distance == margin the fill is kept, one texel farther it is 0.
        EXPECT_NE(value(16 + margin - 1, 15, 0), 0.0f);
        EXPECT_NE(value(15 + margin, 24 + margin - 1, 0), 0.0f);
        for (auto [x, y] : {std::pair{16 + margin, 15}, std::pair{15 + margin + 1, 24 + margin},
                            std::pair{30, 2}, std::pair{56 + margin, 24}}) {
            EXPECT_EQ(value(x, y, 0), 0.0f) << x << ", " << y;
            EXPECT_EQ(value(x, y, 1), 0.0f) << x << ", " << y;
        }
    }

    TEST(PadTexels, ConstantRegionFillsWithItsValueAndMarginMinusOneFillsAll)
    {
        const int w = 40, h = 40;
        std::vector<uint8_t> covered(static_cast<size_t>(w) * h, 0);
        cover(covered, w, 10, 12, 19, 17);
        std::vector<float> pixels(covered.size(), 0.0f);
        for (size_t t = 0; t < covered.size(); ++t)
            if (covered[t])
                pixels[t] = 0.75f;
        pad_texels(pixels, w, h, 1, covered, -1);
        // Push-pull of a constant only averages copies of it.
        for (float v : pixels)
            ASSERT_NEAR(v, 0.75f, 1e-6f);
    }

    TEST(PadTexels, MarginZeroClearsTheHolesOnly)
    {
        const int w = 8, h = 8;
        std::vector<uint8_t> covered(64, 0);
        cover(covered, w, 2, 2, 5, 6);
        std::vector<float> pixels(64, 9.0f);
        pad_texels(pixels, w, h, 1, covered, 0);
        for (size_t t = 0; t < 64; ++t)
            EXPECT_EQ(pixels[t], covered[t] ? 9.0f : 0.0f) << t;
    }

    TEST(PadTexels, BadArgumentsAreErrors)
    {
        std::vector<float> pixels(16, 0.0f);
        std::vector<uint8_t> covered(16, 1);
        EXPECT_NE(patina::test::message_of([&] {
                      pad_texels(pixels, 4, 4, 1, covered, -2);
                  }).find("padding margin -2"),
                  std::string::npos);
        EXPECT_NE(patina::test::message_of([&] {
                      pad_texels(pixels, 4, 4, 2, covered, 1);
                  }).find("16 values"),
                  std::string::npos);
    }

}  // namespace
}  // namespace patina::texgen
