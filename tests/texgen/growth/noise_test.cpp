// Solid noise (Perlin 2002), the noise/turbulence patterns and steady thickening.
#include "texgen/growth/noise_pattern.h"
#include "texgen/growth/solid_noise.h"
#include "texgen/growth/steady_thickening.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace patina::texgen {
namespace {

    TEST(SolidNoise, RangeMeanAndDeterminism)
    {
        const SolidNoise a(1), b(1), c(2);
        double sum = 0.0, lo = 1.0, hi = -1.0;
        int differ = 0;
        const int n = 20000;
        for (int i = 0; i < n; ++i) {
            const double x = 0.37 * i, y = 0.11 * i + 3.0, z = 0.05 * i;
            const double v = a.noise(x, y, z);
            ASSERT_EQ(v, b.noise(x, y, z));
            differ += v != c.noise(x, y, z);
            sum += v;
            lo = std::min(lo, v);
            hi = std::max(hi, v);
        }
        std::printf("[ measured ] noise over %d points: mean %.4f, range [%.3f, %.3f]\n", n,
                    sum / n, lo, hi);
        // Improved noise is a sum of gradient ramps: zero mean and |n| <= about 1.
        EXPECT_NEAR(sum / n, 0.0, 0.03);
        EXPECT_GE(lo, -1.1);
        EXPECT_LE(hi, 1.1);
        EXPECT_LT(lo, -0.4); // and it does use its range
        EXPECT_GT(hi, 0.4);
        EXPECT_GT(differ, n * 9 / 10);
    }

    TEST(SolidNoise, ContinuousAndSmooth)
    {
        // Perlin 2002: the quintic fade makes noise C2, so its slope is bounded: a step of
        // 1e-3 changes it by at most a few 1e-3 everywhere, including across lattice planes.
        const SolidNoise noise(5);
        double worst = 0.0;
        for (int i = 0; i < 5000; ++i) {
            const double x = 0.0137 * i, y = 0.7 + 0.0031 * i, z = 0.2;
            worst = std::max(worst, std::abs(noise.noise(x + 1e-3, y, z) - noise.noise(x, y, z)));
        }
        std::printf("[ measured ] largest noise change per 1e-3 step: %.5f\n", worst);
        EXPECT_LT(worst, 4e-3);
        EXPECT_GT(worst, 1e-4);
    }

    TEST(SolidNoise, TurbulenceIsNormalisedAndRougher)
    {
        const SolidNoise noise(9);
        double lo = 1.0, hi = 0.0, rough_single = 0.0, rough_turb = 0.0;
        for (int i = 0; i < 4000; ++i) {
            const double x = 0.01 * i;
            const double t = noise.turbulence(x, 0.3, 0.6, 6);
            lo = std::min(lo, t);
            hi = std::max(hi, t);
            rough_single += std::abs(std::abs(noise.noise(x + 0.01, 0.3, 0.6)) -
                                     std::abs(noise.noise(x, 0.3, 0.6)));
            rough_turb += std::abs(noise.turbulence(x + 0.01, 0.3, 0.6, 6) - t);
        }
        EXPECT_GE(lo, 0.0);
        EXPECT_LT(hi, 1.0);
        // Octaves add detail: more total variation than one octave, weighted the same.
        EXPECT_GT(rough_turb, 1.3 * rough_single * (1.0 / (2.0 - 1.0 / 32.0)));
    }

    TEST(NoisePattern, ContinuousOverTheLatticeAndInRange)
    {
        const Lattice grid = make_grid_lattice(128, 128, 0.01f);
        GrowthParameters p = resolve_growth_parameters(grid, {});
        EXPECT_NEAR(p.feature_size, 0.32, 1e-6); // 32 cells by default
        for (bool turbulence : {false, true}) {
            const auto map = noise_pattern(grid, p, 3, turbulence);
            const auto [lo, hi] = std::minmax_element(map.begin(), map.end());
            EXPECT_GE(*lo, 0.0f);
            EXPECT_LE(*hi, 1.0f);
            EXPECT_GT(*hi - *lo, 0.2f);
            float step = 0.0f;
            for (int y = 0; y < 128; ++y)
                for (int x = 0; x + 1 < 128; ++x)
                    step = std::max(step, std::abs(map[y * 128 + x + 1] - map[y * 128 + x]));
            std::printf("[ measured ] %s: largest neighbour difference %.4f\n",
                        turbulence ? "turbulence" : "noise", step);
            // One cell is 1/32 of a feature: the pattern changes by a small step per cell
            // (turbulence's top octave is 16 times finer, so it may step further).
            EXPECT_LT(step, turbulence ? 0.25f : 0.1f);
            EXPECT_EQ(map, noise_pattern(grid, p, 3, turbulence));
        }
    }

    TEST(SteadyThickening, RelativelyUniformAndSmooth)
    {
        // D&H 1996 §3.3: "a very simple, relatively uniform pattern".
        const Lattice grid = make_grid_lattice(128, 128, 0.01f);
        const GrowthParameters p = resolve_growth_parameters(grid, {});
        const auto map = steady_thickening_pattern(grid, p, 6);
        double sum = 0.0, sq = 0.0;
        float step = 0.0f;
        for (size_t i = 0; i < map.size(); ++i) {
            sum += map[i];
            sq += static_cast<double>(map[i]) * map[i];
            if (i % 128 != 127)
                step = std::max(step, std::abs(map[i + 1] - map[i]));
        }
        const double m = sum / map.size();
        const double cv = std::sqrt(sq / map.size() - m * m) / m;
        std::printf("[ measured ] ST mean %.3f, coefficient of variation %.3f, step %.4f\n", m,
                    cv, step);
        EXPECT_NEAR(m, 1.0, 0.1);
        EXPECT_LT(cv, 0.25);
        EXPECT_GT(cv, 0.02);
        EXPECT_GT(*std::min_element(map.begin(), map.end()), 0.5f);
        EXPECT_LT(step, 0.1f);
    }

} // namespace
} // namespace patina::texgen
