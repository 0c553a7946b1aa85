// Which voxels along the slab seams can receive a solute flux in a transport step
// (transport.cpp). A flux across a seam goes into a ghost of the slab it leaves, and the ghost
// hands it to its sources in the neighbour slab (SlabLattice::feeds). Ghosts receive fluxes
// only from the active layers of their own slab (stone_state.h: active_depth), so a group of
// feeding voxels (one slab, one layer) needs the step only if one of its ghosts lies within
// its slab's active layers; the rest of the seam (most of the shell's depth) is skipped.
#pragma once

#include "texgen/stone/slab_lattice.h"

#include <cstdint>
#include <vector>

namespace patina::texgen::stone {

class SeamSchedule {
public:
    SeamSchedule() = default;
    explicit SeamSchedule(const SlabLattice& lattice);

    /// Groups: slab s, layer k is group s * n_d + k.
    size_t group_count() const { return group_begin_.empty() ? 0 : group_begin_.size() - 1; }
    /// The group's voxels: lattice.feeding_cells()[first(g) .. last(g)).
    uint32_t first(size_t group) const { return group_begin_[group]; }
    uint32_t last(size_t group) const { return group_begin_[group + 1]; }
    /// Whether a ghost feeding the group can hold a flux: one of them lies within the first
    /// active[slab] + 1 layers of its slab (fluxes reach one layer below the active ones).
    bool may_receive(size_t group, const std::vector<int>& active) const;

private:
    /// The shallowest ghost layer of one neighbour slab among a group's feeds.
    struct Source {
        int slab;
        int layer;
    };
    std::vector<uint32_t> group_begin_;
    std::vector<uint32_t> source_begin_;
    std::vector<Source> sources_;
};

} // namespace patina::texgen::stone
