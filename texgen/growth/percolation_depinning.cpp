#include "texgen/growth/percolation_depinning.h"

#include "core/sampling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace patina::texgen {
namespace {

    constexpr uint64_t kStreamBlocked = 0x647064626c6f636bULL; // "dpdblock"
    constexpr uint64_t kStreamSeeds = 0x6470647365656473ULL;   // "dpdseeds"
    constexpr uint64_t kStreamSpread = 0x6470647370726561ULL;  // "dpdsprea"
    constexpr uint64_t kStreamLevels = 0x6470646c6576656cULL;  // "dpdlevel"
    constexpr int32_t kNever = std::numeric_limits<int32_t>::max();
    constexpr int kMaxSweeps = 1 << 16;

    /// The v-th output of SplitMix64 started at `base` (Steele, Lea & Flood 2014, "Fast
    /// splittable pseudorandom number generators"): random bits per node that do not depend
    /// on the order nodes are visited in, cheap enough for a few per node and level.
    inline uint64_t node_bits(uint64_t base, uint64_t v)
    {
        uint64_t z = base + (v + 1) * 0x9e3779b97f4a7c15ULL;
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }

    /// Uniform in [0, 1) from the top 53 bits of a hash.
    inline double unit(uint64_t h) { return static_cast<double>(h >> 11) * 0x1p-53; }

    /// Waiting times, in sweeps, of an event with chance p per sweep (geometric on 1, 2, ...),
    /// tabulated at the midpoints of 2^bits equal quantiles so that a few hash bits draw one.
    class GeometricTable {
    public:
        GeometricTable(double p, int bits) : table_(size_t{1} << bits)
        {
            const double n = static_cast<double>(table_.size());
            for (size_t k = 0; k < table_.size(); ++k) {
                if (p >= 1.0) {
                    table_[k] = 1;
                } else if (p <= 0.0) {
                    table_[k] = kNever;
                } else {
                    // Inverse CDF: P(G > g) = (1 - p)^g.
                    const double u = (static_cast<double>(k) + 0.5) / n;
                    const double g = 1.0 + std::floor(std::log(u) / std::log1p(-p));
                    table_[k] = static_cast<int32_t>(std::min(g, double{kMaxSweeps}));
                }
            }
        }
        int32_t operator[](uint64_t k) const { return table_[k]; }

    private:
        std::vector<int32_t> table_;
    };

    /// Returns the node reached by going straight on from `from` to `at`, or -1: leave `at`
    /// through the slot opposite the one that leads back (slot pairs {0, 1} and {2, 3}).
    inline int32_t straight_on(const Lattice& lattice, int32_t from, int32_t at, int* pair)
    {
        const auto& nb = lattice.neighbours[at];
        for (int s = 0; s < 4; ++s) {
            if (nb[s] == from) {
                *pair = s >> 1;
                return nb[s ^ 1];
            }
        }
        return -1;
    }

    /// Appends the nodes of a straight walk of `steps` from `start` leaving by `slot`, each
    /// with the slot pair the walk runs along there.
    void walk(const Lattice& lattice, int32_t start, int slot, int steps,
              std::vector<std::pair<int32_t, int>>* out)
    {
        int32_t from = start;
        int32_t at = lattice.neighbours[start][slot];
        int pair = slot >> 1;
        for (int s = 0; s < steps && at >= 0; ++s) {
            out->emplace_back(at, pair);
            const int32_t next = straight_on(lattice, from, at, &pair);
            from = at;
            at = next;
        }
    }

    int stochastic_round(double x, double u)
    {
        const double f = std::floor(x);
        return static_cast<int>(f) + (u < x - f ? 1 : 0);
    }

} // namespace

std::vector<uint8_t> dpd_blocked_nodes(const Lattice& lattice, double blocked_fraction,
                                       uint64_t seed)
{
    std::vector<uint8_t> blocked(lattice.size());
    const uint64_t base = hash_values(seed, kStreamBlocked);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, blocked.size(), 1 << 14),
                      [&](const tbb::blocked_range<size_t>& r) {
                          for (size_t i = r.begin(); i != r.end(); ++i)
                              blocked[i] = unit(node_bits(base, i)) <
                                           blocked_fraction;
                      });
    return blocked;
}

void dpd_patch_nodes(const Lattice& lattice, int32_t centre, int side, std::vector<int32_t>& out)
{
    // Offsets -back .. +ahead along each pair: exactly `side` nodes on a grid.
    const int back = (side - 1) / 2;
    const int ahead = side - 1 - back;
    std::vector<std::pair<int32_t, int>> line{{centre, 0}};
    walk(lattice, centre, 0, ahead, &line);
    walk(lattice, centre, 1, back, &line);
    std::vector<std::pair<int32_t, int>> column;
    for (const auto& [node, pair] : line) {
        const int across = (pair ^ 1) << 1; // the first slot of the other pair
        column.assign(1, {node, 0});
        walk(lattice, node, across, ahead, &column);
        walk(lattice, node, across + 1, back, &column);
        for (const auto& c : column)
            out.push_back(c.first);
    }
}

int dpd_sweeps(const Lattice& lattice, const GrowthParameters& resolved)
{
    const double sweeps = std::round(resolved.spread_distance / mean_cell_size(lattice));
    if (!(sweeps <= kMaxSweeps))
        throw std::invalid_argument("growth parameter 'spread_distance' (" +
                                    std::to_string(resolved.spread_distance) + " m) is " +
                                    std::to_string(sweeps) + " lattice sweeps; at most " +
                                    std::to_string(kMaxSweeps) + " are supported");
    return std::max(1, static_cast<int>(sweeps));
}

std::vector<std::vector<uint8_t>> percolation_depinning_levels(const Lattice& lattice,
                                                               const GrowthParameters& p,
                                                               uint64_t seed,
                                                               std::span<const double> times)
{
    const size_t n = lattice.size();
    if (n == 0)
        throw std::invalid_argument("DPD: the lattice is empty");
    if (p.levels < 1 || p.levels > 255)
        throw std::invalid_argument("growth parameter 'levels' must be 1 to 255 (got " +
                                    std::to_string(p.levels) + ")");
    if (!(p.patch_size > 0) || !(p.spread_distance > 0) || !(p.seed_density > 0))
        throw std::invalid_argument("DPD: parameters must be resolved first");
    const int sweeps = dpd_sweeps(lattice, p);
    const std::vector<uint8_t> blocked = dpd_blocked_nodes(lattice, p.blocked_fraction, seed);

    // Seed patches: some in the first sweep (the run starts from a bare surface), more at
    // random sweeps over the run, placed only if their centre is still unoccupied then
    // ("at unoccupied positions").
    double area = 0.0;
    for (float c : lattice.cell_size)
        area += static_cast<double>(c) * c;
    Pcg32 rng(hash_values(seed, kStreamSeeds));
    struct Seed {
        int32_t sweep;
        int32_t node;
    };
    std::vector<Seed> seeds;
    const int initial = stochastic_round(p.seed_density * area, rng.uniform_double());
    const int later =
        stochastic_round(p.seed_density * p.new_seed_ratio * area, rng.uniform_double());
    for (int s = 0; s < initial + later; ++s) {
        const auto node = static_cast<int32_t>(rng.uniform_u32(static_cast<uint32_t>(n)));
        const int32_t sweep = s < initial ? 1 : 1 + static_cast<int32_t>(rng.uniform_u32(sweeps));
        seeds.push_back({sweep, node});
    }
    std::stable_sort(seeds.begin(), seeds.end(),
                     [](const Seed& a, const Seed& b) { return a.sweep < b.sweep; });

    // Level 0, the overall pattern: first-passage times by Dial's bucket queue. An edge's
    // delay is the sweeps until the patch advances onto its far end, much shorter onto an
    // unblocked node (D&H 1996 §3.3: "the rules for it are much less stringent").
    const GeometricTable open_delay(p.advance_unblocked, 12);
    const GeometricTable blocked_delay(p.advance_blocked, 12);
    std::vector<int32_t> first(n, kNever);
    std::vector<std::vector<int32_t>> buckets(static_cast<size_t>(sweeps) + 1);
    std::vector<int32_t> patch;
    size_t next_seed = 0;
    const uint64_t spread_base = hash_values(seed, kStreamSpread);
    for (int32_t t = 0; t <= sweeps; ++t) {
        auto& bucket = buckets[t];
        for (; next_seed < seeds.size() && seeds[next_seed].sweep == t; ++next_seed) {
            const int32_t centre = seeds[next_seed].node;
            if (first[centre] < t)
                continue; // landed on an occupied cell
            const int side = std::max(
                1, static_cast<int>(std::lround(p.patch_size / lattice.cell_size[centre])));
            patch.clear();
            dpd_patch_nodes(lattice, centre, side, patch);
            for (int32_t v : patch) {
                if (first[v] > t) {
                    first[v] = t;
                    bucket.push_back(v);
                }
            }
        }
        for (size_t k = 0; k < bucket.size(); ++k) {
            // The bucket lists nodes all over the lattice: fetch what the entries a little
            // ahead will read while this one is relaxed.
            if (k + 16 < bucket.size()) {
                __builtin_prefetch(&lattice.neighbours[bucket[k + 16]]);
                __builtin_prefetch(&first[bucket[k + 16]]);
            }
            if (k + 8 < bucket.size()) {
                for (int32_t w : lattice.neighbours[bucket[k + 8]]) {
                    if (w >= 0) {
                        __builtin_prefetch(&first[w]);
                        __builtin_prefetch(&blocked[w]);
                    }
                }
            }
            const int32_t v = bucket[k];
            if (first[v] != t)
                continue; // a stale entry: reached earlier
            const uint64_t bits = node_bits(spread_base, static_cast<uint64_t>(v));
            const auto& nb = lattice.neighbours[v];
            for (int s = 0; s < 4; ++s) {
                const int32_t w = nb[s];
                if (w < 0)
                    continue;
                const uint64_t u = (bits >> (12 * s)) & 0xfff;
                const int32_t delay = blocked[w] ? blocked_delay[u] : open_delay[u];
                if (delay > sweeps - t)
                    continue;
                const int32_t reached = t + delay;
                if (reached < first[w]) {
                    first[w] = reached;
                    buckets[reached].push_back(w);
                }
            }
        }
        std::vector<int32_t>().swap(bucket);
    }

    // Upper levels: a node climbs from level l to l + 1 after its own level-l time, by the
    // first of the clocks started by each supporter (itself and its level-l neighbours).
    // Each clock has chance q per sweep, set so that a fully supported node climbs the
    // levels in about half the run.
    const double per_level = std::min(1.0, 2.0 * p.levels / sweeps);
    const double q = 1.0 - std::pow(1.0 - per_level, 1.0 / 5.0);
    const GeometricTable climb_delay(q, 12);

    std::vector<double> limits(times.size());
    for (size_t k = 0; k < times.size(); ++k) {
        if (!(times[k] >= 0.0 && times[k] <= 1.0))
            throw std::invalid_argument("DPD: time " + std::to_string(times[k]) +
                                        " is outside [0, 1]");
        limits[k] = times[k] * sweeps;
    }
    std::vector<std::vector<uint8_t>> levels(times.size(), std::vector<uint8_t>(n, 0));
    std::vector<int32_t> below = std::move(first);
    std::vector<int32_t> above(n);
    const auto count_reached = [&](const std::vector<int32_t>& level, size_t begin, size_t end) {
        for (size_t k = 0; k < limits.size(); ++k)
            for (size_t v = begin; v < end; ++v)
                levels[k][v] += level[v] <= limits[k];
    };
    for (int l = 0; l < p.levels; ++l) {
        const bool last = l + 1 == p.levels;
        const uint64_t level_base = hash_values(seed, kStreamLevels, static_cast<uint64_t>(l));
        tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 13),
                          [&](const tbb::blocked_range<size_t>& r) {
            count_reached(below, r.begin(), r.end());
            if (last)
                return;
            for (size_t v = r.begin(); v != r.end(); ++v) {
                const int32_t own = below[v];
                if (own == kNever) {
                    above[v] = kNever;
                    continue;
                }
                const uint64_t bits = node_bits(level_base, v);
                int64_t best = int64_t{own} + climb_delay[bits & 0xfff];
                const auto& nb = lattice.neighbours[v];
                for (int s = 0; s < 4; ++s) {
                    const int32_t u = nb[s];
                    if (u < 0 || below[u] == kNever)
                        continue;
                    const uint64_t g = (bits >> (12 * (s + 1))) & 0xfff;
                    best = std::min(best, int64_t{std::max(below[u], own)} + climb_delay[g]);
                }
                above[v] = best > sweeps ? kNever : static_cast<int32_t>(best);
            }
        });
        below.swap(above);
    }
    return levels;
}

} // namespace patina::texgen
