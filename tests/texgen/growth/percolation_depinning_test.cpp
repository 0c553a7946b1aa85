// Directed percolation depinning as Dorsey & Hanrahan 1996 §3.3 and figure 6 describe it.
#include "texgen/growth/percolation_depinning.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <set>

namespace patina::texgen {
namespace {

    double coverage(const std::vector<uint8_t>& levels)
    {
        const auto occupied = std::count_if(levels.begin(), levels.end(),
                                            [](uint8_t l) { return l > 0; });
        return static_cast<double>(occupied) / static_cast<double>(levels.size());
    }

    GrowthParameters resolved(const Lattice& lattice, GrowthParameters p = {})
    {
        return resolve_growth_parameters(lattice, p);
    }

    TEST(PercolationDepinning, SeedPatchIsASquareOnAGrid)
    {
        // D&H 1996 §3.3: "the seed patches are 10 x 10 squares".
        const Lattice grid = make_grid_lattice(40, 40, 0.01f);
        std::vector<int32_t> nodes;
        dpd_patch_nodes(grid, 20 * 40 + 20, 10, nodes);
        const std::set<int32_t> unique(nodes.begin(), nodes.end());
        ASSERT_EQ(unique.size(), 100u);
        int min_x = 99, max_x = -1, min_y = 99, max_y = -1;
        for (int32_t v : unique) {
            min_x = std::min(min_x, v % 40);
            max_x = std::max(max_x, v % 40);
            min_y = std::min(min_y, v / 40);
            max_y = std::max(max_y, v / 40);
        }
        EXPECT_EQ(max_x - min_x, 9);
        EXPECT_EQ(max_y - min_y, 9);
        // At a corner the lattice ends: the patch is clipped, not wrapped.
        nodes.clear();
        dpd_patch_nodes(grid, 0, 10, nodes);
        EXPECT_EQ(std::set<int32_t>(nodes.begin(), nodes.end()).size(), 36u); // 6 x 6
    }

    TEST(PercolationDepinning, BlockedShareMatchesTheParameter)
    {
        const Lattice grid = make_grid_lattice(200, 200, 0.01f);
        for (double share : {0.0, 0.3, 0.5, 1.0}) {
            const auto blocked = dpd_blocked_nodes(grid, share, 4);
            const double measured =
                std::count(blocked.begin(), blocked.end(), 1) / static_cast<double>(grid.size());
            EXPECT_NEAR(measured, share, 0.01) << share; // 40000 cells: sd 0.0025
        }
    }

    TEST(PercolationDepinning, CoverageAndLevelsGrowMonotonically)
    {
        const Lattice grid = make_grid_lattice(160, 160, 0.01f);
        const GrowthParameters p = resolved(grid);
        // The seeds appear in the first sweep, then the run goes on in tenths.
        std::vector<double> times = {1.0 / dpd_sweeps(grid, p)};
        for (int k = 1; k <= 10; ++k)
            times.push_back(k / 10.0);
        EXPECT_EQ(percolation_depinning_levels(grid, p, 21, std::vector<double>{0.0})[0],
                  std::vector<uint8_t>(grid.size(), 0)); // bare at the start
        const auto levels = percolation_depinning_levels(grid, p, 21, times);
        std::printf("[ measured ] DPD coverage over the run:");
        for (size_t k = 0; k < times.size(); ++k)
            std::printf(" %.3f", coverage(levels[k]));
        std::printf("\n");
        EXPECT_GT(coverage(levels[0]), 0.0); // the initial seed patches
        EXPECT_GT(coverage(levels[5]), 2.0 * coverage(levels[0]));
        EXPECT_GT(coverage(levels[10]), 0.5);
        for (size_t k = 1; k < times.size(); ++k) {
            EXPECT_GE(coverage(levels[k]), coverage(levels[k - 1]));
            for (size_t i = 0; i < grid.size(); ++i)
                ASSERT_GE(levels[k][i], levels[k - 1][i]) << "node " << i << " time " << k;
        }
        const uint8_t top = *std::max_element(levels[10].begin(), levels[10].end());
        EXPECT_EQ(top, p.levels);
    }

    TEST(PercolationDepinning, PatchesAdvanceMuchFasterOverUnblockedCells)
    {
        // D&H 1996 §3.3: "patches are much more likely to advance onto an unblocked cell
        // than a blocked cell".
        const Lattice grid = make_grid_lattice(256, 256, 0.01f);
        GrowthParameters p = resolved(grid);
        p.new_seed_ratio = 0.0;
        // The cells the patches took between their seeding (which covers blocked and
        // unblocked cells alike) and five sweeps later: mostly unblocked ones.
        const std::vector<double> times = {1.0 / dpd_sweeps(grid, p), 0.05};
        const auto levels = percolation_depinning_levels(grid, p, 8, times);
        const auto blocked = dpd_blocked_nodes(grid, p.blocked_fraction, 8);
        double taken = 0, taken_open = 0;
        for (size_t i = 0; i < grid.size(); ++i) {
            if (levels[0][i] == 0 && levels[1][i] > 0) {
                ++taken;
                taken_open += blocked[i] == 0;
            }
        }
        ASSERT_GT(taken, 500);
        std::printf("[ measured ] DPD cells taken by spreading: %.0f, %.3f of them unblocked "
                    "(half the lattice is)\n", taken, taken_open / taken);
        EXPECT_GT(taken_open / taken, 0.65);

        // And a wholly unblocked lattice is covered far sooner than a wholly blocked one.
        p.blocked_fraction = 0.0;
        const std::vector<double> mid = {0.5};
        const double free_cover = coverage(percolation_depinning_levels(grid, p, 8, mid)[0]);
        p.blocked_fraction = 1.0;
        const double stuck_cover = coverage(percolation_depinning_levels(grid, p, 8, mid)[0]);
        std::printf("[ measured ] DPD coverage at mid-run: all unblocked %.3f, all blocked %.3f\n",
                    free_cover, stuck_cover);
        EXPECT_GT(free_cover, 2.0 * stuck_cover);
    }

    TEST(PercolationDepinning, NewSeedsAppearOverTime)
    {
        const Lattice grid = make_grid_lattice(160, 160, 0.01f);
        GrowthParameters p = resolved(grid);
        p.advance_unblocked = 1e-9; // patches stay as they were seeded
        p.advance_blocked = 0.0;
        const std::vector<double> times = {1.0 / dpd_sweeps(grid, p), 1.0};
        p.new_seed_ratio = 0.0;
        const auto still = percolation_depinning_levels(grid, p, 5, times);
        EXPECT_DOUBLE_EQ(coverage(still[1]), coverage(still[0]));
        p.new_seed_ratio = 3.0;
        const auto seeded = percolation_depinning_levels(grid, p, 5, times);
        EXPECT_EQ(still[0], seeded[0]);
        EXPECT_GT(coverage(seeded[1]), 2.0 * coverage(seeded[0]));
    }

    TEST(PercolationDepinning, SizesInMetresGiveTheSamePatternAtAnyResolution)
    {
        // A 1 m square at 100 and at 200 cells a side, with every size given in metres: the
        // covered share at each time is about the same (patches of 0.1 m, not of 10 cells).
        GrowthParameters world;
        world.patch_size = 0.1;
        world.seed_density = 4.0; // per m^2
        world.spread_distance = 0.6;
        // Times: the first sweep (the seed patches alone), then 0.3 and 0.6 of the run.
        std::vector<double> times = {0.0, 0.3, 0.6};
        std::vector<double> coarse(times.size(), 0.0), fine(times.size(), 0.0);
        const int runs = 6;
        const Lattice a = make_grid_lattice(100, 100, 0.01f);
        const Lattice b = make_grid_lattice(200, 200, 0.005f);
        std::vector<double> times_a = times, times_b = times;
        times_a[0] = 1.0 / dpd_sweeps(a, resolved(a, world));
        times_b[0] = 1.0 / dpd_sweeps(b, resolved(b, world));
        for (int s = 0; s < runs; ++s) {
            const auto la = percolation_depinning_levels(a, resolved(a, world), 100 + s, times_a);
            const auto lb = percolation_depinning_levels(b, resolved(b, world), 100 + s, times_b);
            for (size_t k = 0; k < times.size(); ++k) {
                coarse[k] += coverage(la[k]) / runs;
                fine[k] += coverage(lb[k]) / runs;
            }
        }
        for (size_t k = 0; k < times.size(); ++k) {
            std::printf("[ measured ] DPD coverage at %.1f: 100^2 %.3f, 200^2 %.3f\n", times[k],
                        coarse[k], fine[k]);
            EXPECT_NEAR(fine[k] / coarse[k], 1.0, 0.25) << times[k];
        }
        // The seed patches alone: 4 seeds of 0.01 m^2 on 1 m^2, about 4 % (overlaps aside).
        EXPECT_NEAR(coarse[0], 0.04, 0.025);
    }

    TEST(PercolationDepinning, UpperLevelsFollowSupport)
    {
        // D&H 1996 §3.3: "the probability of a cell appearing in level l + 1 is proportional
        // to the number of cells in level l that support it": old, well supported patch
        // interiors are thick, freshly reached edges thin.
        const Lattice grid = make_grid_lattice(160, 160, 0.01f);
        const GrowthParameters p = resolved(grid);
        std::vector<double> times;
        for (int k = 0; k <= 20; ++k)
            times.push_back(k / 20.0);
        const auto levels = percolation_depinning_levels(grid, p, 33, times);
        double early_sum = 0, early = 0, late_sum = 0, late = 0;
        for (size_t i = 0; i < grid.size(); ++i) {
            if (levels[5][i] > 0) { // taken in the first quarter
                early_sum += levels[20][i];
                ++early;
            } else if (levels[15][i] == 0 && levels[20][i] > 0) { // in the last quarter
                late_sum += levels[20][i];
                ++late;
            }
            // A level is never reached before the one below: counts are levels, in order.
            ASSERT_LE(levels[20][i], p.levels);
        }
        ASSERT_GT(early, 0);
        ASSERT_GT(late, 0);
        std::printf("[ measured ] DPD final level: taken early %.2f, taken late %.2f\n",
                    early_sum / early, late_sum / late);
        EXPECT_GT(early_sum / early, 2.0 * late_sum / late);
    }

    TEST(PercolationDepinning, DeterministicPerSeed)
    {
        const Lattice grid = make_grid_lattice(90, 70, 0.01f);
        const GrowthParameters p = resolved(grid);
        const std::vector<double> times = {0.25, 1.0};
        EXPECT_EQ(percolation_depinning_levels(grid, p, 3, times),
                  percolation_depinning_levels(grid, p, 3, times));
        EXPECT_NE(percolation_depinning_levels(grid, p, 3, times),
                  percolation_depinning_levels(grid, p, 4, times));
    }

} // namespace
} // namespace patina::texgen
