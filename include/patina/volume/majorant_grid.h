// patina/volume/majorant_grid.h — a coarse grid of density bounds over a VoxelGrid, and
// the walk of a ray through it.
//
// Delta and ratio tracking (pbrt-v4 §11.2 and §14.2) need a majorant σ̄ >= σt along the
// ray. One bound for the whole box is correct but slow where the stone is thin; this grid
// stores, per block of B³ voxels, the largest density trilinear interpolation can reach in
// the block (VoxelGrid::max_density_over), and `traverse` hands the ray's segments through
// the blocks, front to back, with their bound (Amanatides & Woo 1987, "A Fast Voxel
// Traversal Algorithm for Ray Tracing", Eurographics). pbrt-v4's DDAMajorantIterator does
// the same (§11.4.3).
#pragma once

#include <patina/volume/voxel_grid.h>

#include <limits>

namespace patina::volume {

class MajorantGrid {
public:
    MajorantGrid() = default;
    /// Bounds of `grid` per block of block³ voxels (block >= 1).
    MajorantGrid(const VoxelGrid& grid, int block) : lo_(grid.lo()), hi_(grid.hi())
    {
        for (int a = 0; a < 3; ++a) {
            m_[a] = (grid.size(a) + block - 1) / block;
            block_size_[a] = static_cast<double>(block) * grid.cell(a);
        }
        max_.resize(static_cast<size_t>(m_[0]) * m_[1] * m_[2]);
        for (int k = 0; k < m_[2]; ++k)
            for (int j = 0; j < m_[1]; ++j)
                for (int i = 0; i < m_[0]; ++i)
                    max_[index(i, j, k)] =
                        grid.max_density_over(i * block, (i + 1) * block, j * block,
                                              (j + 1) * block, k * block, (k + 1) * block);
    }

    int size(int axis) const { return m_[axis]; }
    float max_density(int i, int j, int k) const { return max_[index(i, j, k)]; }

    /// Calls f(t0, t1, max_density) for each segment of the ray o + t d, t in [0, t_max],
    /// inside the box, in order of t; stops early when f returns false. d need not be unit
    /// (t is in its units) but must be finite and non-zero.
    template <typename F> void traverse(shading::Vec3 o, shading::Vec3 d, double t_max, F&& f) const
    {
        if (max_.empty())
            return;
        // Clip the ray to the box (slabs method)
        double t_enter = 0.0, t_exit = t_max;
        for (int a = 0; a < 3; ++a) {
            if (d[a] == 0.0f) {
                if (o[a] < lo_[a] || o[a] > hi_[a])
                    return;
                continue;
            }
            double ta = (static_cast<double>(lo_[a]) - o[a]) / d[a];
            double tb = (static_cast<double>(hi_[a]) - o[a]) / d[a];
            if (ta > tb)
                std::swap(ta, tb);
            t_enter = std::max(t_enter, ta);
            t_exit = std::min(t_exit, tb);
        }
        if (!(t_enter < t_exit))
            return;

        // The block of the entry point and the t of the next block face on each axis
        constexpr double kInf = std::numeric_limits<double>::infinity();
        int cell[3], step[3];
        double t_next[3], t_delta[3];
        for (int a = 0; a < 3; ++a) {
            const double p = o[a] + t_enter * d[a];
            cell[a] = std::clamp(static_cast<int>(std::floor((p - lo_[a]) / block_size_[a])), 0,
                                 m_[a] - 1);
            if (d[a] > 0.0f) {
                step[a] = 1;
                t_next[a] = (lo_[a] + (cell[a] + 1) * block_size_[a] - o[a]) / d[a];
                t_delta[a] = block_size_[a] / d[a];
            } else if (d[a] < 0.0f) {
                step[a] = -1;
                t_next[a] = (lo_[a] + cell[a] * block_size_[a] - o[a]) / d[a];
                t_delta[a] = -block_size_[a] / d[a];
            } else {
                step[a] = 0;
                t_next[a] = kInf;
                t_delta[a] = kInf;
            }
        }

        // Walk block to block: Amanatides & Woo 1987, §3
        double t = t_enter;
        while (t < t_exit) {
            const int axis = t_next[0] < t_next[1] ? (t_next[0] < t_next[2] ? 0 : 2)
                                                   : (t_next[1] < t_next[2] ? 1 : 2);
            const double t1 = std::min(t_next[axis], t_exit);
            if (t1 > t && !f(t, t1, max_[index(cell[0], cell[1], cell[2])]))
                return;
            t = std::max(t, t1);
            cell[axis] += step[axis];
            if (cell[axis] < 0 || cell[axis] >= m_[axis])
                return;
            t_next[axis] += t_delta[axis];
        }
    }

private:
    size_t index(int i, int j, int k) const
    {
        return (static_cast<size_t>(k) * m_[1] + j) * m_[0] + i;
    }

    shading::Vec3 lo_, hi_;
    int m_[3] = {0, 0, 0};
    double block_size_[3] = {0.0, 0.0, 0.0};
    std::vector<float> max_;
};

} // namespace patina::volume
