// The moisture front's per-voxel work (moisture.cpp, front_step) over one row of a slab, a
// few voxels at a time in the lanes of a vector (lanes.h): the same bits as the loop over
// the row's voxels.
#pragma once

#include "texgen/stone_rows/row_fields.h"
#include "texgen/stone/stone_state.h"

#include <array>
#include <cstdint>

namespace patina::texgen::stone {

struct FrontRows : RowFields {
    StoneState* st = nullptr;
    const float* wetness = nullptr;  ///< per column
    float* wet_time = nullptr;

    bool wet = false;
    float dt = 0.0f, inv_eta = 0.0f, evaporation = 0.0f;

    FrontRows(StoneState& st, bool wet);

    /// The new moisture of the n_t voxels of row (j, k) of slab s into `out` from the old
    /// moisture (read in place, with the halo): air to 0; surface voxels soak in wet phases
    /// and dry in dry ones; dry voxels take in water by Darcy's law from their moist face
    /// neighbours; in dry phases the moist zone dries down each column. Voxels that dry give
    /// their dissolved minerals back as solid (or crust at the surface); moist ones add to
    /// their wet time.
    void row(int s, int j, int k, float* out) const;
};

} // namespace patina::texgen::stone
