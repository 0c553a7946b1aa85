#include "texgen/slabs/slab_mapping.h"

#include <algorithm>
#include <cmath>

namespace patina::texgen::stone {

using Imath::V3d;

namespace {
    /// Candidates whose first Newton step lands this far outside are not refined (see
    /// world_to_slab).
    constexpr double kQuickReject = 1.0;
} // namespace

V3d slab_to_world(const SlabCorners& c, const V3d& t)
{
    const V3d a = c[0] + t.x * (c[1] - c[0]), b = c[2] + t.x * (c[3] - c[2]);
    const V3d e = c[4] + t.x * (c[5] - c[4]), f = c[6] + t.x * (c[7] - c[6]);
    const V3d outer = a + t.y * (b - a), inner = e + t.y * (f - e);
    return outer + t.z * (inner - outer);
}

void slab_derivatives(const SlabCorners& c, const V3d& t, V3d& du, V3d& dv, V3d& dw)
{
    const double u = t.x, v = t.y, w = t.z;
    // d/du: the u-edges (c1 - c0, c3 - c2, c5 - c4, c7 - c6) blended bilinearly in v, w.
    du = (1 - v) * (1 - w) * (c[1] - c[0]) + v * (1 - w) * (c[3] - c[2]) +
         (1 - v) * w * (c[5] - c[4]) + v * w * (c[7] - c[6]);
    dv = (1 - u) * (1 - w) * (c[2] - c[0]) + u * (1 - w) * (c[3] - c[1]) +
         (1 - u) * w * (c[6] - c[4]) + u * w * (c[7] - c[5]);
    dw = (1 - u) * (1 - v) * (c[4] - c[0]) + u * (1 - v) * (c[5] - c[1]) +
         (1 - u) * v * (c[6] - c[2]) + u * v * (c[7] - c[3]);
}

bool world_to_slab(const SlabCorners& c, const V3d& p, V3d& uvw, double reject_beyond)
{
    double size = 0.0;
    for (int i = 1; i < 8; ++i)
        size = std::max(size, (c[i] - c[0]).length());
    const double tol = 1e-9 * size;
    // Damped Newton: halve a step that does not reduce the residual (the trilinear map of a
    // skewed slab is far from linear), from the centre and, failing that, from the corners.
    auto solve = [&](const V3d& start, double reject) {
        uvw = start;
        V3d r = slab_to_world(c, uvw) - p;
        for (int it = 0; it < 30; ++it) {
            const double norm = r.length();
            if (norm <= tol)
                return true;
            V3d du, dv, dw;
            slab_derivatives(c, uvw, du, dv, dw);
            const double det = du.cross(dv).dot(dw);
            if (!(std::abs(det) > 1e-300))
                return false;
            const V3d delta(r.cross(dv).dot(dw) / det, du.cross(r).dot(dw) / det,
                            du.cross(dv).dot(r) / det);
            if (it == 0 && outside_distance(uvw - delta) > reject)
                return false;
            double step = 1.0;
            double moved = 0.0;
            for (int half = 0; half < 8; ++half, step *= 0.5) {
                V3d next = uvw - step * delta;
                for (int k = 0; k < 3; ++k)
                    next[k] = std::clamp(next[k], -2.0, 3.0);
                const V3d rn = slab_to_world(c, next) - p;
                if (rn.length() < norm || half == 7) {
                    const V3d d = next - uvw;
                    moved = std::max({std::abs(d.x), std::abs(d.y), std::abs(d.z)});
                    uvw = next;
                    r = rn;
                    break;
                }
            }
            // Converging outside: a full Newton step that has become small against the
            // distance still left to the slab (quadratic convergence) leaves the answer
            // outside too.
            if (reject < std::numeric_limits<double>::infinity() && step == 1.0 &&
                outside_distance(uvw) > 0.05 + 4.0 * moved)
                return false;
        }
        return r.length() <= tol * 1e3;
    };
    if (solve(V3d(0.5), reject_beyond))
        return true;
    // Clearly outside (the usual case for a candidate slab that does not hold p): no retries.
    if (outside_distance(uvw) > 0.25)
        return false;
    for (int corner = 0; corner < 8; ++corner)
        if (solve(V3d(corner & 1 ? 0.9 : 0.1, corner & 2 ? 0.9 : 0.1, corner & 4 ? 0.9 : 0.1),
                  std::numeric_limits<double>::infinity()))
            return true;
    return false;
}

double outside_distance(const V3d& t)
{
    double d = 0.0;
    for (int k = 0; k < 3; ++k)
        d = std::max({d, -t[k], t[k] - 1.0});
    return d;
}

SlabLocator::SlabLocator(const std::vector<SlabCorners>& slabs) : slabs_(slabs)
{
    boxes_.resize(slabs.size());
    double mean = 0.0;
    for (size_t s = 0; s < slabs.size(); ++s) {
        // Bilinear faces bulge at most to the hull of the corners: the corner box bounds them.
        for (const V3d& c : slabs[s])
            boxes_[s].extendBy(c);
        const V3d pad = (boxes_[s].max - boxes_[s].min) * 1e-6 + V3d(1e-12);
        boxes_[s].min -= pad;
        boxes_[s].max += pad;
        bounds_.extendBy(boxes_[s]);
        mean += (boxes_[s].max - boxes_[s].min).length();
    }
    if (slabs.empty())
        return;
    mean /= double(slabs.size());
    const V3d extent = bounds_.max - bounds_.min;
    for (int k = 0; k < 3; ++k)
        res_[k] = std::clamp(int(std::ceil(extent[k] / std::max(mean, 1e-30))), 1, 256);
    cell_size_ = V3d(extent.x / res_[0], extent.y / res_[1], extent.z / res_[2]);
    const size_t n_cells = size_t(res_[0]) * res_[1] * res_[2];
    auto cell_range = [&](const Imath::Box3d& b, int lo[3], int hi[3]) {
        for (int k = 0; k < 3; ++k) {
            lo[k] = std::clamp(int((b.min[k] - bounds_.min[k]) / cell_size_[k]), 0, res_[k] - 1);
            hi[k] = std::clamp(int((b.max[k] - bounds_.min[k]) / cell_size_[k]), 0, res_[k] - 1);
        }
    };
    std::vector<uint32_t> count(n_cells + 1, 0);
    for (int pass = 0; pass < 2; ++pass) {
        if (pass == 1) {
            cell_begin_.assign(n_cells + 1, 0);
            for (size_t i = 0; i < n_cells; ++i)
                cell_begin_[i + 1] = cell_begin_[i] + count[i];
            cell_slabs_.resize(cell_begin_[n_cells]);
            std::fill(count.begin(), count.end(), 0);
        }
        for (size_t s = 0; s < slabs.size(); ++s) {
            int lo[3], hi[3];
            cell_range(boxes_[s], lo, hi);
            for (int z = lo[2]; z <= hi[2]; ++z)
                for (int y = lo[1]; y <= hi[1]; ++y)
                    for (int x = lo[0]; x <= hi[0]; ++x) {
                        const size_t cell = (size_t(z) * res_[1] + y) * res_[0] + x;
                        if (pass == 1)
                            cell_slabs_[cell_begin_[cell] + count[cell]] = uint32_t(s);
                        ++count[cell];
                    }
        }
    }
}

template <class F> void SlabLocator::for_candidates(const V3d& p, F&& f) const
{
    if (slabs_.empty() || !bounds_.intersects(p))
        return;
    int c[3];
    for (int k = 0; k < 3; ++k)
        c[k] = std::clamp(int((p[k] - bounds_.min[k]) / cell_size_[k]), 0, res_[k] - 1);
    const size_t cell = (size_t(c[2]) * res_[1] + c[1]) * res_[0] + c[0];
    for (uint32_t i = cell_begin_[cell]; i < cell_begin_[cell + 1]; ++i) {
        const uint32_t s = cell_slabs_[i];
        if (boxes_[s].intersects(p))
            f(int(s));
    }
}

std::optional<SlabPoint> SlabLocator::locate(const V3d& p, double tolerance) const
{
    std::optional<SlabPoint> best;
    double best_out = tolerance;
    double best_depth = -1.0;
    for_candidates(p, [&](int s) {
        V3d uvw;
        if (!world_to_slab(slabs_[s], p, uvw, kQuickReject))
            return;
        const double out = outside_distance(uvw);
        if (out > tolerance)
            return;
        // Prefer the slab p is deepest inside (distance to its nearest face, negative out).
        double depth = 1.0;
        for (int k = 0; k < 3; ++k)
            depth = std::min({depth, uvw[k], 1.0 - uvw[k]});
        if (!best || depth > best_depth) {
            best = SlabPoint{s, uvw};
            best_depth = depth;
            best_out = out;
        }
    });
    (void)best_out;
    return best;
}

std::vector<SlabPoint> SlabLocator::locate_all(const V3d& p, double tolerance) const
{
    std::vector<SlabPoint> all;
    for_candidates(p, [&](int s) {
        V3d uvw;
        if (world_to_slab(slabs_[s], p, uvw, kQuickReject) && outside_distance(uvw) <= tolerance)
            all.push_back(SlabPoint{s, uvw});
    });
    return all;
}

} // namespace patina::texgen::stone
