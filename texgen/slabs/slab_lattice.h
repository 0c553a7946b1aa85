// The voxels of a slab shell: n_t x n_t x n_d voxels per slab on the (u, v, w) lattice, each
// slab stored with a one-voxel halo so the 13-point stencil (§4.3.5) reads its neighbours
// without branches. Halo voxels across a slab's side are ghosts: their world position (the
// slab's lattice extrapolated by one voxel) is located in the neighbouring slab, and the
// ghost is the trilinear interpolation of that slab's voxels, so slabs are connected
// whatever their relative orientation (the valence of a base vertex varies). A ghost whose
// position lies in no slab (the shell's rim at a sharp edge) copies its own slab's nearest
// voxel, and the halo above and below the shell copies the first and last layer (no flux
// through the inner face; the outer face lies in the air).
#pragma once

#include "texgen/slabs/slab_mapping.h"
#include "texgen/slabs/slab_shell.h"
#include "texgen/slabs/stencil.h"

#include <Imath/ImathVec.h>

#include <array>
#include <cstdint>
#include <span>
#include <vector>

namespace patina::texgen::stone {

/// Index arithmetic of the haloed voxel arrays.
struct SlabGrid {
    int n_t = 0;            ///< voxels along u and v
    int n_d = 0;            ///< voxels along w (depth)
    int slab_count = 0;
    int sx = 0, sy = 0, sz = 0;  ///< haloed extents: n_t + 2, n_t + 2, n_d + 2
    size_t slab_size = 0;

    SlabGrid() = default;
    SlabGrid(int tangential, int depth, int slabs);
    /// Cell (i, j, k) of slab s, with i, j in [-1, n_t] and k in [-1, n_d].
    size_t index(int s, int i, int j, int k) const
    {
        return size_t(s) * slab_size + (size_t(k + 1) * sy + size_t(j + 1)) * sx + size_t(i + 1);
    }
    /// Layer k of slab s among the layers of the haloed grid (cell / (sx sy)), and row (j, k)
    /// among its rows (cell / sx), without dividing.
    size_t layer(int s, int k) const { return size_t(s) * size_t(sz) + size_t(k + 1); }
    size_t row(int s, int j, int k) const { return layer(s, k) * size_t(sy) + size_t(j + 1); }
    size_t cell_count() const { return slab_size * size_t(slab_count); }
    size_t voxel_count() const { return size_t(n_t) * n_t * n_d * slab_count; }
    /// Slab coordinates of the centre of voxel (i, j, k) (outside [0,1] for halo cells).
    Imath::V3d uvw(int i, int j, int k) const
    {
        return Imath::V3d((i + 0.5) / n_t, (j + 0.5) / n_t, (k + 0.5) / n_d);
    }
};

/// What lets a halo fill skip ghosts that would get the value they hold: the rows of the
/// grid (cell / sx) written with new values since the field's last fill, and per slab the
/// ghost layers that fill made current. Whoever writes the field marks the rows it changes;
/// a write that is not marked must be followed by a fill without HaloChanges (all ghosts).
struct HaloChanges {
    std::vector<uint8_t> row_changed;    ///< per row of the haloed grid
    std::vector<uint8_t> layer_changed;  ///< per layer of the haloed grid (row / sy)
    std::vector<int> filled_layers;      ///< per slab: ghosts of layers [0, this) are current

    /// Mark the row of `cell` (sized by the first fill; before it, every ghost is filled).
    void mark(size_t cell, const SlabGrid& g)
    {
        if (row_changed.empty())
            return;
        const size_t row = cell / size_t(g.sx);
        row_changed[row] = 1;
        layer_changed[row / size_t(g.sy)] = 1;
    }
    /// The same for row (j, k) of slab s, without the divisions (a write-back marks a row
    /// at a time).
    void mark_row(int s, int j, int k, const SlabGrid& g)
    {
        if (row_changed.empty())
            return;
        row_changed[g.row(s, j, k)] = 1;
        layer_changed[g.layer(s, k)] = 1;
    }
};

/// One source of a ghost cell.
struct GhostSource {
    uint32_t cell = 0;
    float weight = 0.0f;
};

class SlabLattice {
public:
    /// Lay out `shell` with n_t voxels along each slab edge and n_d through its depth.
    SlabLattice(const SlabShell& shell, int n_t, int n_d);

    const SlabGrid& grid() const { return grid_; }
    const std::vector<SlabCorners>& slabs() const { return shell_.slabs; }
    const SlabShell& shell() const { return shell_; }
    const SlabLocator& locator() const { return locator_; }

    /// Per cell (interior voxels; 0 in the halo): the six stencil weights (SoA), the voxel's
    /// volume |det J| / (n_t^2 n_d), and its centre in world space.
    const std::array<std::vector<float>, 6>& weights() const { return weights_; }
    const std::vector<float>& volume() const { return volume_; }
    const std::vector<Imath::V3f>& position() const { return position_; }
    /// Per slab: the stencil's diagonal signs and the cell offsets of the six directions.
    const StencilSigns& signs(int slab) const { return signs_[size_t(slab)]; }
    const std::array<long, 6>& offsets(int slab) const { return offsets_[size_t(slab)]; }
    /// Axis offsets (1, sx, sx*sy): the same in every slab.
    long axis_offset(int a) const { return a == 0 ? 1 : a == 1 ? grid_.sx : long(grid_.sx) * grid_.sy; }

    /// Fill the halo of `field` (cell_count floats) from the neighbours (see above). With
    /// `active` (layers per slab that a step reads), halo cells deeper than their slab's
    /// active layers are left as they are.
    /// With `changes`, ghosts that are current (see HaloChanges) are skipped, and `changes`
    /// is updated to this fill.
    void fill_halo(float* field, const std::vector<int>* active = nullptr,
                   HaloChanges* changes = nullptr) const;
    /// The same for several fields at once (one walk over the ghosts' sources; `changes`
    /// covers them all).
    void fill_halo(std::span<float* const> fields, const std::vector<int>* active = nullptr,
                   HaloChanges* changes = nullptr) const;
    /// Whether `changes` marks a row in a layer that the sources of slab s's ghosts of
    /// layer k lie in (before a fill clears the marks).
    bool ghost_sources_changed(int slab, int k, const HaloChanges& changes) const;
    /// Ghost cells whose position lies in no other slab (copied from their own slab).
    size_t unconnected_ghosts() const { return unconnected_; }

    /// Whether a cell may exchange fluxes: interior voxels and ghosts located in another
    /// slab; not the halo above and below the shell nor unconnected ghosts (no-flux).
    bool flux_partner(size_t cell) const { return flux_partner_[cell] != 0; }
    const uint8_t* flux_partner_data() const { return flux_partner_.data(); }
    /// The ghosts a voxel feeds (CSR by cell): what a flux into a ghost delivers to its
    /// sources, so fluxes across slab seams conserve mass (transport.cpp). Only the ghosts
    /// it is a source of nonzero weight of: the others would hand it +-0.
    struct Feed {
        uint32_t ghost;
        float weight;
    };
    const std::vector<uint32_t>& feed_begin() const { return feed_begin_; }
    const std::vector<Feed>& feeds() const { return feeds_; }
    /// The 8 voxels a ghost cell (a halo cell beside a slab's side) interpolates, which its
    /// feeds go to, with their weights (0 for most where slabs meet edge to edge).
    std::array<GhostSource, 8> ghost_sources(size_t ghost_cell) const;

    /// Trilinear sample of a field at slab point `p` (halo filled), between voxel centres.
    float sample(const float* field, const SlabPoint& p) const;

private:
    SlabShell shell_;
    SlabGrid grid_;
    SlabLocator locator_;
    std::array<std::vector<float>, 6> weights_;
    std::vector<float> volume_;
    std::vector<Imath::V3f> position_;
    std::vector<StencilSigns> signs_;
    std::vector<std::array<long, 6>> offsets_;
    std::vector<uint32_t> ghost_cell_;
    /// A ghost's sources: the 2 x 2 x 2 voxels from `base` in trilinear_sources' order (i
    /// fastest), with their weights; 36 bytes a ghost where 8 (cell, weight) pairs take 64,
    /// and the halo fills stream them every step.
    struct GhostBlock {
        uint32_t base = 0;
        std::array<float, 8> weight{};
    };
    std::array<uint32_t, 8> block_offset_{};
    std::vector<GhostBlock> ghost_sources_;
    /// Per ghost: bit c set where its weight c is not 0 (a ghost in line with its neighbour's
    /// voxel centres along an axis has half its weights 0: 5.44 of 8 are used on average on
    /// the paper-size grid).
    std::vector<uint8_t> ghost_weights_used_;
    /// Per ghost: the row (cell / sx) of its first source, what a fill with HaloChanges
    /// checks before it reads the block (no division, 4 bytes a ghost streamed).
    std::vector<uint32_t> ghost_source_row_;
    /// Per ghost layer (slab * n_d + k): the layers of the haloed grid (row / sy) its ghosts'
    /// sources lie in (CSR), so that a fill skips a layer whose sources did not change.
    std::vector<uint32_t> ghost_layer_begin_;
    std::vector<uint32_t> ghost_layer_sources_;
    size_t unconnected_ = 0;
    std::vector<uint8_t> flux_partner_;
    std::vector<uint32_t> feed_begin_;
    std::vector<Feed> feeds_;
};

/// Trilinear interpolation weights of the voxel centres of a slab around (u, v, w), clamped
/// to the interior voxels; used for ghosts and for sampling.
std::array<GhostSource, 8> trilinear_sources(const SlabGrid& grid, const SlabPoint& p,
                                             bool clamp_to_interior);

} // namespace patina::texgen::stone
