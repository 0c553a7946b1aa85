// Row kernel of the moisture front; the model (Darcy's law, §4.3.2) is described at the top of
// moisture.cpp, which drives it.
#include "texgen/stone_rows/front_rows.h"

#include "texgen/stone_rows/lanes.h"

namespace patina::texgen::stone {

using namespace lanes;

namespace {

    /// The voxel dried: what the water held recrystallises in place, in the pores below the
    /// surface, and as a crust (efflorescence, iron oxide) where the water evaporated at the
    /// surface.
    void recrystallise(StoneState& st, size_t c, bool surface)
    {
        auto& into = surface ? st.crust : st.solid;
        for (int m = 0; m < kSpecies; ++m) {
            into[m][c] += st.dissolved[m][c];
            st.dissolved[m][c] = 0.0f;
        }
    }

    /// Voxels c .. c + n - 1 (n <= kLanes; their columns from `column`) into out.
    [[gnu::always_inline]] inline void front_group(const FrontRows& t, const long* axis,
                                                   size_t c, size_t column, float* out, int n)
    {
        const float* theta = t.moisture;
        const VF th0 = load(theta + c, n);
        const VI f = load(t.flags + c, n);
        const VI stone = (f & int(kStone)) != 0;
        const VI surface = (f & int(kSurface)) != 0;
        // Air to 0: moisture is never negative, so t x 0 is +0 and t x 1 is t.
        const VF kept = th0 * (stone ? VF{} + 1.0f : VF{});
        // Which voxels can change: surface voxels, moist ones (their wet time grows) and dry
        // ones beside a moist voxel (Darcy inflow).
        VI near_moist = th0 >= 0.5f;
        for (int a = 0; a < 3; ++a)
            near_moist |= (load(theta + c - size_t(axis[a]), n) >= 0.5f) |
                          (load(theta + c + size_t(axis[a]), n) >= 0.5f);
        const VI work = stone & (near_moist | surface);
        if (!any(work)) {
            store(out, kept, n);
            return;
        }
        // Surface voxels soak in wet phases (where it rains) and dry in dry ones; in dry
        // phases the moist zone also dries inwards down each column from a dry outer voxel.
        const VF th = th0;
        VF th_surface = th, th_moist = th;
        if (t.wet) {
            if (any(work & surface)) {
                const VI rained = load(t.wetness + column, n) > 0.05f;
                th_surface = rained ? VF{} + 1.0f : th;
            }
        } else {
            const VF drying = t.dt * t.evaporation * vsqrt(axis_metric(t.weight, 2, c, n));
            th_surface = th - drying;
            const size_t above = c - size_t(axis[2]);
            const VI outer_dry =
                (load(t.density + above, n) < 0.5f) | (load(theta + above, n) < 0.5f);
            th_moist = outer_dry ? th - drying : th;
        }
        // Dry voxels beside a moist one: Darcy inflow from the moist face neighbours.
        VF th_dry = th;
        if (any(work & ~surface & (th < 0.5f))) {
            const VF K_c = load(t.permeability + c, n), p_c = load(t.pressure + c, n),
                     psi_c = load(t.head + c, n);
            VF speed{};
            for (int a = 0; a < 3; ++a)
                for (int sign = -1; sign <= 1; sign += 2) {
                    const size_t y = c + size_t(sign * axis[a]);
                    const VI moist_y =
                        ~((load(t.density + y, n) < 0.5f) | (load(theta + y, n) < 0.5f));
                    const VF kf = 0.5f * (K_c + load(t.permeability + y, n));
                    const VF vd = -kf * t.inv_eta * ((p_c - load(t.pressure + y, n)) +
                                                     (psi_c - load(t.head + y, n)));
                    const VI flows = moist_y & (vd > 0.0f);
                    if (any(flows))
                        speed = flows ? speed + vd * axis_metric(t.weight, a, c, n) : speed;
                }
            th_dry = th + t.dt * speed / load(t.porosity + c, n);
        }
        VF th1 = surface ? th_surface : (th < 0.5f ? th_dry : th_moist);
        th1 = vclamp(th1, VF{}, VF{} + 1.0f);
        const VI dried = work & (th0 >= 0.5f) & (th1 < 0.5f);
        if (any(dried))
            for (int l = 0; l < n; ++l)
                if (dried[l])
                    recrystallise(*t.st, c + size_t(l), surface[l] != 0);
        const VI moist = work & (th1 >= 0.5f);
        if (any(moist)) {
            const VF wet_time = load(t.wet_time + c, n);
            store(t.wet_time + c, moist ? wet_time + t.dt : wet_time, n);
        }
        store(out, work ? th1 : kept, n);
    }

    [[gnu::target_clones("avx2", "default")]]
    void front_lanes(const FrontRows& t, const SlabGrid& g, size_t row, size_t first_column,
                     float* out)
    {
        const long axis[3] = {1, g.sx, long(g.sx) * g.sy};
        for (int i0 = 0; i0 < g.n_t; i0 += kLanes) {
            const size_t c = row + size_t(i0), column = first_column + size_t(i0);
            if (g.n_t - i0 >= kLanes)
                front_group(t, axis, c, column, out + i0, kLanes);
            else
                front_group(t, axis, c, column, out + i0, g.n_t - i0);
        }
    }

} // namespace

FrontRows::FrontRows(StoneState& s, bool is_wet) : RowFields(s), st(&s), wet(is_wet)
{
    wetness = s.column_wetness.data();
    wet_time = s.wet_time.data();
    dt = float(s.dt);
    inv_eta = float(1.0 / s.params.viscosity);
    evaporation = float(s.params.evaporation_speed);
}

void FrontRows::row(int s, int j, int k, float* out) const
{
    const SlabGrid& g = st->lattice->grid();
    front_lanes(*this, g, g.index(s, 0, j, k), column_index(g, s, 0, j), out);
}

} // namespace patina::texgen::stone
