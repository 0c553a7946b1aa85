// The pressure diffusion's per-voxel work (moisture.cpp, pressure_step) over one row of a
// slab, a few voxels at a time in the lanes of a vector (lanes.h): the same bits as the loop
// over the row's voxels.
#pragma once

#include "texgen/stone_rows/row_fields.h"
#include "texgen/stone/stone_state.h"

namespace patina::texgen::stone {

struct PressureRows : RowFields {
    const StoneState* st = nullptr;
    float rate = 0.0f;  ///< dt times the pressure diffusivity

    explicit PressureRows(const StoneState& st);

    /// The new pressure of the n_t voxels of row (j, k) of slab s into `out`, from the old
    /// pressure (read in place, with the halo): air and surface voxels keep their Dirichlet
    /// values, dry stone takes the front's p = 0, and moist stone diffuses,
    /// p + rate (phi lap p + grad phi . grad p).
    void row(int s, int j, int k, float* out) const;
};

} // namespace patina::texgen::stone
