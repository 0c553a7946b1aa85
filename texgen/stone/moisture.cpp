// Travel of moisture (Dorsey et al. 1999 §4.3.2): pressure diffusion with Dirichlet
// conditions at the surface and at the moist/dry front, and the front moved by Darcy's law.
//
// The paper prints dp/dt = -div(phi grad p) = -phi lap p - grad phi . grad p; with that sign
// the pressure would un-diffuse (blow up), so we integrate the diffusion equation
// dp/dt = div(alpha phi grad p) = alpha (phi lap p + grad phi . grad p), alpha a scale.
// lap p is the 13-point stencil (§4.3.5); the gradients are central differences along the
// lattice axes, dotted through the inverse metric H (stencil.h): grad a . grad b = Da^T H Db.
//
// Darcy's law v = -K/eta (grad p - rho g): along a lattice direction d (from a moist voxel y
// into a dry voxel x), v . d = -K/eta ((p_x - p_y) + (psi_x - psi_y)) with the head
// psi = rho |g| up . x. The front advances into x by the pore velocity (v . d / phi) over the
// spacing |d| (1/|d|^2 ~ H_aa), as a moisture fraction theta in [0, 1] that makes x moist at
// 1/2. In dry phases the surface dries at `evaporation_speed`, and the dry zone spreads
// inwards down each column (water evaporates from the surface side); dissolved minerals in
// a voxel that dries recrystallise in place (as crust in a surface voxel).
#include "texgen/stone_rows/front_rows.h"
#include "texgen/stone_rows/live_rows.h"
#include "texgen/stone_rows/pressure_rows.h"
#include "texgen/stone/stone_state.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <bit>
#include <cstring>

namespace patina::texgen::stone {

namespace {

    /// Whether the pressure step changes any of the n voxels from `row`: a moist stone voxel
    /// below the surface, or a dry one whose pressure is not yet the front's +0 (it dried in
    /// the last step; compared as bits, as the step writes +0). Air and surface voxels keep
    /// their Dirichlet values. Branch-free, so that it vectorises: most rows of the active
    /// layers are air or dry stone.
    inline bool pressure_changes(const StoneState& st, size_t row, int n)
    {
        const uint8_t* f = st.flags.data() + row;
        const float* theta = st.moisture.data() + row;
        const float* p = st.pressure.data() + row;
        int any = 0;
        for (int i = 0; i < n; ++i)
            any |= int((f[i] & (kStone | kSurface)) == kStone) &
                   (int(theta[i] >= 0.5f) | int(std::bit_cast<uint32_t>(p[i]) != 0u));
        return any != 0;
    }

    /// Updates the first `layers` layers of slab s of `field` in place: `compute(k, out)`
    /// writes the new values of layer k's rows (n_t x n_t, row-major) from the old ones and
    /// returns, per row, whether it wrote it (rows it leaves keep their values). The stencils
    /// reach one layer up and down, so layer k is written back only once layer k + 1 has been
    /// computed: the same result as a double buffer, without a second array to stream. Rows
    /// whose bits change are written and marked in `changes`; the others stay clean.
    template <class Compute>
    void update_layers_in_place(float* field, const SlabGrid& g, int s, int layers,
                                HaloChanges& changes, Compute&& compute)
    {
        const size_t n = size_t(g.n_t) * size_t(g.n_t);
        thread_local std::vector<float> buffer;
        thread_local std::vector<uint8_t> written;
        buffer.resize(2 * n);
        written.resize(2 * size_t(g.n_t));
        auto write_back = [&](int k) {
            const float* from = buffer.data() + size_t(k & 1) * n;
            const uint8_t* rows = written.data() + size_t(k & 1) * size_t(g.n_t);
            for (int j = 0; j < g.n_t; ++j) {
                const float* row = from + size_t(j) * g.n_t;
                float* to = field + g.index(s, 0, j, k);
                if (rows[j] && std::memcmp(row, to, sizeof(float) * size_t(g.n_t)) != 0) {
                    std::copy(row, row + g.n_t, to);
                    changes.mark_row(s, j, k, g);
                }
            }
        };
        for (int k = 0; k < layers; ++k) {
            uint8_t* rows = written.data() + size_t(k & 1) * size_t(g.n_t);
            std::fill(rows, rows + g.n_t, 0);
            compute(k, buffer.data() + size_t(k & 1) * n, rows);
            if (k > 0)
                write_back(k - 1);
        }
        if (layers > 0)
            write_back(layers - 1);
    }

    void pressure_step(StoneState& st, bool wet)
    {
        const SlabLattice& lat = *st.lattice;
        const SlabGrid& g = lat.grid();
        float* p = st.pressure.data();
        // Dirichlet values: the surface and the air above it carry the surface pressure.
        // Below the active layers the stone is dry and p = 0 is never read. They stay in
        // place from step to step of a phase until the surface moves (StoneState::
        // pressure_preset_depth): only layers that became active since are set then.
        std::vector<char> changed(size_t(g.slab_count), 0);
        const float surface_p = float(st.params.surface_pressure);
        if (st.pressure_preset_depth.size() != size_t(g.slab_count) ||
            st.pressure_preset_wet != wet) {
            st.pressure_preset_depth.assign(size_t(g.slab_count), 0);
            st.pressure_preset_wet = wet;
        }
        tbb::parallel_for(0, g.slab_count, [&](int s) {
            int& preset = st.pressure_preset_depth[size_t(s)];
            const int from = preset;
            preset = std::max(preset, st.active_depth[size_t(s)]);
            for (int k = from; k < st.active_depth[size_t(s)]; ++k)
                for (int j = 0; j < g.n_t; ++j) {
                    const size_t row = g.index(s, 0, j, k);
                    const uint8_t* f = st.flags.data() + row;
                    const float* wetness = st.column_wetness.data() + column_index(g, s, 0, j);
                    float* pr = p + row;
                    // Read-only and branch-free first (it vectorises): in most steps no value
                    // changes, and the row's cache lines stay clean.
                    auto boundary = [&](int i) {
                        return wet ? surface_p * wetness[i] : 0.0f;
                    };
                    int differs = 0;
                    for (int i = 0; i < g.n_t; ++i)
                        differs |= int(!(f[i] & kStone) || (f[i] & kSurface)) &
                                   int(std::bit_cast<uint32_t>(pr[i]) !=
                                       std::bit_cast<uint32_t>(boundary(i)));
                    if (!differs)
                        continue;
                    changed[size_t(s)] = 1;
                    st.pressure_halo.mark_row(s, j, k, g);
                    for (int i = 0; i < g.n_t; ++i)
                        if (!(f[i] & kStone) || (f[i] & kSurface))
                            pr[i] = boundary(i);
                }
        });
        // The halo holds the last step's pressure (filled at its end); unless a boundary
        // value changed (a new phase, erosion), it is still the halo of these values.
        if (std::find(changed.begin(), changed.end(), 1) != changed.end())
            lat.fill_halo(p, &st.active_depth, &st.pressure_halo);

        const PressureRows rows(st);
        tbb::parallel_for(0, g.slab_count, [&](int s) {
            const int layers = st.active_depth[size_t(s)];
            auto compute = [&](int k, float* out, uint8_t* written) {
                for (int j = 0; j < g.n_t; ++j) {
                    if (!pressure_changes(st, g.index(s, 0, j, k), g.n_t))
                        continue;
                    written[j] = 1;
                    rows.row(s, j, k, out + size_t(j) * g.n_t);
                }
            };
            update_layers_in_place(p, g, s, layers, st.pressure_halo, compute);
        });
        lat.fill_halo(p, &st.active_depth, &st.pressure_halo);
    }

    void front_step(StoneState& st, bool wet)
    {
        const SlabLattice& lat = *st.lattice;
        const SlabGrid& g = lat.grid();
        float* theta = st.moisture.data();
        const FrontRows rows(st, wet);
        // Below the active layers the stone is dry and unreachable this step: nothing moves.
        // Nor in a row without a moist or surface voxel in it or across its faces: air stays
        // at 0 (erosion dries what it turns to air) and dry stone without a moist face
        // neighbour keeps its moisture.
        tbb::parallel_for(0, g.slab_count, [&](int s) {
          const int layers = st.active_depth[size_t(s)];
          thread_local LiveRows live;
          live.scan(st, s, std::min(layers, g.n_d));
          update_layers_in_place(theta, g, s, layers, st.moisture_halo,
                                 [&](int k, float* out, uint8_t* written) {
            for (int j = 0; j < g.n_t; ++j) {
                if (!live.live_around(j, k))
                    continue;
                rows.row(s, j, k, out + size_t(j) * g.n_t);
                written[j] = 1;
            }
          });
        });
        refresh_active_depth(st);
        lat.fill_halo(st.moisture.data(), &st.active_depth, &st.moisture_halo);
    }

} // namespace

void moisture_step(StoneState& st, bool wet)
{
    pressure_step(st, wet);
    front_step(st, wet);
}

} // namespace patina::texgen::stone
