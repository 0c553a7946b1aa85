// World <-> slab mapping (Dorsey et al. 1999 §4.1): slab -> world is trilinear in the eight
// corners; world -> slab finds candidate slabs in a uniform grid of their bounding boxes and
// inverts the trilinear map by Newton iteration.
#pragma once

#include "texgen/stone/slab_shell.h"

#include <Imath/ImathBox.h>
#include <Imath/ImathMatrix.h>

#include <optional>
#include <vector>

namespace patina::texgen::stone {

/// Trilinear interpolation of the corners at (u, v, w).
Imath::V3d slab_to_world(const SlabCorners& c, const Imath::V3d& uvw);
/// Columns d/du, d/dv, d/dw of slab_to_world (Imath row-vector matrices: row r = column r).
void slab_derivatives(const SlabCorners& c, const Imath::V3d& uvw, Imath::V3d& du,
                      Imath::V3d& dv, Imath::V3d& dw);

/// A point in slab coordinates.
struct SlabPoint {
    int slab = -1;
    Imath::V3d uvw;
};

/// Newton iteration for the (u, v, w) of `p` in slab `c`, from the centre; true when it
/// converged (|slab_to_world(uvw) - p| below 1e-9 of the slab's size). `uvw` may lie outside
/// [0, 1]^3 (p outside the slab).
bool world_to_slab(const SlabCorners& c, const Imath::V3d& p, Imath::V3d& uvw);

class SlabLocator {
public:
    explicit SlabLocator(const std::vector<SlabCorners>& slabs);

    /// The slab containing p (within `tolerance` of [0,1]^3 in slab coordinates) and its
    /// (u, v, w); where slabs share a face, the one p is deepest inside. Thread-safe.
    std::optional<SlabPoint> locate(const Imath::V3d& p, double tolerance = 1e-7) const;
    /// Every slab containing p within `tolerance` (the overlap test of the shell).
    std::vector<SlabPoint> locate_all(const Imath::V3d& p, double tolerance = 1e-7) const;

    const Imath::Box3d& bounds() const { return bounds_; }

private:
    template <class F> void for_candidates(const Imath::V3d& p, F&& f) const;

    const std::vector<SlabCorners>& slabs_;
    std::vector<Imath::Box3d> boxes_;
    Imath::Box3d bounds_;
    int res_[3] = {1, 1, 1};
    Imath::V3d cell_size_;
    std::vector<uint32_t> cell_begin_;
    std::vector<uint32_t> cell_slabs_;
};

/// How far outside [0, 1]^3 a slab coordinate lies (0 inside).
double outside_distance(const Imath::V3d& uvw);

} // namespace patina::texgen::stone
