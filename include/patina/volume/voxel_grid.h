// patina/volume/voxel_grid.h — a world-aligned voxel grid of stone density and composition,
// sampled trilinearly.
//
// The grid covers the box [lo, hi] with nx × ny × nz voxels; voxel (i, j, k) holds its
// values at its centre lo + (i + ½, j + ½, k + ½) · (hi − lo) / (nx, ny, nz). Between centres
// the values are interpolated trilinearly (Dorsey et al. 1999 §4.1: "each slab is a trilinear
// volume"); between the outermost centres and the box faces they are held constant; outside
// the box the density is 0 (no stone).
//
// Per voxel: `density`, the stone volume fraction s in [0, 1] (§4.3.4), and three
// composition fractions in [0, 1]: black crust, iron (yellowing) and salt (efflorescence)
// (§2.3, §4.3.3). Construction allocates; lookups do not.
#pragma once

#include <patina/shading/vec.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

namespace patina::volume {

/// What a voxel holds besides its density.
enum Composition : int { kCrust = 0, kIron = 1, kSalt = 2, kCompositionCount = 3 };

class VoxelGrid {
public:
    VoxelGrid() = default;
    /// An empty grid of nx × ny × nz voxels (all zero) over [lo, hi]; lo < hi on every axis.
    VoxelGrid(int nx, int ny, int nz, shading::Vec3 lo, shading::Vec3 hi)
        : n_{nx, ny, nz}, lo_(lo), hi_(hi),
          density_(static_cast<size_t>(nx) * ny * nz, 0.0f),
          composition_(density_.size(), std::array<float, kCompositionCount>{})
    {
        for (int a = 0; a < 3; ++a)
            inv_cell_[a] = static_cast<float>(n_[a]) / (hi_[a] - lo_[a]);
    }

    int size(int axis) const { return n_[axis]; }
    shading::Vec3 lo() const { return lo_; }
    shading::Vec3 hi() const { return hi_; }
    /// Edge length of a voxel along `axis`.
    float cell(int axis) const { return 1.0f / inv_cell_[axis]; }

    size_t index(int i, int j, int k) const
    {
        return (static_cast<size_t>(k) * n_[1] + j) * n_[0] + i;
    }
    float& density_at(int i, int j, int k) { return density_[index(i, j, k)]; }
    float density_at(int i, int j, int k) const { return density_[index(i, j, k)]; }
    std::array<float, kCompositionCount>& composition_at(int i, int j, int k)
    {
        return composition_[index(i, j, k)];
    }

    /// True when p lies inside the box (faces included).
    bool contains(shading::Vec3 p) const
    {
        return p.x >= lo_.x && p.x <= hi_.x && p.y >= lo_.y && p.y <= hi_.y && p.z >= lo_.z &&
               p.z <= hi_.z;
    }

    /// Trilinear density at p; 0 outside the box.
    float density(shading::Vec3 p) const
    {
        Stencil s;
        if (!stencil(p, &s))
            return 0.0f;
        float d = 0.0f;
        for (int c = 0; c < 8; ++c)
            d += s.weight[c] * density_[s.index[c]];
        return d;
    }

    /// Trilinear density and composition at p; false (outputs zero) outside the box.
    bool sample(shading::Vec3 p, float* density, float composition[kCompositionCount]) const
    {
        *density = 0.0f;
        for (int m = 0; m < kCompositionCount; ++m)
            composition[m] = 0.0f;
        Stencil s;
        if (!stencil(p, &s))
            return false;
        for (int c = 0; c < 8; ++c) {
            *density += s.weight[c] * density_[s.index[c]];
            const auto& q = composition_[s.index[c]];
            for (int m = 0; m < kCompositionCount; ++m)
                composition[m] += s.weight[c] * q[m];
        }
        return true;
    }

    /// The largest density any point of the voxel-index box [i0, i1) × [j0, j1) × [k0, k1)
    /// (in units of voxels from lo) can interpolate: the maximum over the voxels whose
    /// centres lie within one voxel of it (trilinear weights are a convex combination).
    float max_density_over(int i0, int i1, int j0, int j1, int k0, int k1) const
    {
        const int a0 = std::max(i0 - 1, 0), a1 = std::min(i1 + 1, n_[0]);
        const int b0 = std::max(j0 - 1, 0), b1 = std::min(j1 + 1, n_[1]);
        const int c0 = std::max(k0 - 1, 0), c1 = std::min(k1 + 1, n_[2]);
        float m = 0.0f;
        for (int k = c0; k < c1; ++k)
            for (int j = b0; j < b1; ++j)
                for (int i = a0; i < a1; ++i)
                    m = std::max(m, density_[index(i, j, k)]);
        return m;
    }

private:
    struct Stencil {
        size_t index[8];
        float weight[8];
    };

    /// The eight voxels and weights of trilinear interpolation at p (false outside the box).
    bool stencil(shading::Vec3 p, Stencil* s) const
    {
        if (!contains(p) || density_.empty())
            return false;
        int i0[3], i1[3];
        float f[3];
        for (int a = 0; a < 3; ++a) {
            // Continuous index of p among the voxel centres, held at the outermost centres
            const float x = std::clamp((p[a] - lo_[a]) * inv_cell_[a] - 0.5f, 0.0f,
                                       static_cast<float>(n_[a] - 1));
            i0[a] = std::min(static_cast<int>(x), n_[a] - 1);
            i1[a] = std::min(i0[a] + 1, n_[a] - 1);
            f[a] = x - static_cast<float>(i0[a]);
        }
        for (int c = 0; c < 8; ++c) {
            const int i = (c & 1) ? i1[0] : i0[0];
            const int j = (c & 2) ? i1[1] : i0[1];
            const int k = (c & 4) ? i1[2] : i0[2];
            s->index[c] = index(i, j, k);
            s->weight[c] = ((c & 1) ? f[0] : 1.0f - f[0]) * ((c & 2) ? f[1] : 1.0f - f[1]) *
                           ((c & 4) ? f[2] : 1.0f - f[2]);
        }
        return true;
    }

    int n_[3] = {0, 0, 0};
    shading::Vec3 lo_, hi_;
    float inv_cell_[3] = {0.0f, 0.0f, 0.0f};
    std::vector<float> density_;
    std::vector<std::array<float, kCompositionCount>> composition_;
};

} // namespace patina::volume
