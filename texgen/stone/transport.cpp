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
#include "texgen/stone/live_rows.h"
#include "texgen/stone/stone_state.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>

namespace patina::texgen::stone {

namespace {

    inline bool moist(const StoneState& st, size_t c)
    {
        return st.density[c] >= 0.5f && st.moisture[c] >= 0.5f;
    }

    /// Depth step of each stencil direction in slab s (the sign of its w component).
    std::array<int, 6> depth_steps(const SlabLattice& lat, int s)
    {
        const StencilSigns& sg = lat.signs(s);
        return {0, 0, 1, 0, sg.s[1], sg.s[2]};
    }

    /// Whether y = c + offset, depth_step layers from c's layer k, exchanges solutes with c:
    /// inside the shell's depth (the halo above and below it is a no-flux boundary, a copy of
    /// the first and last layer), an interior voxel or a connected ghost, and moist.
    inline bool solute_partner(const StoneState& st, size_t c, int k, long offset,
                               int depth_step, size_t* y)
    {
        const int ky = k + depth_step;
        *y = c + offset;
        return ky >= 0 && ky < st.lattice->grid().n_d && st.lattice->flux_partner(*y) &&
               moist(st, *y);
    }

    /// The species in the lanes of one vector (the fourth lane is unused).
    using F4 = float __attribute__((vector_size(16)));
    using Fields = std::array<float*, kSpecies>;
    static_assert(kSpecies <= 4);

    inline F4 gather(const Fields& f, size_t c)
    {
        F4 v{};
        for (int m = 0; m < kSpecies; ++m)
            v[m] = f[size_t(m)][c];
        return v;
    }

    inline void scatter(const Fields& f, size_t c, F4 v)
    {
        for (int m = 0; m < kSpecies; ++m)
            f[size_t(m)][c] = v[m];
    }

    inline F4 per_species(const std::array<double, kSpecies>& a, float scale = 1.0f)
    {
        F4 v{};
        for (int m = 0; m < kSpecies; ++m)
            v[m] = scale * float(a[size_t(m)]);
        return v;
    }

    inline float axis_metric(const std::array<std::vector<float>, 6>& w, int a, size_t c)
    {
        return a == 0 ? w[0][c] + w[3][c] + w[5][c]
             : a == 1 ? w[1][c] + w[3][c] + w[4][c]
                      : w[2][c] + w[4][c] + w[5][c];
    }

} // namespace

void transport_step(StoneState& st, bool wet, int steps)
{
    const SlabLattice& lat = *st.lattice;
    const SlabGrid& g = lat.grid();
    const auto& w = lat.weights();
    const auto& vol = lat.volume();
    const StoneParameters& prm = st.params;
    const float dt = float(st.dt * steps);
    const float alpha = float(prm.pressure_diffusivity);
    const float inv_eta = float(1.0 / prm.viscosity);

    // Concentrations in the water, C = amount / water volume fraction (phi * density), and
    // whether each moist voxel has its whole stencil of moist partners.
    // Only the active layers (and the one below, read by their stencils) change or are read.
    if (st.full_stencil.size() != g.cell_count())
        st.full_stencil.assign(g.cell_count(), 0);
    tbb::parallel_for(0, g.slab_count * g.n_d, [&](int sk) {
        const int s = sk / g.n_d, k = sk % g.n_d;
        if (k > st.active_depth[size_t(s)])
            return;
        const auto& o = lat.offsets(s);
        const std::array<int, 6> dk = depth_steps(lat, s);
        for (int j = 0; j < g.n_t; ++j) {
            const size_t row = g.index(s, 0, j, k);
            // Branch-free, so that it vectorises: every voxel, as the ghosts interpolate
            // dry voxels' concentrations too.
            const float* phi = st.porosity.data() + row;
            const float* rho = st.density.data() + row;
            for (int m = 0; m < kSpecies; ++m) {
                const float* amount = st.dissolved[m].data() + row;
                float* conc = st.concentration[m].data() + row;
                for (int i = 0; i < g.n_t; ++i) {
                    // Most voxels hold nothing: 0 / water is the amount itself (sign kept).
                    const float water = phi[i] * rho[i];
                    const float a = amount[i];
                    conc[i] = water > 0.0f ? (a != 0.0f ? a / water : a) : 0.0f;
                }
            }
            // Whether each moist voxel has its whole stencil (read only for moist voxels, so
            // rows without one are left as they are).
            int any_moist = 0;
            for (int i = 0; i < g.n_t; ++i)
                any_moist |= int(st.moisture[row + size_t(i)] >= 0.5f);
            if (!any_moist)
                continue;
            for (int i = 0; i < g.n_t; ++i) {
                const size_t c = row + size_t(i);
                bool full = moist(st, c);
                size_t y = 0;
                for (int d = 0; d < 6 && full; ++d)
                    for (int sign = -1; sign <= 1 && full; sign += 2)
                        full = solute_partner(st, c, k, sign * o[d], sign * dk[d], &y);
                st.full_stencil[c] = full;
            }
        }
    });
    std::array<float*, kSpecies> concentrations;
    for (int m = 0; m < kSpecies; ++m)
        concentrations[size_t(m)] = st.concentration[m].data();
    lat.fill_halo(concentrations, &st.active_depth);

    // Fluxes handed to ghosts (per species; one slab's halo is written by its own task only).
    for (int m = 0; m < kSpecies; ++m)
        if (st.ghost_flux[m].size() != g.cell_count())
            st.ghost_flux[m].assign(g.cell_count(), 0.0f);
    if (st.ghost_flux_depth.size() != size_t(g.slab_count))
        st.ghost_flux_depth.assign(size_t(g.slab_count), g.n_d - 1);
    Fields C, dissolved, solid_of, crust_of, ledger;
    for (int m = 0; m < kSpecies; ++m) {
        C[size_t(m)] = st.concentration[m].data();
        dissolved[size_t(m)] = st.dissolved[m].data();
        solid_of[size_t(m)] = st.solid[m].data();
        crust_of[size_t(m)] = st.crust[m].data();
        ledger[size_t(m)] = st.ghost_flux[m].data();
    }
    const F4 dm = per_species(prm.diffusivity, alpha);
    const F4 saturation = per_species(prm.saturation);
    F4 rate_cap{};
    for (int m = 0; m < kSpecies; ++m)
        rate_cap[m] = std::min(1.0f, dt * float(prm.solubility[m]));
    const float crystallise = std::min(1.0f, dt * float(prm.crystallisation_rate));
    auto exchange = [&](size_t y, bool ghost, F4 F, F4& flux) {
        if (!ghost) {
            flux += F;
        } else {
            flux += 0.5f * F;
            scatter(ledger, y, gather(ledger, y) + 0.5f * F);
        }
    };
    tbb::parallel_for(0, g.slab_count, [&](int s) {
      // Ghosts receive from the active layers and one below; clear what the last step wrote.
      int& written = st.ghost_flux_depth[size_t(s)];
      const int active = st.active_depth[size_t(s)];
      for (int k = 0; k <= std::min(g.n_d - 1, std::max(active, written)); ++k)
          for (int j = -1; j <= g.n_t; ++j)
              for (int i = -1; i <= g.n_t; i += (j < 0 || j == g.n_t) ? 1 : g.n_t + 1)
                  for (int m = 0; m < kSpecies; ++m)
                      st.ghost_flux[m][g.index(s, i, j, k)] = 0.0f;
      written = active;
      // Only moist voxels and (wet) surface voxels change: rows without either are skipped.
      thread_local LiveRows live;
      live.scan(st, s, std::min(active, g.n_d));
      for (int k = 0; k < active; ++k) {
        const auto& o = lat.offsets(s);
        const std::array<int, 6> dk = depth_steps(lat, s);
        for (int j = 0; j < g.n_t; ++j) {
            if (!live.live(j, k))
                continue;
            for (int i = 0; i < g.n_t; ++i) {
                const size_t c = g.index(s, i, j, k);
                const uint8_t f = st.flags[c];
                if (!(f & kStone))
                    continue;
                const size_t col = column_index(g, s, i, j);
                if (wet && (f & kSurface)) {
                    // Deposits turn binder into black crust; salt from the atmosphere.
                    const float dep = st.column_deposit[col];
                    const float turned = std::min(st.solid[kSoluble][c],
                                                  dt * float(prm.black_crust_rate) * dep);
                    st.solid[kSoluble][c] -= turned;
                    st.black[c] += turned;
                    if (moist(st, c))
                        st.dissolved[kSalt][c] += dt * float(prm.salt_supply) * dep;
                }
                if (!moist(st, c))
                    continue;
                const float water_c = st.porosity[c] * st.density[c];
                const float vw_c = water_c * vol[c];
                const bool full_c = st.full_stencil[c] != 0;
                // Is this a front voxel (a dry stone face neighbour)?
                bool front = false;
                for (int a = 0; a < 3 && !front; ++a)
                    for (int sign = -1; sign <= 1 && !front; sign += 2) {
                        const size_t y = c + sign * lat.axis_offset(a);
                        front = st.density[y] >= 0.5f && st.moisture[y] < 0.5f;
                    }
                // The pairs this voxel exchanges with, and what of each exchange does not
                // depend on the species: worked out once, then used for all three.
                struct Diffusive {
                    size_t y;
                    bool ghost, negative_allowed;
                    float pair_weight, porosity, water;
                };
                struct Advective {
                    size_t y;
                    bool ghost;
                    float q;
                };
                std::array<Diffusive, 12> diffusive;
                std::array<Advective, 6> advective;
                int n_diffusive = 0, n_advective = 0;
                for (int d = 0; d < 6; ++d)
                    for (int sign = -1; sign <= 1; sign += 2) {
                        size_t y = 0;
                        if (!solute_partner(st, c, k, sign * o[d], sign * dk[d], &y))
                            continue;
                        // Ghosts carry no weights, volume or stencil flag: use c's.
                        const bool ghost = vol[y] == 0.0f;
                        const float wy = ghost ? w[d][c] : w[d][y];
                        const float vy = ghost ? vol[c] : vol[y];
                        const float vw_y = st.porosity[y] * st.density[y] * vy;
                        diffusive[size_t(n_diffusive++)] = {
                            y, ghost, full_c && (ghost || st.full_stencil[y]),
                            w[d][c] + wy, std::min(st.porosity[c], st.porosity[y]),
                            std::min(vw_c, vw_y)};
                        if (d >= 3)
                            continue;
                        // Directions 0-2 are the lattice axes: the face neighbours also
                        // exchange by advection (a solute partner there is exactly a moist
                        // flux partner, the halo above and below the shell being none).
                        // Darcy flow rate (volume per time) from c into y, symmetric in the
                        // pair up to its sign; limited so a step moves at most a tenth of the
                        // smaller voxel's water.
                        const float kf = 0.5f * (st.permeability[c] + st.permeability[y]);
                        const float vd = -kf * inv_eta *
                                         ((st.pressure[y] - st.pressure[c]) +
                                          (st.head[y] - st.head[c]));
                        const float hc = axis_metric(w, d, c);
                        const float hy = ghost ? hc : axis_metric(w, d, y);
                        float q = vd * 0.25f * (vol[c] + vy) * (hc + hy);
                        const float cap = 0.1f / dt * std::min(vw_c, vw_y);
                        q = std::clamp(q, -cap, cap);
                        advective[size_t(n_advective++)] = {y, ghost, q};
                    }
                // The three species in the lanes of one vector: each lane does the scalar
                // operations in the same order, so the bits are those of a loop over species.
                const F4 cc = gather(C, c);
                F4 flux{}; // amount x volume per unit time into c
                // A flux F from y into c: whole inside the slab; half across a seam, the
                // other half taken from the ghost's sources (see the top of the file).
                for (int e = 0; e < n_diffusive; ++e) {
                    const Diffusive& x = diffusive[size_t(e)];
                    F4 kappa = dm * 0.5f * x.pair_weight * x.porosity * x.water;
                    if (!x.negative_allowed)
                        kappa = kappa < 0.0f ? F4{} : kappa;
                    exchange(x.y, x.ghost, kappa * (gather(C, x.y) - cc), flux);
                }
                for (int e = 0; e < n_advective; ++e) {
                    const Advective& x = advective[size_t(e)];
                    exchange(x.y, x.ghost,
                             std::max(0.0f, -x.q) * gather(C, x.y) - std::max(0.0f, x.q) * cc,
                             flux);
                }
                F4 amount = gather(dissolved, c) + dt * flux / vol[c];
                F4 take{};
                if (front) {
                    // Dissolution up to saturation, from the solid mineral; at most up to
                    // saturation in one step, however fast the rate.
                    const F4 room = saturation - cc;
                    take = rate_cap * (room > 0.0f ? room : F4{}) * water_c;
                    const F4 solid = gather(solid_of, c);
                    take = solid < take ? solid : take;
                    scatter(solid_of, c, solid - take);
                    amount += take;
                }
                if (!wet && (f & kSurface)) {
                    // Evaporation at the surface: the load crystallises as crust.
                    const F4 cryst = crystallise * amount;
                    scatter(crust_of, c, gather(crust_of, c) + cryst);
                    amount -= cryst;
                }
                // In place: neighbours read only the concentrations computed above.
                scatter(dissolved, c, amount);
                const float dissolved_now = take[kSoluble];
                // Decay index (§4.3.4): time moist plus binder dissolved.
                st.decay[c] += float(prm.decay_water) * dt +
                               float(prm.decay_dissolution) * dissolved_now;
            }
        }
      }
    });

    // Seams: each voxel gives up what the ghosts it feeds received, by its weight in them;
    // only the groups whose ghosts lie in their slab's active layers can have received.
    const auto& begin = lat.feed_begin();
    const auto& feeds = lat.feeds();
    const auto& feeding = lat.feeding_cells();
    tbb::parallel_for(size_t(0), st.seams.group_count(), [&](size_t q) {
        if (!st.seams.may_receive(q, st.active_depth))
            return;
        for (uint32_t e0 = st.seams.first(q); e0 < st.seams.last(q); ++e0) {
            const size_t c = feeding[e0];
            std::array<float, kSpecies> out{};
            for (uint32_t e = begin[c]; e < begin[c + 1]; ++e)
                for (int m = 0; m < kSpecies; ++m)
                    out[m] += feeds[e].weight * st.ghost_flux[m][feeds[e].ghost];
            for (int m = 0; m < kSpecies; ++m)
                st.dissolved[m][c] -= dt * out[m] / vol[c];
        }
    });
}

} // namespace patina::texgen::stone
