#include "texgen/growth/deposition.h"

#include "core/sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace patina::texgen {
namespace {

    constexpr int kMaxRelaxationSteps = 16;
    constexpr uint64_t kStreamDeposition = 0x6465706f73697431ULL; // "deposit1"

    /// A uniform node index from one 32-bit draw, without modulo bias or a division per
    /// draw (Lemire 2019, "Fast random integer generation in an interval", ACM TOMS 45(1)).
    class NodePicker {
    public:
        explicit NodePicker(uint32_t n) : n_(n), threshold_((0u - n) % n) {}
        uint32_t operator()(Pcg32& rng) const
        {
            for (;;) {
                const uint64_t m = static_cast<uint64_t>(rng.uniform_u32()) * n_;
                if (static_cast<uint32_t>(m) >= threshold_)
                    return static_cast<uint32_t>(m >> 32);
            }
        }

    private:
        uint32_t n_;
        uint32_t threshold_;
    };

    /// Family's rule on the nearest neighbours (Family 1986; Barabási & Stanley 1995 ch. 5): settle on the
    /// lowest of the node and its neighbours; stay on a tie with the node, else pick one of
    /// the lowest neighbours at random.
    inline int32_t settle_nearest(const Lattice& lattice, const std::vector<int32_t>& h,
                                  int32_t i, Pcg32& rng)
    {
        const auto& nb = lattice.neighbours[i];
        int32_t lowest = h[i];
        int32_t candidates[4];
        int count = 0;
        for (int32_t j : nb) {
            if (j < 0)
                continue;
            if (h[j] < lowest) {
                lowest = h[j];
                candidates[0] = j;
                count = 1;
            } else if (h[j] == lowest && count > 0) {
                candidates[count++] = j;
            }
        }
        if (count == 0)
            return i;
        return count == 1 ? candidates[0] : candidates[rng.uniform_u32(count)];
    }

    /// The relaxation within r lattice steps: a breadth-first search, remembered by a
    /// visit stamp per node so that each particle costs only the nodes it looks at.
    class WideRelaxation {
    public:
        explicit WideRelaxation(size_t n) : stamp_(n, 0) {}

        int32_t settle(const Lattice& lattice, const std::vector<int32_t>& h, int32_t i,
                       int steps, Pcg32& rng)
        {
            if (++generation_ == 0) { // wrapped: clear the stamps once every 2^32 particles
                std::fill(stamp_.begin(), stamp_.end(), 0u);
                generation_ = 1;
            }
            frontier_.assign(1, i);
            stamp_[i] = generation_;
            int32_t best = i;
            int32_t lowest = h[i];
            for (int d = 1; d <= steps && !frontier_.empty(); ++d) {
                next_.clear();
                // The nearest lowest wins, so a ring only competes if it is strictly lower.
                int32_t ring_lowest = std::numeric_limits<int32_t>::max();
                int32_t ring_best = -1;
                uint32_t ring_ties = 0;
                for (int32_t a : frontier_) {
                    for (int32_t b : lattice.neighbours[a]) {
                        if (b < 0 || stamp_[b] == generation_)
                            continue;
                        stamp_[b] = generation_;
                        next_.push_back(b);
                        if (h[b] < ring_lowest) {
                            ring_lowest = h[b];
                            ring_best = b;
                            ring_ties = 1;
                        } else if (h[b] == ring_lowest && rng.uniform_u32(++ring_ties) == 0) {
                            ring_best = b; // reservoir choice: each tie equally likely
                        }
                    }
                }
                if (ring_best >= 0 && ring_lowest < lowest) {
                    lowest = ring_lowest;
                    best = ring_best;
                }
                frontier_.swap(next_);
            }
            return best;
        }

    private:
        std::vector<uint32_t> stamp_;
        uint32_t generation_ = 0;
        std::vector<int32_t> frontier_, next_;
    };

} // namespace

bool is_deposition_model(GrowthModelKind model)
{
    return model == GrowthModelKind::RandomDeposition ||
           model == GrowthModelKind::RandomDepositionRelaxed ||
           model == GrowthModelKind::BallisticDeposition;
}

std::vector<std::vector<int32_t>> deposit_heights(const Lattice& lattice, GrowthModelKind model,
                                                  const GrowthParameters& parameters,
                                                  uint64_t seed,
                                                  std::span<const uint64_t> counts)
{
    if (!is_deposition_model(model))
        throw std::invalid_argument("deposit_heights: model '" +
                                    std::string(growth_model_name(model)) +
                                    "' is not a deposition model (RD, RDR or BD)");
    const size_t n = lattice.size();
    if (n == 0 || n > std::numeric_limits<int32_t>::max())
        throw std::invalid_argument("deposit_heights: the lattice has " + std::to_string(n) +
                                    " nodes");
    if (!std::is_sorted(counts.begin(), counts.end()))
        throw std::invalid_argument("deposit_heights: particle counts must not decrease");
    // A height never exceeds the particles dropped, so int32 heights need a bound on those.
    if (!counts.empty() && counts.back() > static_cast<uint64_t>(
                                               std::numeric_limits<int32_t>::max()))
        throw std::invalid_argument("deposit_heights: " + std::to_string(counts.back()) +
                                    " particles is more than 2^31 - 1");

    // Relaxation reach per node in lattice steps (its cell size may vary over a mesh).
    std::vector<uint8_t> reach;
    bool wide = false;
    if (model == GrowthModelKind::RandomDepositionRelaxed && parameters.relaxation_radius > 0) {
        reach.resize(n);
        for (size_t i = 0; i < n; ++i) {
            const double steps =
                std::round(parameters.relaxation_radius / lattice.cell_size[i]);
            if (!(steps <= kMaxRelaxationSteps))
                throw std::invalid_argument(
                    "growth parameter 'relaxation_radius' (" +
                    std::to_string(parameters.relaxation_radius) + " m) is " +
                    std::to_string(steps) + " lattice steps; at most " +
                    std::to_string(kMaxRelaxationSteps) + " are supported");
            reach[i] = static_cast<uint8_t>(std::max(1.0, steps));
            wide = wide || reach[i] > 1;
        }
    }

    std::vector<int32_t> h(n, 0);
    std::vector<std::vector<int32_t>> snapshots;
    snapshots.reserve(counts.size());
    Pcg32 rng(hash_values(seed, kStreamDeposition));
    const NodePicker pick(static_cast<uint32_t>(n));
    const auto& neighbours = lattice.neighbours;
    uint64_t dropped = 0;
    WideRelaxation relaxation(wide ? n : 0);

    for (uint64_t target : counts) {
        const uint64_t todo = target - dropped;
        switch (model) {
        case GrowthModelKind::RandomDeposition:
            // Barabási & Stanley 1995 ch. 4: the particle falls straight onto its column.
            for (uint64_t p = 0; p < todo; ++p)
                ++h[pick(rng)];
            break;
        case GrowthModelKind::RandomDepositionRelaxed:
            // Family 1986 (B&S 1995 ch. 5): it then slides to the lowest nearby column.
            if (wide) {
                for (uint64_t p = 0; p < todo; ++p) {
                    const auto i = static_cast<int32_t>(pick(rng));
                    const int32_t j = reach[i] > 1
                                          ? relaxation.settle(lattice, h, i, reach[i], rng)
                                          : settle_nearest(lattice, h, i, rng);
                    ++h[j];
                }
            } else {
                for (uint64_t p = 0; p < todo; ++p)
                    ++h[settle_nearest(lattice, h, static_cast<int32_t>(pick(rng)), rng)];
            }
            break;
        case GrowthModelKind::BallisticDeposition:
            // B&S 1995 ch. 2, D&H 1996 §3.3: h_i = max(h_i + 1, h of its neighbours).
            for (uint64_t p = 0; p < todo; ++p) {
                const uint32_t i = pick(rng);
                const auto& nb = neighbours[i];
                int32_t v = h[i] + 1;
                for (int32_t j : nb)
                    v = std::max(v, j >= 0 ? h[j] : 0);
                h[i] = v;
            }
            break;
        default:
            break;
        }
        dropped = target;
        snapshots.push_back(h);
    }
    return snapshots;
}

} // namespace patina::texgen
