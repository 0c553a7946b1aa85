// grow(): the thickness maps a script's texture(MODEL RATE STEP TOTAL) reads.
#include "texgen/growth/growth_model.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>

namespace patina::texgen {
namespace {

    using patina::test::message_of;

    constexpr GrowthModelKind kAllModels[] = {
        GrowthModelKind::SteadyThickening,        GrowthModelKind::RandomDeposition,
        GrowthModelKind::RandomDepositionRelaxed, GrowthModelKind::BallisticDeposition,
        GrowthModelKind::DirectedPercolationDepinning, GrowthModelKind::Noise,
        GrowthModelKind::Turbulence};

    GrowthSpec spec_of(GrowthModelKind model, GrowthRate rate = GrowthRate::Linear)
    {
        GrowthSpec spec;
        spec.model = model;
        spec.rate = rate;
        spec.step = 1;
        spec.total = 1;
        return spec;
    }

    std::vector<std::vector<float>> grow_with_threads(int threads, const Lattice& lattice,
                                                      const GrowthSpec& spec, uint64_t seed,
                                                      std::span<const double> fractions)
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);
        return grow(lattice, spec, seed, fractions);
    }

    TEST(Grow, NormalisedMonotoneSnapshots)
    {
        const Lattice grid = make_grid_lattice(96, 80, 0.01f);
        const std::vector<double> fractions = {0.0, 0.05, 0.25, 0.5, 1.0};
        for (GrowthModelKind model : kAllModels) {
            const auto maps = grow(grid, spec_of(model, GrowthRate::Parabolic), 17, fractions);
            const std::string name(growth_model_name(model));
            ASSERT_EQ(maps.size(), fractions.size()) << name;
            for (const auto& map : maps) {
                ASSERT_EQ(map.size(), grid.size());
                EXPECT_GE(*std::min_element(map.begin(), map.end()), 0.0f) << name;
                EXPECT_LE(*std::max_element(map.begin(), map.end()), 1.0f) << name;
            }
            // Normalised by the maximum at the end of the run.
            EXPECT_EQ(*std::max_element(maps.back().begin(), maps.back().end()), 1.0f) << name;
            // Nothing has grown at the start.
            EXPECT_EQ(*std::max_element(maps[0].begin(), maps[0].end()), 0.0f) << name;
            for (size_t k = 1; k < maps.size(); ++k)
                for (size_t i = 0; i < grid.size(); ++i)
                    ASSERT_GE(maps[k][i], maps[k - 1][i]) << name << " node " << i;
        }
    }

    TEST(Grow, RateWarpsTheRun)
    {
        // Parabolic growth has done half its growth a quarter of the way through (x^2 = kt):
        // the RD snapshot at 0.25 of a parabolic run is the linear run's at 0.5.
        const Lattice grid = make_grid_lattice(64, 64, 0.01f);
        const std::vector<double> quarter = {0.25}, half = {0.5};
        EXPECT_EQ(grow(grid, spec_of(GrowthModelKind::RandomDeposition, GrowthRate::Parabolic), 4,
                       quarter),
                  grow(grid, spec_of(GrowthModelKind::RandomDeposition), 4, half));
        // And the mean RD thickness follows the rate law: mean height t * layers.
        const auto cubic = grow(grid, spec_of(GrowthModelKind::RandomDeposition, GrowthRate::Cubic),
                                4, std::vector<double>{0.125, 1.0});
        double a = 0, b = 0;
        for (size_t i = 0; i < grid.size(); ++i) {
            a += cubic[0][i];
            b += cubic[1][i];
        }
        EXPECT_NEAR(a / b, 0.5, 1e-6); // cbrt(1/8); RD's mean is exact (B&S 1995 ch. 4)
    }

    TEST(Grow, SameBitsForOneAndTwoThreads)
    {
        // 75000 nodes: the deposition models run in three blocks.
        const Lattice grid = make_grid_lattice(300, 250, 0.01f);
        const std::vector<double> fractions = {0.3, 0.9};
        for (GrowthModelKind model : kAllModels) {
            const GrowthSpec spec = spec_of(model, GrowthRate::Logarithmic);
            EXPECT_EQ(grow_with_threads(1, grid, spec, 99, fractions),
                      grow_with_threads(2, grid, spec, 99, fractions))
                << growth_model_name(model);
        }
    }

    TEST(Grow, SeedsGiveDifferentPatterns)
    {
        const Lattice grid = make_grid_lattice(64, 64, 0.01f);
        const std::vector<double> end = {1.0};
        for (GrowthModelKind model : kAllModels)
            EXPECT_NE(grow(grid, spec_of(model), 1, end), grow(grid, spec_of(model), 2, end))
                << growth_model_name(model);
    }

    TEST(Grow, BadParametersNameThemselves)
    {
        const Lattice grid = make_grid_lattice(16, 16, 0.01f);
        const std::vector<double> half = {0.5};
        const auto message = [&](auto edit) {
            GrowthSpec spec = spec_of(GrowthModelKind::DirectedPercolationDepinning);
            edit(spec.parameters);
            return message_of([&] { grow(grid, spec, 1, half); });
        };
        const auto has = [](const std::string& text, const std::string& part) {
            return text.find(part) != std::string::npos;
        };
        EXPECT_TRUE(has(message([](GrowthParameters& p) { p.layers = -2; }), "'layers'"));
        EXPECT_TRUE(has(message([](GrowthParameters& p) { p.blocked_fraction = 1.5; }),
                        "'blocked_fraction'"));
        EXPECT_TRUE(has(message([](GrowthParameters& p) { p.patch_size = -0.1; }),
                        "'patch_size'"));
        EXPECT_TRUE(has(message([](GrowthParameters& p) { p.levels = 0; }), "'levels'"));
        EXPECT_TRUE(has(message([](GrowthParameters& p) { p.octaves = 40; }), "'octaves'"));
        EXPECT_TRUE(has(message([](GrowthParameters& p) { p.feature_size = std::nan(""); }),
                        "'feature_size'"));
        EXPECT_TRUE(has(message([](GrowthParameters& p) { p.advance_unblocked = 0; }),
                        "'advance_unblocked'"));
        EXPECT_TRUE(has(message([](GrowthParameters& p) { p.spread_distance = 1e6; }),
                        "'spread_distance'"));
        const std::string fraction = message_of([&] {
            grow(grid, spec_of(GrowthModelKind::BallisticDeposition), 1,
                 std::vector<double>{1.25});
        });
        EXPECT_TRUE(has(fraction, "1.25")) << fraction;
        EXPECT_TRUE(has(fraction, "BD")) << fraction;
        GrowthSpec backwards = spec_of(GrowthModelKind::Noise);
        backwards.step = 3;
        backwards.total = 2;
        EXPECT_TRUE(has(message_of([&] { grow(grid, backwards, 1, half); }), "step"));
        Lattice empty;
        EXPECT_THROW(grow(empty, spec_of(GrowthModelKind::Noise), 1, half),
                     std::invalid_argument);
    }

    // Not run by default (it takes a few seconds): the speed of each model on the lead's
    // benchmark lattice, 2048 x 2048. Run with --gtest_also_run_disabled_tests.
    TEST(Grow, DISABLED_TimingOn2048Grid)
    {
        const Lattice grid = make_grid_lattice(2048, 2048, 1.0f / 2048);
        const std::vector<double> fractions = {0.25, 1.0};
        for (GrowthModelKind model : kAllModels) {
            const auto start = std::chrono::steady_clock::now();
            const auto maps = grow(grid, spec_of(model), 5, fractions);
            const double seconds =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
            std::printf("[ measured ] %-10s on 2048^2: %.3f s\n",
                        std::string(growth_model_name(model)).c_str(), seconds);
            EXPECT_EQ(maps.size(), 2u);
        }
    }

} // namespace
} // namespace patina::texgen
