// Row kernels of the transport step; the model and its conservation are described at the top
// of transport.cpp, which drives them. Here only how a row is worked: kLanes voxels at a time,
// each lane the scalar code of its voxel (std::min, std::max and std::clamp spelled as the
// selects they are, so that even the sign of a zero is kept).
#include "texgen/stone_rows/transport_rows.h"

#include "texgen/stone_rows/lanes.h"

#include <algorithm>
#include <bit>

namespace patina::texgen::stone {

using namespace lanes;

namespace {

    /// Moist voxels (as transport.cpp's moist()), and those that are solute partners.
    [[gnu::always_inline]] inline VI moist(const TransportRows& t, size_t at, int n)
    {
        return (load(t.density + at, n) >= 0.5f) & (load(t.moisture + at, n) >= 0.5f);
    }

    [[gnu::always_inline]] inline VI solute_partner(const TransportRows& t, size_t at, int n)
    {
        return (load(t.partner + at, n) != 0) & moist(t, at, n);
    }

    /// The bits of a float vector, to compare and test values as stored (-0 is not +0).
    [[gnu::always_inline]] inline VI bits(VF v)
    {
        VI b;
        std::memcpy(&b, &v, sizeof v);
        return b;
    }

    [[gnu::target_clones("avx2", "default")]]
    TransportRows::ConcentrationRow concentration_lanes(const TransportRows& t, size_t row,
                                                        int n_t, size_t m, bool known_zero)
    {
        const float* amount = t.dissolved[m] + row;
        float* conc = t.concentration[m] + row;
        // Most rows hold nothing and held nothing at the last step (+0 in, +0 out): then
        // only the amounts are read, and the cache lines stay clean.
        VI any_amount{};
        for (int i0 = 0; i0 < n_t; i0 += kLanes)
            any_amount |= bits(load(amount + i0, std::min(kLanes, n_t - i0)));
        if (!any(any_amount != 0)) {
            if (known_zero)
                return {true, false};
            VI any_conc{};
            for (int i0 = 0; i0 < n_t; i0 += kLanes)
                any_conc |= bits(load(conc + i0, std::min(kLanes, n_t - i0)));
            if (!any(any_conc != 0))
                return {true, false};
        }
        // Every voxel, as the ghosts interpolate dry voxels' concentrations too; 0 / water
        // is the amount itself (its sign kept).
        TransportRows::ConcentrationRow out;
        VI any_fresh{};
        for (int i0 = 0; i0 < n_t; i0 += kLanes) {
            const int n = std::min(kLanes, n_t - i0);
            const size_t c = row + size_t(i0);
            const VF water = load(t.porosity + c, n) * load(t.density + c, n);
            const VF a = load(amount + i0, n);
            const VF fresh = water > 0.0f ? (a != 0.0f ? a / water : a) : VF{};
            any_fresh |= bits(fresh);
            if (any(bits(fresh) != bits(load(conc + i0, n)))) {
                store(conc + i0, fresh, n);
                out.changed = true;
            }
        }
        out.zero = !any(any_fresh != 0);
        return out;
    }

    [[gnu::target_clones("avx2", "default")]]
    void full_stencil_lanes(const TransportRows& t, const Partners& pt, size_t row, int n_t)
    {
        for (int i0 = 0; i0 < n_t; i0 += kLanes) {
            const int n = std::min(kLanes, n_t - i0);
            const size_t c = row + size_t(i0);
            VI full = moist(t, c, n);
            for (size_t e = 0; e < 12 && any(full); ++e)
                full = pt.inside[e] ? full & solute_partner(t, c + size_t(pt.offset[e]), n)
                                    : VI{};
            for (int l = 0; l < n; ++l)
                t.full_stencil[c + size_t(l)] = full[l] != 0;
        }
    }

    /// Wet phases: deposits turn binder at the surface into black crust, and salt comes in
    /// from the atmosphere (the `surface` lanes; the columns of a row are consecutive).
    [[gnu::always_inline]] inline void deposit(const TransportRows& t, VI surface, size_t c,
                                               size_t column, int n)
    {
        const VF dep = load(t.st->column_deposit.data() + column, n);
        const VF soluble = load(t.solid[kSoluble] + c, n);
        const VF turned = vmin(soluble, t.dt * t.black_crust_rate * dep);
        store(t.solid[kSoluble] + c, surface ? soluble - turned : soluble, n);
        const VF black = load(t.black + c, n);
        store(t.black + c, surface ? black + turned : black, n);
        const VI salted = surface & moist(t, c, n);
        if (any(salted)) {
            const VF salt = load(t.dissolved[kSalt] + c, n);
            store(t.dissolved[kSalt] + c, salted ? salt + t.dt * t.salt_supply * dep : salt, n);
        }
    }

    /// Voxels c .. c + n - 1 of a row (n <= kLanes; the columns from `first_column`).
    [[gnu::always_inline]] inline void transport_group(const TransportRows& t,
                                                       const Partners& pt, const long* axis,
                                                       size_t c, size_t first_column, int n)
    {
        const VI f = load(t.flags + c, n);
        const VI stone = (f & int(kStone)) != 0;
        if (!any(stone))
            return;
        const VI surface = stone & ((f & int(kSurface)) != 0);
        if (t.deposits && any(surface))
            deposit(t, surface, c, first_column, n);
        const VI M = stone & moist(t, c, n);
        if (!any(M))
            return;

        const VF rho = load(t.density + c, n), phi = load(t.porosity + c, n);
        const VF vol = load(t.volume + c, n);
        const VF water_c = phi * rho;
        const VF vw_c = water_c * vol;
        const VI full_c = load(t.full_stencil + c, n) != 0;
        // A front voxel has a dry stone face neighbour.
        VI front{};
        for (int a = 0; a < 3; ++a)
            for (int sign = -1; sign <= 1; sign += 2) {
                const size_t y = c + size_t(sign * axis[a]);
                front |= (load(t.density + y, n) >= 0.5f) & (load(t.moisture + y, n) < 0.5f);
            }
        std::array<VF, kSpecies> cc, flux;
        for (int m = 0; m < kSpecies; ++m) {
            cc[size_t(m)] = load(t.concentration[size_t(m)] + c, n);
            flux[size_t(m)] = opaque_zero();
        }
        // What ghosts receive, by entry (12 diffusive, then 6 advective) and species: half
        // of each exchange, added to the ledger voxel by voxel after the group.
        std::array<std::array<VF, kSpecies>, 18> half;
        // (Which entries hand anything to a ghost is a bit mask: zeroing the arrays per group
        // would cost more than the group.)
        std::array<VI, 18> to_ghost;
        uint32_t ghost_entries = 0;
        auto exchange = [&](size_t e, VI valid, VI ghost, size_t m, VF F) {
            flux[m] = valid ? flux[m] + (ghost ? 0.5f * F : F) : flux[m];
            half[e][m] = 0.5f * F;
        };
        // Darcy flows across the faces (directions 0-2), from the diffusive pass.
        // (Not zero-initialised: that costs a rep stos per group; `flows` says which are set.)
        std::array<VF, 6> q;
        std::array<VI, 6> q_valid, q_ghost;
        unsigned flows = 0;
        for (size_t e = 0; e < 12; ++e) {
            if (!pt.inside[e])
                continue;
            const size_t y = c + size_t(pt.offset[e]);
            const VI valid = M & solute_partner(t, y, n);
            if (!any(valid))
                continue;
            const int d = int(e / 2);
            // Ghosts carry no weights, volume or stencil flag: use c's.
            const VF vol_y = load(t.volume + y, n);
            const VI ghost = vol_y == 0.0f;
            const VF w_c = load(t.weight[size_t(d)] + c, n);
            const VF w_y = ghost ? w_c : load(t.weight[size_t(d)] + y, n);
            const VF vy = ghost ? vol : vol_y;
            const VF phi_y = load(t.porosity + y, n);
            const VF vw_y = phi_y * load(t.density + y, n) * vy;
            const VI negative_allowed = full_c & (ghost | (load(t.full_stencil + y, n) != 0));
            const VF pair_weight = w_c + w_y;
            const VF porosity = vmin(phi, phi_y);
            const VF water = vmin(vw_c, vw_y);
            to_ghost[e] = valid & ghost;
            ghost_entries |= uint32_t(any(to_ghost[e])) << e;
            for (size_t m = 0; m < kSpecies; ++m) {
                VF kappa = t.half_diffusivity[m] * pair_weight * porosity * water;
                kappa = negative_allowed ? kappa : (kappa < 0.0f ? VF{} : kappa);
                const VF cy = load(t.concentration[m] + y, n);
                exchange(e, valid, ghost, m, kappa * (cy - cc[m]));
            }
            if (d >= 3)
                continue;
            // Darcy flow rate from c into y, limited to a tenth of the smaller water
            // volume per step (transport.cpp).
            const VF kf = 0.5f * (load(t.permeability + c, n) + load(t.permeability + y, n));
            const VF vd = -kf * t.inv_eta *
                          ((load(t.pressure + y, n) - load(t.pressure + c, n)) +
                           (load(t.head + y, n) - load(t.head + c, n)));
            const VF hc = axis_metric(t.weight, d, c, n);
            const VF hy = ghost ? hc : axis_metric(t.weight, d, y, n);
            const VF cap = 0.1f / t.dt * water;
            q[e] = vclamp(vd * 0.25f * (vol + vy) * (hc + hy), -cap, cap);
            q_valid[e] = valid;
            q_ghost[e] = ghost;
            flows |= 1u << e;
        }
        for (size_t a = 0; a < 6; ++a) {
            const size_t e = 12 + a;
            if (!(flows >> a & 1u))
                continue;
            const size_t y = c + size_t(pt.offset[a]);
            to_ghost[e] = q_valid[a] & q_ghost[a];
            ghost_entries |= uint32_t(any(to_ghost[e])) << e;
            const VF in = vmax(VF{}, -q[a]), out = vmax(VF{}, q[a]);
            for (size_t m = 0; m < kSpecies; ++m) {
                const VF cy = load(t.concentration[m] + y, n);
                exchange(e, q_valid[a], q_ghost[a], m, in * cy - out * cc[m]);
            }
        }
        if (ghost_entries) {
            // Voxel by voxel, entries in order: the scalar loop's order of the ledger's sums
            // (two entries may feed one ghost). Only the set bits are visited.
            std::array<uint32_t, kLanes> lane_entries{};
            for (uint32_t bits = ghost_entries; bits; bits &= bits - 1) {
                const int e = std::countr_zero(bits);
                for (unsigned on = lane_bits(to_ghost[size_t(e)]); on; on &= on - 1)
                    lane_entries[size_t(std::countr_zero(on))] |= 1u << e;
            }
            for (int l = 0; l < n; ++l)
                for (uint32_t bits = lane_entries[size_t(l)]; bits; bits &= bits - 1) {
                    const size_t e = size_t(std::countr_zero(bits));
                    const size_t a = e < 12 ? e : e - 12;
                    const size_t y = c + size_t(l) + size_t(pt.offset[a]);
                    for (size_t m = 0; m < kSpecies; ++m)
                        t.ledger[m][y] += half[e][m][l];
                    if (!t.ghost_hit[y]) {
                        t.ghost_hit[y] = 1;
                        t.ghost_hits[pt.slab].push_back(uint32_t(y));
                    }
                }
        }

        const VI front_m = M & front;
        const VI dries = t.wet ? VI{} : M & surface;
        VF take_soluble{};
        for (size_t m = 0; m < kSpecies; ++m) {
            const VF old = load(t.dissolved[m] + c, n);
            VF amount = old + t.dt * flux[m] / vol;
            // Dissolution at the front up to saturation, from the solid mineral.
            const VF room = t.saturation[m] - cc[m];
            const VF solid = load(t.solid[m] + c, n);
            VF take = t.rate_cap[m] * (room > 0.0f ? room : VF{}) * water_c;
            take = solid < take ? solid : take;
            take = front_m ? take : VF{};
            store(t.solid[m] + c, front_m ? solid - take : solid, n);
            amount = front_m ? amount + take : amount;
            if (m == kSoluble)
                take_soluble = take;
            // Evaporation at the surface in dry phases: the load crystallises as crust.
            if (!t.wet) {
                const VF crust = load(t.crust[m] + c, n);
                const VF cryst = t.crystallise * amount;
                store(t.crust[m] + c, dries ? crust + cryst : crust, n);
                amount = dries ? amount - cryst : amount;
            }
            store(t.dissolved[m] + c, M ? amount : old, n);
        }
        // Decay index (§4.3.4): time moist plus binder dissolved.
        const VF decay = load(t.decay + c, n);
        const VF grown = decay + (t.decay_water * t.dt + t.decay_dissolution * take_soluble);
        store(t.decay + c, M ? grown : decay, n);
    }

    [[gnu::target_clones("avx2", "default")]]
    void transport_lanes(const TransportRows& t, const Partners& pt, const SlabGrid& g,
                         size_t row, size_t first_column)
    {
        const long axis[3] = {1, g.sx, long(g.sx) * g.sy};
        for (int i0 = 0; i0 < g.n_t; i0 += kLanes) {
            // Whole groups with a constant lane count (their loads and stores are moves).
            const size_t c = row + size_t(i0), column = first_column + size_t(i0);
            if (g.n_t - i0 >= kLanes)
                transport_group(t, pt, axis, c, column, kLanes);
            else
                transport_group(t, pt, axis, c, column, g.n_t - i0);
        }
    }

} // namespace

Partners::Partners(const SlabLattice& lat, int s, int k) : slab(s)
{
    const auto& o = lat.offsets(s);
    const StencilSigns& sg = lat.signs(s);
    const std::array<int, 6> dk = {0, 0, 1, 0, sg.s[1], sg.s[2]};
    for (int d = 0; d < 6; ++d)
        for (int sign = -1; sign <= 1; sign += 2) {
            const size_t e = size_t(2 * d + (sign > 0));
            offset[e] = sign * o[size_t(d)];
            const int ky = k + sign * dk[size_t(d)];
            inside[e] = ky >= 0 && ky < lat.grid().n_d;
        }
}

TransportRows::TransportRows(StoneState& s, bool is_wet, float step)
    : RowFields(s), st(&s), wet(is_wet), dt(step)
{
    const SlabLattice& lat = *s.lattice;
    const StoneParameters& prm = s.params;
    full_stencil = s.full_stencil.data();
    volume = lat.volume().data();
    partner = lat.flux_partner_data();
    for (size_t m = 0; m < kSpecies; ++m) {
        concentration[m] = s.concentration[m].data();
        dissolved[m] = s.dissolved[m].data();
        solid[m] = s.solid[m].data();
        crust[m] = s.crust[m].data();
        ledger[m] = s.ghost_flux[m].data();
    }
    deposits = wet && std::any_of(s.column_deposit.begin(), s.column_deposit.end(),
                                  [](float d) { return d != 0.0f; });
    ghost_hit = s.ghost_hit.data();
    ghost_hits = s.ghost_hits.data();
    decay = s.decay.data();
    black = s.black.data();
    const float alpha = float(prm.pressure_diffusivity);
    inv_eta = float(1.0 / prm.viscosity);
    crystallise = std::min(1.0f, dt * float(prm.crystallisation_rate));
    decay_water = float(prm.decay_water);
    decay_dissolution = float(prm.decay_dissolution);
    black_crust_rate = float(prm.black_crust_rate);
    salt_supply = float(prm.salt_supply);
    for (size_t m = 0; m < kSpecies; ++m) {
        half_diffusivity[m] = alpha * float(prm.diffusivity[m]) * 0.5f;
        saturation[m] = float(prm.saturation[m]);
        rate_cap[m] = std::min(1.0f, dt * float(prm.solubility[m]));
    }
}

TransportRows::ConcentrationRow TransportRows::concentration_row(size_t row, size_t m,
                                                               bool known_zero) const
{
    return concentration_lanes(*this, row, st->lattice->grid().n_t, m, known_zero);
}

void TransportRows::full_stencil_row(int s, int j, int k) const
{
    const SlabGrid& g = st->lattice->grid();
    full_stencil_lanes(*this, Partners(*st->lattice, s, k), g.index(s, 0, j, k), g.n_t);
}

void TransportRows::transport_row(int s, int j, int k) const
{
    const SlabGrid& g = st->lattice->grid();
    transport_lanes(*this, Partners(*st->lattice, s, k), g, g.index(s, 0, j, k),
                    column_index(g, s, 0, j));
}

} // namespace patina::texgen::stone
