// Which voxels along the slab seams can receive a solute flux in a transport step
// (transport.cpp). A flux across a seam goes into a ghost of the slab it leaves, and the ghost
// hands it to its sources in the neighbour slab (SlabLattice::feeds). Ghosts receive fluxes
// only where a moist voxel borders a moist ghost, which the transport step flags per slab and
// layer (StoneState::ghost_received); a group of feeding voxels (one slab, one layer) needs
// the seam pass only if one of its ghosts lies in a flagged layer, and the rest of the seam
// (most of the shell's depth, and the dry part of the active layers) is skipped.
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
    /// Whether a ghost feeding the group received a flux: one of them lies in a layer
    /// flagged in `received` (slab * n_d + layer, StoneState::ghost_received).
    bool received(size_t group, const std::vector<uint8_t>& received, int n_d) const;

private:
    /// The ghost layers of one neighbour slab among a group's feeds.
    struct Source {
        int slab;
        int first_layer, last_layer;
    };
    std::vector<uint32_t> group_begin_;
    std::vector<uint32_t> source_begin_;
    std::vector<Source> sources_;
};

} // namespace patina::texgen::stone
