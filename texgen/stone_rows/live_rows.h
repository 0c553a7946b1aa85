// Rows of a slab where a step has work: a row (j, k) of voxels along u is "live" when it holds
// a moist voxel (moisture >= 1/2) or a surface voxel, its halo ends included. Most of a
// slab's active layers are air above the surface or dry stone below it, where the moisture
// and transport steps change nothing; they skip rows without live rows around them.
#pragma once

#include "texgen/stone/stone_state.h"

#include <cstdint>
#include <vector>

namespace patina::texgen::stone {

class LiveRows {
public:
    /// Scan the rows j in [-1, n_t] of layers k in [-1, last] of slab s (halo rows included:
    /// ghosts and the halo above the shell, which copies the first layer). Without
    /// `surface`, only moist voxels make a row live.
    void scan(const StoneState& st, int s, int last, bool surface = true);

    /// Whether row (j, k) is live; j in [-1, n_t], k in [-1, last].
    bool live(int j, int k) const { return live_[at(j, k)] != 0; }

    /// Whether row (j, k) or a row across one of its faces (j +- 1, k +- 1) is live: only
    /// then can the moisture of its voxels change (Darcy inflow comes across faces).
    /// Needs k + 1 <= last.
    bool live_around(int j, int k) const
    {
        return live(j, k) || live(j - 1, k) || live(j + 1, k) || live(j, k - 1) ||
               live(j, k + 1);
    }

private:
    size_t at(int j, int k) const { return size_t(k + 1) * size_t(stride_) + size_t(j + 1); }

    std::vector<uint8_t> live_;
    int stride_ = 0;
};

} // namespace patina::texgen::stone
