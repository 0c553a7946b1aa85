// PCG32, hashing, piecewise-constant distributions and MIS weights (core/sampling.h).
#include "core/sampling.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>
#include <vector>

namespace patina {
namespace {

    TEST(SamplingTest, Pcg32MatchesReferenceOutput)
    {
        // pcg-c-basic's pcg32-demo: pcg32_srandom_r(&rng, 42u, 54u) then pcg32_random_r gives
        // 0xa15c02b7 0x7b47f409 0xba1d3330 0x83d2f293 0xbfa4784b 0xcbed606e.
        Pcg32 rng(54u, 42u);
        const uint32_t expected[6] = {0xa15c02b7u, 0x7b47f409u, 0xba1d3330u,
                                      0x83d2f293u, 0xbfa4784bu, 0xcbed606eu};
        for (uint32_t e : expected)
            EXPECT_EQ(rng.uniform_u32(), e);
    }

    TEST(SamplingTest, Pcg32IsReproducibleAndStreamsDiffer)
    {
        Pcg32 a(7, 3), b(7, 3), c(8, 3);
        int same_as_c = 0;
        for (int i = 0; i < 1000; ++i) {
            const uint32_t va = a.uniform_u32();
            EXPECT_EQ(va, b.uniform_u32());
            same_as_c += va == c.uniform_u32();
        }
        EXPECT_LT(same_as_c, 3);
    }

    TEST(SamplingTest, Pcg32AdvanceSkipsExactly)
    {
        Pcg32 a(11, 5), b(11, 5);
        for (int i = 0; i < 12345; ++i)
            a.uniform_u32();
        b.advance(12345);
        EXPECT_TRUE(a == b);
        const uint32_t v = a.uniform_u32();
        EXPECT_EQ(v, b.uniform_u32());
        b.advance(-1); // back one step: the value just drawn comes again
        EXPECT_EQ(b.uniform_u32(), v);
    }

    TEST(SamplingTest, UniformFloatRangeAndMean)
    {
        Pcg32 rng(1);
        double sum = 0.0, sum2 = 0.0;
        const int n = 200000;
        for (int i = 0; i < n; ++i) {
            const float u = rng.uniform_float();
            ASSERT_GE(u, 0.0f);
            ASSERT_LT(u, 1.0f);
            sum += u;
            sum2 += double(u) * u;
        }
        // Mean 1/2 and variance 1/12 of U[0,1), within 5 standard errors.
        EXPECT_NEAR(sum / n, 0.5, 5.0 * std::sqrt(1.0 / 12.0 / n));
        EXPECT_NEAR(sum2 / n - (sum / n) * (sum / n), 1.0 / 12.0, 2e-3);
        // Bounded integers cover the range evenly.
        std::vector<int> counts(7, 0);
        for (int i = 0; i < 70000; ++i)
            ++counts[rng.uniform_u32(7)];
        for (int c : counts)
            EXPECT_NEAR(c, 10000, 500);
    }

    TEST(SamplingTest, PixelSeedsAreIndependentOfOrder)
    {
        // Same (seed, x, y, sample) gives the same numbers whatever was drawn before.
        Pcg32 a = pixel_sample_rng(42, 10, 20, 3);
        for (int i = 0; i < 100; ++i)
            pixel_sample_rng(42, i, i, i).uniform_u32();
        Pcg32 b = pixel_sample_rng(42, 10, 20, 3);
        EXPECT_EQ(a.uniform_u32(), b.uniform_u32());
        // Neighbouring pixels, samples and seeds give distinct streams.
        std::set<uint32_t> firsts;
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 32; ++x)
                for (int s = 0; s < 4; ++s)
                    firsts.insert(pixel_sample_rng(1, x, y, s).uniform_u32());
        EXPECT_GT(firsts.size(), 4096u - 4u); // birthday collisions of 32-bit values are rare
        EXPECT_NE(hash_values(1, 2), hash_values(2, 1));
        EXPECT_NE(mix_bits(0), mix_bits(1));
    }

    TEST(SamplingTest, PixelStreamAndSampleRngArePixelSampleRngInTwoSteps)
    {
        // The renderer hashes a pixel once and starts each sample from it: same numbers.
        for (uint64_t seed : {0ull, 1ull, 0x5eedull})
            for (int x : {0, 7, 511})
                for (int y : {0, 3, 300})
                    for (uint64_t s : {0ull, 1ull, 15ull, 1000ull}) {
                        Pcg32 a = pixel_sample_rng(seed, x, y, s);
                        Pcg32 b = sample_rng(pixel_stream(seed, x, y), seed, s);
                        EXPECT_TRUE(a == b);
                        for (int i = 0; i < 4; ++i)
                            EXPECT_EQ(a.uniform_u32(), b.uniform_u32());
                    }
    }

    TEST(SamplingTest, Distribution1DSampleAndPdfAgree)
    {
        const std::vector<float> f = {1.0f, 0.0f, 3.0f, 4.0f, 2.0f};
        const Distribution1D d(f, 2.0f, 7.0f); // pieces of width 1
        EXPECT_DOUBLE_EQ(d.integral(), 10.0);
        // Piece i has probability f_i / 10; within it the density is f_i / 10 per unit length.
        for (int i = 0; i < 5; ++i)
            EXPECT_FLOAT_EQ(d.discrete_pmf(i), f[i] / 10.0f);
        EXPECT_FLOAT_EQ(d.pdf(4.5f), 0.3f);
        EXPECT_EQ(d.pdf(1.0f), 0.0f);
        // The returned pdf equals pdf(x), zero-weight pieces are never chosen, and the inverse
        // CDF is monotone.
        float last = -1.0f;
        std::vector<int> counts(5, 0);
        const int n = 100000;
        for (int k = 0; k < n; ++k) {
            const float u = (k + 0.5f) / n;
            float pdf = 0.0f;
            int offset = -1;
            const float x = d.sample_continuous(u, &pdf, &offset);
            ASSERT_GE(x, 2.0f);
            ASSERT_LT(x, 7.0f);
            ASSERT_GE(x, last);
            last = x;
            EXPECT_EQ(pdf, d.pdf(x));
            EXPECT_NE(offset, 1);
            float pmf = 0.0f, ur = -1.0f;
            const int i = d.sample_discrete(u, &pmf, &ur);
            ASSERT_GE(ur, 0.0f);
            ASSERT_LT(ur, 1.0f);
            EXPECT_FLOAT_EQ(pmf, d.discrete_pmf(i));
            ++counts[i];
        }
        for (int i = 0; i < 5; ++i)
            EXPECT_NEAR(counts[i] / double(n), f[i] / 10.0, 1e-4);
    }

    TEST(SamplingTest, Distribution1DAllZeroIsUniform)
    {
        const std::vector<float> f(4, 0.0f);
        const Distribution1D d(f);
        EXPECT_EQ(d.integral(), 0.0);
        EXPECT_FLOAT_EQ(d.pdf(0.3f), 1.0f);
        float pdf = 0.0f;
        EXPECT_NEAR(d.sample_continuous(0.3f, &pdf), 0.3f, 1e-6);
        EXPECT_FLOAT_EQ(pdf, 1.0f);
    }

    TEST(SamplingTest, Distribution2DSampleAndPdfAgree)
    {
        // 4 x 3 image with a zero row and a bright texel.
        const int nu = 4, nv = 3;
        const std::vector<float> f = {1, 1, 1, 1, //
                                      0, 0, 0, 0, //
                                      1, 2, 8, 1};
        const Distribution2D d(f, nu, nv);
        // Integral over [0,1]^2: sum / (nu nv) = 16 / 12.
        EXPECT_NEAR(d.integral(), 16.0 / 12.0, 1e-6);
        // Density of texel (2, 2) = f / integral = 8 / (16/12) = 6.
        EXPECT_NEAR(d.pdf(0.6f, 0.9f), 6.0f, 1e-5);
        EXPECT_EQ(d.pdf(0.5f, 0.5f), 0.0f);
        // Chi-square over the texels: each is hit with probability f / 16.
        std::vector<double> counts(nu * nv, 0.0);
        Pcg32 rng(3);
        const int n = 160000;
        for (int k = 0; k < n; ++k) {
            const auto s = d.sample(rng.uniform_float(), rng.uniform_float());
            ASSERT_NEAR(s.pdf, d.pdf(s.u, s.v), 1e-5 * s.pdf);
            ASSERT_GT(s.pdf, 0.0f);
            counts[static_cast<int>(s.v * nv) * nu + static_cast<int>(s.u * nu)] += 1.0;
        }
        double chi2 = 0.0;
        int dof = -1;
        for (int i = 0; i < nu * nv; ++i) {
            const double expected = n * f[i] / 16.0;
            if (expected == 0.0) {
                EXPECT_EQ(counts[i], 0.0);
                continue;
            }
            chi2 += (counts[i] - expected) * (counts[i] - expected) / expected;
            ++dof;
        }
        EXPECT_LT(chi2, 24.3); // the 99.9% quantile of chi-square with 7 degrees of freedom
        EXPECT_EQ(dof, 7);
    }

    TEST(SamplingTest, MisHeuristics)
    {
        // Veach 1997, ch. 9: w_f + w_g = 1; power heuristic (1·2)² / ((1·2)² + (1·1)²) = 0.8.
        EXPECT_FLOAT_EQ(power_heuristic(1, 2.0f, 1, 1.0f), 0.8f);
        EXPECT_FLOAT_EQ(power_heuristic(1, 2.0f, 1, 1.0f) + power_heuristic(1, 1.0f, 1, 2.0f),
                        1.0f);
        EXPECT_FLOAT_EQ(balance_heuristic(1, 3.0f, 1, 1.0f), 0.75f);
        EXPECT_EQ(power_heuristic(1, INFINITY, 1, 1.0f), 1.0f);
        EXPECT_EQ(power_heuristic(1, 0.0f, 1, 0.0f), 0.0f);
    }

} // namespace
} // namespace patina
