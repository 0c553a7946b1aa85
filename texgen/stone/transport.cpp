// Dissolution at the front and convective diffusion of the dissolved minerals (Dorsey et al.
// 1999 §4.3.3), and the crusts they leave on the surface.
//
// Dissolution: at a front voxel (moist, beside a dry stone voxel) dC_i/dt = k_i (m_i - C_i),
// drawing on the solid mineral and stopping at saturation m_i. (The paper prints
// -k_i (m_i - C_i), which would precipitate below saturation; its own text, "the quantity m_i
// cuts off dissolution upon saturation", needs the + sign.)
//
// Transport: d(phi C)/dt + v . grad(phi C) = div(phi D grad C) in conservative form between
// pairs of moist voxels: the 13-point stencil's weight for a direction (the mean of both
// ends' weights) times the smaller water volume of the pair is the coupling, and advection
// by Darcy's velocity is upwinded across each face; a flux leaving one voxel enters the
// other. Two things keep this explicit step stable (without them the marble statue's salt
// grew to 1e38 after 20 cycles):
// - The solute's diffusivity in the pores is D = alpha D_i phi (Archie's law with exponent
//   1; the paper gives no value): it diffuses at most as fast as the pressure, whose step
//   limit dt already covers (simulation.cpp), and in practice much slower, as solutes do.
//   With the smaller water volume of the pair, no voxel's rate exceeds alpha D_i phi_max
//   times its stencil weights, however little water it holds.
// - The 13-point stencil has negative weights (§4.3.5); they are part of a consistent
//   Laplacian only when the whole stencil is there. Where a voxel's stencil is cut by the
//   dry front, the surface or the shell's ends, a negative coupling would pump solute
//   uphill without bound (two moist voxels joined only by a negative weight), so couplings
//   touching such a voxel are clamped to >= 0.
// Across a slab seam the partner is a ghost (an interpolation of the neighbour slab's
// voxels) and both slabs see the exchange: each takes half of its own flux, and the ghost
// hands the opposite half to its source voxels with the interpolation weights. So the total
// is conserved exactly everywhere; the halo above and below the shell is no-flux.
//
// Crusts: in dry phases the water evaporating at the surface leaves its dissolved load as a
// crust (efflorescence for salts, yellowing for iron, case hardening for the binder); in wet
// phases deposits (the deposit map: soot, sulphur) turn the binder at the surface into a
// black crust, and salt may be brought in from the atmosphere.
#include "core/huge_pages.h"
#include "texgen/stone_rows/live_rows.h"
#include "texgen/stone/stone_state.h"
#include "texgen/stone_rows/transport_rows.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cmath>

namespace patina::texgen::stone {

void transport_step(StoneState& st, bool wet, int steps)
{
    const SlabLattice& lat = *st.lattice;
    const SlabGrid& g = lat.grid();
    const auto& vol = lat.volume();
    const float dt = float(st.dt * steps);
    if (st.full_stencil.size() != g.cell_count()) {
        st.full_stencil.assign(g.cell_count(), 0);
        advise_huge_pages(st.full_stencil);
    }
    // Fluxes handed to ghosts (per species; one slab's halo is written by its own task only).
    for (int m = 0; m < kSpecies; ++m)
        if (st.ghost_flux[m].size() != g.cell_count()) {
            st.ghost_flux[m].assign(g.cell_count(), 0.0f);
            advise_huge_pages(st.ghost_flux[m]);
        }
    if (st.ghost_hit.size() != g.cell_count()) {
        st.ghost_hit.assign(g.cell_count(), 0);
        st.seam_mark.assign(g.cell_count(), 0);
        advise_huge_pages(st.ghost_hit);
        advise_huge_pages(st.seam_mark);
        st.ghost_hits.assign(size_t(g.slab_count), {});
        st.seam_due.assign(size_t(g.slab_count), {});
    }
    if (st.concentration_zero.size() != g.cell_count() / size_t(g.sx))
        st.concentration_zero.assign(g.cell_count() / size_t(g.sx), 0);
    const TransportRows rows(st, wet, dt);

    // Concentrations in the water, C = amount / water volume fraction (phi * density), and
    // whether each moist voxel has its whole stencil of moist partners.
    // Only the active layers (and the one below, read by their stencils) change or are read.
    tbb::parallel_for(0, g.slab_count * g.n_d, [&](int sk) {
        const int s = sk / g.n_d, k = sk % g.n_d;
        if (k > st.active_depth[size_t(s)])
            return;
        for (int j = 0; j < g.n_t; ++j) {
            const size_t row = g.index(s, 0, j, k);
            uint8_t& zero = st.concentration_zero[g.row(s, j, k)];
            for (size_t m = 0; m < kSpecies; ++m) {
                const uint8_t bit = uint8_t(1u << m);
                const auto done = rows.concentration_row(row, m, (zero & bit) != 0);
                zero = done.zero ? uint8_t(zero | bit) : uint8_t(zero & ~bit);
                if (done.changed)
                    st.concentration_halo.mark_row(s, j, k, g);
            }
            // Whether each moist voxel has its whole stencil (read only for moist voxels, so
            // rows without one are left as they are).
            int any_moist = 0;
            for (int i = 0; i < g.n_t; ++i)
                any_moist |= int(st.moisture[row + size_t(i)] >= 0.5f);
            if (any_moist)
                rows.full_stencil_row(s, j, k);
        }
    });
    std::array<float*, kSpecies> concentrations;
    for (int m = 0; m < kSpecies; ++m)
        concentrations[size_t(m)] = st.concentration[m].data();
    lat.fill_halo(concentrations, &st.active_depth, &st.concentration_halo);

    tbb::parallel_for(0, g.slab_count, [&](int s) {
        // Clear what the ghosts received in the last step.
        for (const uint32_t y : st.ghost_hits[size_t(s)]) {
            for (int m = 0; m < kSpecies; ++m)
                st.ghost_flux[m][y] = 0.0f;
            st.ghost_hit[y] = 0;
        }
        st.ghost_hits[size_t(s)].clear();
        const int active = st.active_depth[size_t(s)];
        // Only moist voxels and surface voxels under deposits change: rows without either
        // are skipped.
        thread_local LiveRows live;
        live.scan(st, s, std::min(active, g.n_d), rows.deposits);
        for (int k = 0; k < active; ++k)
            for (int j = 0; j < g.n_t; ++j)
                if (live.live(j, k))
                    rows.transport_row(s, j, k);
    });

    // Seams: each voxel gives up what the ghosts it feeds received, by its weight in them.
    // Only the sources of the ghosts that received can give anything up, and only those with
    // a weight (a source of weight 0 adds +-0 to its sum: no change, see below): they are
    // marked (each once, whichever slab's ghost marks it first) and listed by the slab that
    // did.
    const auto& begin = lat.feed_begin();
    const auto& feeds = lat.feeds();
    tbb::parallel_for(0, g.slab_count, [&](int s) {
        std::vector<uint32_t>& due = st.seam_due[size_t(s)];
        due.clear();
        for (const uint32_t y : st.ghost_hits[size_t(s)])
            for (const GhostSource& source : lat.ghost_sources(y))
                if (source.weight != 0.0f &&
                    std::atomic_ref<uint8_t>(st.seam_mark[source.cell])
                            .exchange(1, std::memory_order_relaxed) == 0)
                    due.push_back(source.cell);
    });
    tbb::parallel_for(0, g.slab_count, [&](int s) {
        // Each voxel sums over the ghosts it feeds (SlabLattice::feeds: those it is a source
        // of nonzero weight of) that received, in order. The others hold +0, and adding
        // w x +0 (w >= 0) or 0 x f = +-0 leaves a sum that starts at +0 as it is: it is
        // never -0, as x + y is +0 when x = -y; and a voxel whose sum stays +0 would keep
        // its amount. In cell order, which walks the neighbour slabs' arrays
        // forwards rather than at random.
        std::vector<uint32_t>& due = st.seam_due[size_t(s)];
        std::sort(due.begin(), due.end());
        for (const uint32_t c : due) {
            st.seam_mark[c] = 0;
            std::array<float, kSpecies> out{};
            for (uint32_t e = begin[c]; e < begin[c + 1]; ++e) {
                const uint32_t y = feeds[e].ghost;
                if (!st.ghost_hit[y])
                    continue;
                for (int m = 0; m < kSpecies; ++m)
                    out[m] += feeds[e].weight * st.ghost_flux[m][y];
            }
            for (int m = 0; m < kSpecies; ++m)
                st.dissolved[m][c] -= dt * out[m] / vol[c];
        }
    });
}

} // namespace patina::texgen::stone
