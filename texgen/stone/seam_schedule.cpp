#include "texgen/stone/seam_schedule.h"

#include <algorithm>

namespace patina::texgen::stone {

SeamSchedule::SeamSchedule(const SlabLattice& lattice)
{
    const SlabGrid& g = lattice.grid();
    const auto& cells = lattice.feeding_cells(); // ascending: slab-major, then layer
    const auto& begin = lattice.feed_begin();
    const auto& feeds = lattice.feeds();
    auto layer_of = [&](size_t cell) {
        return int((cell % g.slab_size) / (size_t(g.sx) * g.sy)) - 1;
    };
    const size_t groups = size_t(g.slab_count) * size_t(g.n_d);
    group_begin_.assign(groups + 1, 0);
    for (uint32_t c : cells)
        ++group_begin_[(c / g.slab_size) * size_t(g.n_d) + size_t(layer_of(c)) + 1];
    for (size_t q = 0; q < groups; ++q)
        group_begin_[q + 1] += group_begin_[q];

    // Per group, the ghost layers of every neighbour slab that feeds it.
    source_begin_.assign(groups + 1, 0);
    std::vector<Source> group_sources;
    for (size_t q = 0; q < groups; ++q) {
        group_sources.clear();
        for (uint32_t e0 = group_begin_[q]; e0 < group_begin_[q + 1]; ++e0) {
            const uint32_t c = cells[e0];
            for (uint32_t e = begin[c]; e < begin[c + 1]; ++e) {
                const int slab = int(feeds[e].ghost / g.slab_size);
                const int layer = layer_of(feeds[e].ghost);
                auto it = std::find_if(group_sources.begin(), group_sources.end(),
                                       [&](const Source& s) { return s.slab == slab; });
                if (it == group_sources.end()) {
                    group_sources.push_back({slab, layer, layer});
                } else {
                    it->first_layer = std::min(it->first_layer, layer);
                    it->last_layer = std::max(it->last_layer, layer);
                }
            }
        }
        sources_.insert(sources_.end(), group_sources.begin(), group_sources.end());
        source_begin_[q + 1] = uint32_t(sources_.size());
    }
}

bool SeamSchedule::received(size_t group, const std::vector<uint8_t>& received, int n_d) const
{
    for (uint32_t e = source_begin_[group]; e < source_begin_[group + 1]; ++e) {
        const Source& src = sources_[e];
        const uint8_t* flags = received.data() + size_t(src.slab) * size_t(n_d);
        for (int k = src.first_layer; k <= src.last_layer; ++k)
            if (flags[k])
                return true;
    }
    return false;
}

} // namespace patina::texgen::stone
