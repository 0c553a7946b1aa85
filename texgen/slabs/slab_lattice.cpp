#include "texgen/slabs/slab_lattice.h"

#include "core/huge_pages.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cassert>
#include <cmath>
#include <stdexcept>
#include <type_traits>

namespace patina::texgen::stone {

using Imath::V3d;

namespace {

    /// How far inside [0, 1]^3 a slab coordinate lies (distance to the nearest face).
    double inside_depth(const V3d& uvw)
    {
        return std::min({uvw.x, uvw.y, uvw.z, 1.0 - uvw.x, 1.0 - uvw.y, 1.0 - uvw.z});
    }

} // namespace

SlabGrid::SlabGrid(int tangential, int depth, int slabs)
    : n_t(tangential), n_d(depth), slab_count(slabs), sx(tangential + 2), sy(tangential + 2),
      sz(depth + 2), slab_size(size_t(sx) * sy * sz)
{
    if (tangential < 2 || depth < 2 || slabs < 1)
        throw std::runtime_error(fmt::format("slab lattice: need at least 2 voxels along each "
                                             "axis and one slab (got {} x {} x {}, {} slabs)",
                                             tangential, tangential, depth, slabs));
}

std::array<GhostSource, 8> trilinear_sources(const SlabGrid& g, const SlabPoint& p,
                                             bool clamp_to_interior)
{
    const int n[3] = {g.n_t, g.n_t, g.n_d};
    int i0[3];
    double f[3];
    for (int a = 0; a < 3; ++a) {
        // Continuous voxel coordinate: centres at integers.
        double x = p.uvw[a] * n[a] - 0.5;
        const double lo = clamp_to_interior ? 0.0 : -1.0;
        const double hi = clamp_to_interior ? n[a] - 1.0 : double(n[a]);
        x = std::clamp(x, lo, hi);
        i0[a] = std::min(int(std::floor(x)), int(hi) - 1);
        f[a] = x - i0[a];
    }
    std::array<GhostSource, 8> out;
    for (int c = 0; c < 8; ++c) {
        const int di = c & 1, dj = (c >> 1) & 1, dk = (c >> 2) & 1;
        out[c].cell = uint32_t(g.index(p.slab, i0[0] + di, i0[1] + dj, i0[2] + dk));
        out[c].weight = float((di ? f[0] : 1 - f[0]) * (dj ? f[1] : 1 - f[1]) *
                              (dk ? f[2] : 1 - f[2]));
    }
    return out;
}

SlabLattice::SlabLattice(const SlabShell& shell, int n_t, int n_d)
    : shell_(shell), grid_(n_t, n_d, int(shell.slabs.size())), locator_(shell_.slabs)
{
    const size_t cells = grid_.cell_count();
    for (auto& w : weights_)
        w.assign(cells, 0.0f);
    volume_.assign(cells, 0.0f);
    position_.assign(cells, Imath::V3f(0.0f));
    signs_.resize(size_t(grid_.slab_count));
    offsets_.resize(size_t(grid_.slab_count));

    // Per voxel: lattice vectors from the Jacobian, the stencil weights, volume, centre.
    tbb::parallel_for(0, grid_.slab_count, [&](int s) {
        const SlabCorners& c = shell_.slabs[size_t(s)];
        V3d du, dv, dw;
        slab_derivatives(c, V3d(0.5), du, dv, dw);
        const StencilSigns signs = shorter_diagonals(du / n_t, dv / n_t, dw / n_d);
        signs_[size_t(s)] = signs;
        const long ax[3] = {1, grid_.sx, long(grid_.sx) * grid_.sy};
        offsets_[size_t(s)] = {ax[0], ax[1], ax[2], ax[0] + signs.s[0] * ax[1],
                               ax[1] + signs.s[1] * ax[2], ax[0] + signs.s[2] * ax[2]};
        for (int k = 0; k < n_d; ++k)
            for (int j = 0; j < n_t; ++j)
                for (int i = 0; i < n_t; ++i) {
                    const V3d uvw = grid_.uvw(i, j, k);
                    slab_derivatives(c, uvw, du, dv, dw);
                    const V3d lu = du / n_t, lv = dv / n_t, lw = dw / n_d;
                    const StencilWeights w = thirteen_point_weights(lu, lv, lw, signs);
                    const size_t cell = grid_.index(s, i, j, k);
                    for (int d = 0; d < 6; ++d)
                        weights_[d][cell] = float(w.c[d]);
                    volume_[cell] = float(std::abs(lu.cross(lv).dot(lw)));
                    const V3d p = slab_to_world(c, uvw);
                    position_[cell] = Imath::V3f(float(p.x), float(p.y), float(p.z));
                }
    });

    // Ghosts: halo cells beside the slab's four sides, at every depth of the slab.
    for (int s = 0; s < grid_.slab_count; ++s)
        for (int k = 0; k < n_d; ++k)
            for (int j = -1; j <= n_t; ++j)
                for (int i = -1; i <= n_t; ++i)
                    if (i < 0 || j < 0 || i >= n_t || j >= n_t)
                        ghost_cell_.push_back(uint32_t(grid_.index(s, i, j, k)));
    ghost_sources_.resize(ghost_cell_.size());
    ghost_weights_used_.resize(ghost_cell_.size());
    for (uint32_t c = 0; c < 8; ++c)
        block_offset_[c] = (c & 1) + ((c >> 1) & 1) * uint32_t(grid_.sx) +
                           ((c >> 2) & 1) * uint32_t(grid_.sx * grid_.sy);
    std::vector<char> connected(ghost_cell_.size(), 1);
    const int per_slab = int(ghost_cell_.size()) / grid_.slab_count;
    tbb::parallel_for(size_t(0), ghost_cell_.size(), [&](size_t g) {
        const int s = int(g) / per_slab;
        const size_t local = ghost_cell_[g] - size_t(s) * grid_.slab_size;
        const int i = int(local % grid_.sx) - 1, j = int((local / grid_.sx) % grid_.sy) - 1,
                  k = int(local / (size_t(grid_.sx) * grid_.sy)) - 1;
        const V3d p = slab_to_world(shell_.slabs[size_t(s)], grid_.uvw(i, j, k));
        // A side ghost lies half a voxel inside the slab across that side: try it first and
        // search the grid only for corner ghosts or where the neighbour does not hold it.
        std::optional<SlabPoint> at;
        const int side = j < 0 ? 0 : i >= n_t ? 1 : j >= n_t ? 2 : 3;
        const bool corner = (i < 0 || i >= n_t) && (j < 0 || j >= n_t);
        const int across = corner ? -1 : shell_.neighbours[size_t(s)][size_t(side)];
        V3d uvw;
        if (across >= 0 && world_to_slab(shell_.slabs[size_t(across)], p, uvw) &&
            inside_depth(uvw) >= 0.25 / std::max(n_t, n_d))
            at = SlabPoint{across, uvw};
        else
            at = locator_.locate(p, 1e-6);
        if (at && at->slab == s)
            at.reset();
        if (!at) {
            connected[g] = 0;
            at = SlabPoint{s, grid_.uvw(i, j, k)};
        }
        const std::array<GhostSource, 8> sources = trilinear_sources(grid_, *at, true);
        GhostBlock& block = ghost_sources_[g];
        block.base = sources[0].cell;
        uint8_t used = 0;
        for (size_t c = 0; c < 8; ++c) {
            assert(sources[c].cell == block.base + block_offset_[c]);
            block.weight[c] = sources[c].weight;
            used |= uint8_t(uint8_t(sources[c].weight != 0.0f) << c);
        }
        ghost_weights_used_[g] = used;
    });
    unconnected_ = size_t(std::count(connected.begin(), connected.end(), 0));
    ghost_source_row_.resize(ghost_sources_.size());
    for (size_t g = 0; g < ghost_sources_.size(); ++g)
        ghost_source_row_[g] = ghost_sources_[g].base / uint32_t(grid_.sx);
    // The source layers of each ghost layer: those of rows r and r + sy of every ghost (its
    // sources lie in rows r, r + 1, r + sy and r + sy + 1, and r + 1 in r's layer).
    const size_t ghost_layers = size_t(grid_.slab_count) * size_t(n_d);
    const size_t per_ghost_layer = ghost_cell_.size() / ghost_layers;
    ghost_layer_begin_.assign(ghost_layers + 1, 0);
    for (size_t q = 0; q < ghost_layers; ++q) {
        const size_t first = ghost_layer_sources_.size();
        for (size_t g = q * per_ghost_layer; g < (q + 1) * per_ghost_layer; ++g)
            for (const uint32_t below : {0, 1}) {
                const uint32_t layer = ghost_source_row_[g] / uint32_t(grid_.sy) + below;
                if (std::find(ghost_layer_sources_.begin() + long(first),
                              ghost_layer_sources_.end(), layer) == ghost_layer_sources_.end())
                    ghost_layer_sources_.push_back(layer);
            }
        ghost_layer_begin_[q + 1] = uint32_t(ghost_layer_sources_.size());
    }

    // Flux partners, and the feeds of every voxel (which connected ghosts it is a source of).
    flux_partner_.assign(cells, 0);
    for (int s = 0; s < grid_.slab_count; ++s)
        for (int k = 0; k < n_d; ++k)
            for (int j = 0; j < n_t; ++j)
                for (int i = 0; i < n_t; ++i)
                    flux_partner_[grid_.index(s, i, j, k)] = 1;
    // Only sources of nonzero weight are fed: one of weight 0 would get +-0 back, which
    // leaves its sum as it is (see fill_halo and transport.cpp).
    feed_begin_.assign(cells + 1, 0);
    for (size_t g = 0; g < ghost_cell_.size(); ++g)
        if (connected[g]) {
            flux_partner_[ghost_cell_[g]] = 1;
            for (size_t c = 0; c < 8; ++c)
                if (ghost_weights_used_[g] >> c & 1u)
                    ++feed_begin_[ghost_sources_[g].base + block_offset_[c] + 1];
        }
    for (size_t c = 0; c < cells; ++c)
        feed_begin_[c + 1] += feed_begin_[c];
    feeds_.resize(feed_begin_[cells]);
    std::vector<uint32_t> fill(feed_begin_.begin(), feed_begin_.end() - 1);
    for (size_t g = 0; g < ghost_cell_.size(); ++g)
        if (connected[g])
            for (size_t c = 0; c < 8; ++c) {
                if (!(ghost_weights_used_[g] >> c & 1u))
                    continue;
                const uint32_t cell = ghost_sources_[g].base + block_offset_[c];
                feeds_[fill[cell]++] = Feed{ghost_cell_[g], ghost_sources_[g].weight[c]};
            }
    // Every step reads these at a layer's distance apart (core/huge_pages.h).
    for (auto& w : weights_)
        advise_huge_pages(w);
    advise_huge_pages(volume_);
    advise_huge_pages(flux_partner_);
    advise_huge_pages(feed_begin_);
    advise_huge_pages(feeds_);
    advise_huge_pages(ghost_sources_);
    advise_huge_pages(ghost_weights_used_);
    advise_huge_pages(ghost_cell_);
    advise_huge_pages(ghost_source_row_);
}

void SlabLattice::fill_halo(float* field, const std::vector<int>* active,
                            HaloChanges* changes) const
{
    fill_halo(std::span<float* const>(&field, 1), active, changes);
}

void SlabLattice::fill_halo(std::span<float* const> fields, const std::vector<int>* active,
                            HaloChanges* changes) const
{
    // Ghosts are stored by slab, then layer: with `active`, only the ghosts of the layers
    // read this step (k <= active depth) are visited at all. Several fields share one walk
    // over the ghosts' sources (each field's sums in the same order as alone).
    constexpr size_t kMaxFields = 4;
    if (fields.size() > kMaxFields) {
        // Each group of fields starts from the same changes (a fill clears them).
        const HaloChanges before = changes ? *changes : HaloChanges{};
        for (size_t f = 0; f < fields.size(); f += kMaxFields) {
            HaloChanges group = before;
            fill_halo(fields.subspan(f, std::min(kMaxFields, fields.size() - f)), active,
                      changes ? &group : nullptr);
            if (changes)
                *changes = std::move(group);
        }
        return;
    }
    const size_t n = fields.size();
    if (n == 0)
        return;
    const size_t per_slab = ghost_cell_.size() / size_t(grid_.slab_count);
    const size_t per_layer = per_slab / size_t(grid_.n_d);
    const size_t rows = grid_.cell_count() / size_t(grid_.sx);
    if (changes && changes->row_changed.size() != rows) {
        changes->row_changed.assign(rows, 0);
        changes->layer_changed.assign(rows / size_t(grid_.sy), 0);
        changes->filled_layers.assign(size_t(grid_.slab_count), 0);
    }
    // A ghost's sources lie in 4 rows: (j, k), (j + 1, k), (j, k + 1) and (j + 1, k + 1).
    const size_t sy = size_t(grid_.sy);
    const uint8_t* changed = changes ? changes->row_changed.data() : nullptr;
    // Per slab: whether a ghost of its first layer got a new value (the halo above copies
    // the whole first layer, ghosts included).
    std::vector<uint8_t> first_layer_filled(size_t(grid_.slab_count), 0);
    tbb::parallel_for(0, grid_.slab_count, [&](int slab) {
        const int layers =
            active ? std::clamp((*active)[size_t(slab)] + 1, 0, grid_.n_d) : grid_.n_d;
        const size_t begin = size_t(slab) * per_slab;
        // Layers whose ghosts hold the last fill's values (the others are all refilled).
        const int current = changes ? std::min(layers, changes->filled_layers[size_t(slab)]) : 0;
        // The field count as a constant, so the sums stay in registers.
        auto fill = [&]<size_t N>(std::integral_constant<size_t, N>) {
            // Only the sources of nonzero weight: w x = +-0 for w = 0 (the fields are
            // finite), and a sum that starts at +0 is never -0, so adding +-0 leaves it as
            // it is. (A third of the weights are 0, each source another cache line.)
            auto interpolate = [&](size_t g) {
                const GhostBlock& block = ghost_sources_[g];
                std::array<float, N> v{};
                for (uint32_t used = ghost_weights_used_[g]; used; used &= used - 1) {
                    const size_t c = size_t(std::countr_zero(used));
                    for (size_t f = 0; f < N; ++f)
                        v[f] += block.weight[c] * fields[f][block.base + block_offset_[c]];
                }
                for (size_t f = 0; f < N; ++f)
                    fields[f][ghost_cell_[g]] = v[f];
            };
            for (int k = 0; k < layers; ++k) {
                const size_t first = begin + size_t(k) * per_layer, last = first + per_layer;
                if (k >= current) {
                    for (size_t g = first; g < last; ++g)
                        interpolate(g);
                    first_layer_filled[size_t(slab)] |= uint8_t(k == 0);
                    continue;
                }
                // A current ghost layer whose source layers are all unchanged stays; in the
                // others, only the ghosts with a source in a changed row are refilled.
                if (!ghost_sources_changed(slab, k, *changes))
                    continue;
                for (size_t g = first; g < last; ++g) {
                    // Sources 0-1 lie in row r, 2-3 in r + 1, 4-5 in r + sy, 6-7 in
                    // r + sy + 1: only the rows of the sources it uses.
                    const size_t r = ghost_source_row_[g];
                    const uint32_t used = ghost_weights_used_[g];
                    if ((changed[r] & int((used & 0x03u) != 0)) |
                        (changed[r + 1] & int((used & 0x0cu) != 0)) |
                        (changed[r + sy] & int((used & 0x30u) != 0)) |
                        (changed[r + sy + 1] & int((used & 0xc0u) != 0))) {
                        interpolate(g);
                        first_layer_filled[size_t(slab)] |= uint8_t(k == 0);
                    }
                }
            }
        };
        switch (n) {
        case 1: fill(std::integral_constant<size_t, 1>{}); break;
        case 2: fill(std::integral_constant<size_t, 2>{}); break;
        case 3: fill(std::integral_constant<size_t, 3>{}); break;
        default: fill(std::integral_constant<size_t, 4>{}); break;
        }
        if (changes)
            changes->filled_layers[size_t(slab)] = layers;
    });
    const SlabGrid& g = grid_;
    tbb::parallel_for(0, g.slab_count, [&](int s) {
        // The halo above copies the first layer: unless it or its ghosts changed (every
        // change of it is marked and seen here: the first layer is always filled), the copy
        // is already there. The halo below is copied only while the layers reach it.
        const bool top = !changes || first_layer_filled[size_t(s)] ||
                         changes->layer_changed[g.layer(s, 0)];
        const bool bottom = !active || (*active)[size_t(s)] >= g.n_d - 1;
        for (float* field : fields)
            for (int j = -1; j <= g.n_t; ++j)
                for (int i = -1; i <= g.n_t; ++i) {
                    if (top)
                        field[g.index(s, i, j, -1)] = field[g.index(s, i, j, 0)];
                    if (bottom)
                        field[g.index(s, i, j, g.n_d)] = field[g.index(s, i, j, g.n_d - 1)];
                }
        // The marks this fill has seen: a marked row's layer is marked too, so only the rows
        // of marked layers are cleared.
        if (changes)
            for (int k = -1; k <= g.n_d; ++k) {
                uint8_t& layer = changes->layer_changed[g.layer(s, k)];
                if (!layer)
                    continue;
                layer = 0;
                uint8_t* rows = changes->row_changed.data() + g.row(s, -1, k);
                std::fill(rows, rows + g.sy, uint8_t(0));
            }
    });
}

bool SlabLattice::ghost_sources_changed(int slab, int k, const HaloChanges& changes) const
{
    const size_t q = size_t(slab) * size_t(grid_.n_d) + size_t(k);
    for (uint32_t e = ghost_layer_begin_[q]; e < ghost_layer_begin_[q + 1]; ++e)
        if (changes.layer_changed[ghost_layer_sources_[e]])
            return true;
    return false;
}

std::array<GhostSource, 8> SlabLattice::ghost_sources(size_t ghost_cell) const
{
    // The ghost's index: slab, layer, then its place on the layer's ring (rows j = -1 and
    // j = n_t whole, the rows between by their two ends), as the constructor stores them.
    const int n_t = grid_.n_t;
    const size_t s = ghost_cell / grid_.slab_size;
    const size_t local = ghost_cell % grid_.slab_size;
    const int i = int(local % size_t(grid_.sx)) - 1;
    const int j = int((local / size_t(grid_.sx)) % size_t(grid_.sy)) - 1;
    const size_t k = local / (size_t(grid_.sx) * size_t(grid_.sy)) - 1;
    const size_t per_layer = 4 * size_t(n_t) + 4;
    size_t ring;
    if (j < 0)
        ring = size_t(i + 1);
    else if (j < n_t)
        ring = size_t(n_t + 2) + 2 * size_t(j) + (i < 0 ? 0 : 1);
    else
        ring = size_t(n_t + 2) + 2 * size_t(n_t) + size_t(i + 1);
    const size_t g = (s * size_t(grid_.n_d) + k) * per_layer + ring;
    assert(ghost_cell_[g] == ghost_cell);
    std::array<GhostSource, 8> sources;
    for (size_t c = 0; c < 8; ++c)
        sources[c] = {ghost_sources_[g].base + block_offset_[c], ghost_sources_[g].weight[c]};
    return sources;
}

float SlabLattice::sample(const float* field, const SlabPoint& p) const
{
    float v = 0.0f;
    for (const GhostSource& s : trilinear_sources(grid_, p, false))
        v += s.weight * field[s.cell];
    return v;
}

} // namespace patina::texgen::stone
