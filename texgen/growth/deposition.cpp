#include "texgen/growth/deposition.h"

#include "core/sampling.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
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

    /// Family's rule on the nearest neighbours (Family 1986; Barabási & Stanley 1995 ch. 5):
    /// settle on the lowest of the node and its neighbours; stay on a tie with the node, else
    /// pick one of the lowest neighbours at random.
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

    /// One particle landing on node i under the model's rule.
    template <GrowthModelKind M>
    inline void drop(const Lattice& lattice, std::vector<int32_t>& h, uint32_t i, Pcg32& rng)
    {
        if constexpr (M == GrowthModelKind::RandomDeposition) {
            // Barabási & Stanley 1995 ch. 4: the particle falls straight onto its column.
            ++h[i];
        } else if constexpr (M == GrowthModelKind::RandomDepositionRelaxed) {
            // Family 1986 (B&S 1995 ch. 5): it then slides to the lowest nearby column.
            ++h[settle_nearest(lattice, h, static_cast<int32_t>(i), rng)];
        } else {
            // B&S 1995 ch. 2, D&H 1996 §3.3: h_i = max(h_i + 1, h of its neighbours).
            int32_t v = h[i] + 1;
            for (int32_t j : lattice.neighbours[i])
                v = std::max(v, j >= 0 ? h[j] : 0);
            h[i] = v;
        }
    }

    /// Deposition in blocks of nodes, in parallel, with the same bits for any thread count.
    /// The particle sequence is cut into chunks of a quarter monolayer. A chunk's stream
    /// decides how many of its particles land in each block (exactly the multinomial share
    /// of a uniform choice of node); a stream per block where in the block they land, in
    /// order. Blocks that cannot affect each other (no node of one within the rule's reach
    /// of the other) share a colour and run at once; the colours take turns in an order
    /// drawn per chunk, so that two particles landing on either side of a block edge in one
    /// chunk fall in either order, as in one sequence. Only runs of several particles on
    /// both sides of an edge within one chunk lose their interleaving, a small effect on
    /// the order of events that leaves no mark at block edges (the tests look). RD's
    /// columns never interact: all its blocks run at once and its result is exactly RD's.
    /// A lattice of one block (up to 32768 nodes) is exactly the sequential model.
    class BlockedDeposition {
    public:
        BlockedDeposition(const Lattice& lattice, GrowthModelKind model, uint64_t seed)
            : lattice_(lattice), model_(model), seed_(seed), n_(lattice.size()),
              blocks_(static_cast<uint32_t>((n_ + kBlockNodes - 1) / kBlockNodes)),
              chunk_(std::max<uint64_t>(1, n_ / kChunksPerLayer)), pick_node_(
                  static_cast<uint32_t>(n_))
            {
            for (uint32_t b = 0; b < blocks_; ++b) {
                pick_in_block_.emplace_back(block_size(b));
                place_.emplace_back(hash_values(seed_, kStreamPlace, b));
                ties_.emplace_back(hash_values(seed_, kStreamTies, b));
            }
            colour_blocks();
            order_.assign(1, 0);
        }

        /// Drops particles first .. last - 1 of the run's sequence onto h.
        void deposit(std::vector<int32_t>& h, uint64_t first, uint64_t last)
        {
            // The chunks' parts in this range, their block counts drawn a batch at a time in
            // parallel (each from its own stream), then dropped part by part.
            struct Part {
                uint64_t chunk, from, to;
                std::vector<uint32_t> per_block;
            };
            constexpr size_t kBatch = 16;
            std::vector<Part> parts;
            while (first < last) {
                parts.clear();
                while (first < last && parts.size() < kBatch) {
                    const uint64_t c = first / chunk_;
                    const uint64_t end = std::min(last, (c + 1) * chunk_);
                    parts.push_back({c, first - c * chunk_, end - c * chunk_, {}});
                    first = end;
                }
                tbb::parallel_for(size_t{0}, parts.size(), [&](size_t k) {
                    parts[k].per_block = block_counts(parts[k].chunk, parts[k].from, parts[k].to);
                });
                if (model_ == GrowthModelKind::RandomDeposition) {
                    // Columns never interact: the whole batch at once, block by block.
                    for (size_t k = 1; k < parts.size(); ++k)
                        for (uint32_t b = 0; b < blocks_; ++b)
                            parts[0].per_block[b] += parts[k].per_block[b];
                    drop_part(h, parts[0].per_block);
                    continue;
                }
                for (const Part& part : parts) {
                    if (part.chunk != current_)
                        start_chunk(part.chunk);
                    drop_part(h, part.per_block);
                }
            }
        }

    private:
        static constexpr uint32_t kBlockNodes = 1u << 15; // 640 KiB with its neighbours
        static constexpr uint64_t kChunksPerLayer = 4;
        static constexpr uint64_t kStreamBlocks = 0x6465706f626c6b73ULL; // "depoblks"
        static constexpr uint64_t kStreamPlace = 0x6465706f706c6163ULL;  // "depoplac"
        static constexpr uint64_t kStreamOrder = 0x6465706f6f726472ULL;  // "depoordr"
        static constexpr uint64_t kStreamTies = 0x6465706f74696573ULL;   // "depoties"

        uint32_t block_size(uint32_t b) const
        {
            return static_cast<uint32_t>(
                std::min<size_t>(kBlockNodes, n_ - size_t{b} * kBlockNodes));
        }

        /// Greedy colouring of the blocks so that no two of a colour interact: BD reads the
        /// neighbours of the node it writes (reach 1); RDR writes a neighbour of the node
        /// whose neighbours it reads (reach 2).
        void colour_blocks()
        {
            const int reach = model_ == GrowthModelKind::RandomDeposition          ? 0
                              : model_ == GrowthModelKind::BallisticDeposition ? 1
                                                                                  : 2;
            std::vector<int> colour(blocks_, 0);
            if (reach > 0 && blocks_ > 1) {
                std::vector<std::vector<uint32_t>> touching(blocks_);
                tbb::parallel_for(uint32_t{0}, blocks_, [&](uint32_t b) {
                    auto& out = touching[b];
                    const size_t begin = size_t{b} * kBlockNodes, end = begin + block_size(b);
                    for (size_t v = begin; v < end; ++v) {
                        for (int32_t u : lattice_.neighbours[v]) {
                            if (u < 0)
                                continue;
                            if (static_cast<uint32_t>(u) / kBlockNodes != b)
                                out.push_back(static_cast<uint32_t>(u) / kBlockNodes);
                            if (reach < 2)
                                continue;
                            for (int32_t w : lattice_.neighbours[u])
                                if (w >= 0 && static_cast<uint32_t>(w) / kBlockNodes != b)
                                    out.push_back(static_cast<uint32_t>(w) / kBlockNodes);
                        }
                        if (out.size() > 4096) {
                            std::sort(out.begin(), out.end());
                            out.erase(std::unique(out.begin(), out.end()), out.end());
                        }
                    }
                    std::sort(out.begin(), out.end());
                    out.erase(std::unique(out.begin(), out.end()), out.end());
                });
                for (uint32_t b = 0; b < blocks_; ++b) {
                    std::vector<bool> used;
                    for (uint32_t o : touching[b]) {
                        if (o >= b)
                            continue;
                        if (used.size() <= static_cast<size_t>(colour[o]))
                            used.resize(colour[o] + 1, false);
                        used[colour[o]] = true;
                    }
                    int c = 0;
                    while (c < static_cast<int>(used.size()) && used[c])
                        ++c;
                    colour[b] = c;
                }
            }
            const int colours = *std::max_element(colour.begin(), colour.end()) + 1;
            by_colour_.assign(colours, {});
            for (uint32_t b = 0; b < blocks_; ++b)
                by_colour_[colour[b]].push_back(b);
        }

        /// How many of particles from .. to - 1 of chunk c land in each block: the chunk's
        /// stream read from its start (so a chunk cut by a snapshot continues seamlessly).
        std::vector<uint32_t> block_counts(uint64_t c, uint64_t from, uint64_t to) const
        {
            std::vector<uint32_t> per_block(blocks_, 0);
            if (blocks_ == 1) {
                per_block[0] = static_cast<uint32_t>(to - from);
                return per_block;
            }
            Pcg32 rng(hash_values(seed_, kStreamBlocks, c));
            for (uint64_t p = 0; p < from; ++p)
                pick_node_(rng);
            for (uint64_t p = from; p < to; ++p)
                ++per_block[pick_node_(rng) / kBlockNodes];
            return per_block;
        }

        void start_chunk(uint64_t c)
        {
            current_ = c;
            order_.resize(by_colour_.size());
            std::iota(order_.begin(), order_.end(), 0);
            Pcg32 order_rng(hash_values(seed_, kStreamOrder, c));
            for (size_t i = order_.size(); i > 1; --i)
                std::swap(order_[i - 1], order_[order_rng.uniform_u32(static_cast<uint32_t>(i))]);
        }

        /// Drops per_block[b] particles in each block b: the colours in the chunk's order,
        /// the blocks of a colour at once, each continuing its own stream.
        void drop_part(std::vector<int32_t>& h, const std::vector<uint32_t>& per_block)
        {
            for (int colour : order_) {
                const auto& blocks = by_colour_[colour];
                tbb::parallel_for(size_t{0}, blocks.size(), [&](size_t k) {
                    const uint32_t b = blocks[k];
                    const uint32_t base = b * kBlockNodes;
                    const NodePicker& pick = pick_in_block_[b];
                    const uint32_t count = per_block[b];
                    switch (model_) {
                    case GrowthModelKind::RandomDeposition:
                        drop_in_block<GrowthModelKind::RandomDeposition>(h, base, pick, b, count);
                        break;
                    case GrowthModelKind::RandomDepositionRelaxed:
                        drop_in_block<GrowthModelKind::RandomDepositionRelaxed>(h, base, pick, b,
                                                                                count);
                        break;
                    default:
                        drop_in_block<GrowthModelKind::BallisticDeposition>(h, base, pick, b,
                                                                            count);
                        break;
                    }
                });
            }
        }

        /// `count` particles in block b. The landing nodes are drawn kAhead particles early
        /// and their cache lines fetched meanwhile (the heights of a 4M-node lattice do not
        /// fit in cache, and each particle would otherwise wait for memory in turn); RDR's
        /// ties draw from a stream of their own, so the results do not depend on this.
        template <GrowthModelKind M>
        void drop_in_block(std::vector<int32_t>& h, uint32_t base, const NodePicker& pick,
                           uint32_t b, uint32_t count)
        {
            constexpr uint32_t kAhead = 32;
            Pcg32& rng = place_[b];
            Pcg32& ties = ties_[b];
            const auto& neighbours = lattice_.neighbours;
            uint32_t ring[kAhead];
            const uint32_t primed = std::min(count, kAhead);
            for (uint32_t p = 0; p < primed; ++p) {
                ring[p] = base + pick(rng);
                __builtin_prefetch(&h[ring[p]], 1);
                if constexpr (M != GrowthModelKind::RandomDeposition)
                    __builtin_prefetch(&neighbours[ring[p]]);
            }
            for (uint32_t p = 0; p < count; ++p) {
                const uint32_t i = ring[p % kAhead];
                if (p + kAhead < count) {
                    const uint32_t j = base + pick(rng);
                    ring[p % kAhead] = j;
                    __builtin_prefetch(&h[j], 1);
                    if constexpr (M != GrowthModelKind::RandomDeposition)
                        __builtin_prefetch(&neighbours[j]);
                }
                if constexpr (M != GrowthModelKind::RandomDeposition) {
                    // Halfway there: the neighbour list has arrived, fetch their heights.
                    if (p + kAhead / 2 < count) {
                        for (int32_t u : neighbours[ring[(p + kAhead / 2) % kAhead]])
                            if (u >= 0)
                                __builtin_prefetch(&h[u]);
                    }
                }
                drop<M>(lattice_, h, i, ties);
            }
        }

        const Lattice& lattice_;
        GrowthModelKind model_;
        uint64_t seed_;
        size_t n_;
        uint32_t blocks_;
        uint64_t chunk_;
        NodePicker pick_node_;
        std::vector<NodePicker> pick_in_block_;
        std::vector<std::vector<uint32_t>> by_colour_;
        uint64_t current_ = std::numeric_limits<uint64_t>::max();
        std::vector<Pcg32> place_, ties_;
        std::vector<int> order_;
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
    if (wide) {
        // Reaches over several steps interact too far for the blocks below: one stream.
        Pcg32 rng(hash_values(seed, kStreamDeposition));
        const NodePicker pick(static_cast<uint32_t>(n));
        WideRelaxation relaxation(n);
        uint64_t dropped = 0;
        for (uint64_t target : counts) {
            for (; dropped < target; ++dropped) {
                const auto i = static_cast<int32_t>(pick(rng));
                ++h[reach[i] > 1 ? relaxation.settle(lattice, h, i, reach[i], rng)
                                 : settle_nearest(lattice, h, i, rng)];
            }
            snapshots.push_back(h);
        }
        return snapshots;
    }
    BlockedDeposition run(lattice, model, seed);
    uint64_t dropped = 0;
    for (uint64_t target : counts) {
        run.deposit(h, dropped, target);
        dropped = target;
        snapshots.push_back(h);
    }
    return snapshots;
}

} // namespace patina::texgen
