// Row kernel of the pressure diffusion; the model (§4.3.2, and the sign of the printed
// equation) is described at the top of moisture.cpp, which drives it.
#include "texgen/stone_rows/pressure_rows.h"

#include "texgen/stone_rows/lanes.h"

#include <algorithm>

namespace patina::texgen::stone {

using namespace lanes;

namespace {

    /// The slab's stencil: offsets of the six directions and the signs of the metric's
    /// off-diagonal terms.
    struct SlabStencil {
        std::array<long, 6> offset;
        float s0, s1, s2;
    };

    [[gnu::always_inline]] inline VF central(const float* v, size_t c, size_t o, int n)
    {
        return 0.5f * (load(v + c + o, n) - load(v + c - o, n));
    }

    /// Voxels c .. c + n - 1 (n <= kLanes) into out.
    [[gnu::always_inline]] inline void pressure_group(const PressureRows& t,
                                                      const SlabStencil& sl, size_t c,
                                                      float* out, int n)
    {
        const float* p = t.pressure;
        const VI f = load(t.flags + c, n);
        const VI keep = ((f & int(kStone)) == 0) | ((f & int(kSurface)) != 0);
        const VF pc = load(p + c, n);
        // Dry stone: the front's Dirichlet p = 0.
        const VI moist = ~keep & (load(t.moisture + c, n) >= 0.5f);
        if (!any(moist)) {
            store(out, keep ? pc : VF{}, n);
            return;
        }
        const auto& w = t.weight;
        VF lap{};
        for (size_t d = 0; d < 6; ++d) {
            const size_t o = size_t(sl.offset[d]);
            lap += load(w[d] + c, n) * (load(p + c + o, n) + load(p + c - o, n) - 2.0f * pc);
        }
        // Central differences along the axes, through H.
        const size_t ax0 = size_t(sl.offset[0]), ax1 = size_t(sl.offset[1]),
                     ax2 = size_t(sl.offset[2]);
        const VF dp0 = central(p, c, ax0, n), dp1 = central(p, c, ax1, n),
                 dp2 = central(p, c, ax2, n);
        const VF df0 = central(t.porosity, c, ax0, n), df1 = central(t.porosity, c, ax1, n),
                 df2 = central(t.porosity, c, ax2, n);
        const VF w0 = load(w[0] + c, n), w1 = load(w[1] + c, n), w2 = load(w[2] + c, n),
                 w3 = load(w[3] + c, n), w4 = load(w[4] + c, n), w5 = load(w[5] + c, n);
        const VF h00 = w0 + w3 + w5, h11 = w1 + w3 + w4, h22 = w2 + w4 + w5;
        const VF h01 = sl.s0 * w3, h12 = sl.s1 * w4, h02 = sl.s2 * w5;
        const VF cross = df0 * (h00 * dp0 + h01 * dp1 + h02 * dp2) +
                         df1 * (h01 * dp0 + h11 * dp1 + h12 * dp2) +
                         df2 * (h02 * dp0 + h12 * dp1 + h22 * dp2);
        const VF diffused = pc + t.rate * (load(t.porosity + c, n) * lap + cross);
        store(out, keep ? pc : (moist ? diffused : VF{}), n);
    }

    [[gnu::target_clones("avx2", "default")]]
    void pressure_lanes(const PressureRows& t, const SlabStencil& sl, size_t row, int n_t,
                        float* out)
    {
        for (int i0 = 0; i0 < n_t; i0 += kLanes) {
            const size_t c = row + size_t(i0);
            if (n_t - i0 >= kLanes)
                pressure_group(t, sl, c, out + i0, kLanes);
            else
                pressure_group(t, sl, c, out + i0, n_t - i0);
        }
    }

} // namespace

PressureRows::PressureRows(const StoneState& s)
    : RowFields(s), st(&s), rate(float(s.dt * s.params.pressure_diffusivity))
{
}

void PressureRows::row(int s, int j, int k, float* out) const
{
    const SlabLattice& lat = *st->lattice;
    const SlabGrid& g = lat.grid();
    const StencilSigns& sg = lat.signs(s);
    const SlabStencil sl{lat.offsets(s), float(sg.s[0]), float(sg.s[1]), float(sg.s[2])};
    pressure_lanes(*this, sl, g.index(s, 0, j, k), g.n_t, out);
}

} // namespace patina::texgen::stone
