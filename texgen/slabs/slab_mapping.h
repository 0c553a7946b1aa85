// World <-> slab mapping (Dorsey et al. 1999 §4.1): slab -> world is trilinear in the eight
// corners; world -> slab finds candidate slabs in a uniform grid of their bounding boxes and
// inverts the trilinear map by Newton iteration.
#pragma once

#include "texgen/slabs/slab_shell.h"

#include <Imath/ImathBox.h>
#include <Imath/ImathMatrix.h>

#include <algorithm>
#include <limits>
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
/// With a finite `reject_beyond` (the locator's quick rejection of candidate slabs whose box
/// holds p but which do not hold it), gives up (false) as soon as the first Newton step from
/// the centre lands farther than that outside [0, 1]^3 (a linearisation at the centre of a
/// valid slab is off by well under one slab for points inside it), or when a full Newton
/// step is small against the distance still left outside (more than 0.05 + 4 steps).
bool world_to_slab(const SlabCorners& c, const Imath::V3d& p, Imath::V3d& uvw,
                   double reject_beyond = std::numeric_limits<double>::infinity());

class SlabLocator {
public:
    explicit SlabLocator(const std::vector<SlabCorners>& slabs);

    /// The slab containing p (within `tolerance` of [0,1]^3 in slab coordinates) and its
    /// (u, v, w); where slabs share a face, the one p is deepest inside. Thread-safe.
    std::optional<SlabPoint> locate(const Imath::V3d& p, double tolerance = 1e-7) const;
    /// Every slab containing p within `tolerance` (the overlap test of the shell).
    std::vector<SlabPoint> locate_all(const Imath::V3d& p, double tolerance = 1e-7) const;

    const Imath::Box3d& bounds() const { return bounds_; }
    /// The corner box of slab s (slightly padded).
    const Imath::Box3d& box(size_t s) const { return boxes_[s]; }
    /// Calls f(slab) for every slab whose box meets `box` (a slab may be visited more than
    /// once when its box spans several grid cells).
    template <class F> void for_each_near(const Imath::Box3d& box, F&& f) const;

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

template <class F> void SlabLocator::for_each_near(const Imath::Box3d& box, F&& f) const
{
    if (slabs_.empty() || !bounds_.intersects(box))
        return;
    int lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
        lo[k] = std::clamp(int((box.min[k] - bounds_.min[k]) / cell_size_[k]), 0, res_[k] - 1);
        hi[k] = std::clamp(int((box.max[k] - bounds_.min[k]) / cell_size_[k]), 0, res_[k] - 1);
    }
    for (int z = lo[2]; z <= hi[2]; ++z)
        for (int y = lo[1]; y <= hi[1]; ++y)
            for (int x = lo[0]; x <= hi[0]; ++x) {
                const size_t cell = (size_t(z) * res_[1] + y) * res_[0] + x;
                for (uint32_t i = cell_begin_[cell]; i < cell_begin_[cell + 1]; ++i)
                    if (boxes_[cell_slabs_[i]].intersects(box))
                        f(int(cell_slabs_[i]));
            }
}

/// How far outside [0, 1]^3 a slab coordinate lies (0 inside).
double outside_distance(const Imath::V3d& uvw);

} // namespace patina::texgen::stone
