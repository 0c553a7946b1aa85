// Erosion: transformation to clay (Dorsey et al. 1999 §4.3.4). The decay index d of a voxel
// grows with the time it is moist and with the binder dissolved there (transport.cpp). Each
// cycle, erosion events are scattered over the surface voxels with probability proportional
// to d; an event lowers the density within its zone of influence (a cone of `erosion_radius`
// depth steps); a voxel whose density falls below 1/2 is no longer stone, and whatever crust
// it carried falls off with it.
#include "texgen/stone/stone_state.h"

#include "core/sampling.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace patina::texgen::stone {

void erosion_events(StoneState& st)
{
    const StoneParameters& prm = st.params;
    if (prm.erosion_events <= 0.0 || prm.erosion_amount <= 0.0)
        return;
    const SlabLattice& lat = *st.lattice;
    const SlabGrid& g = lat.grid();

    // Surface voxels and the running sum of their decay, in cell order. Each slab lists its
    // own (surface voxels lie in the layers marked in surface_layer, above the surface depth;
    // the halo has no flags), then one serial pass sums them in order: deterministic, and the
    // same sums as a single walk over the cells.
    struct Decaying {
        uint32_t cell;
        float decay;
    };
    std::vector<std::vector<Decaying>> listed(size_t(g.slab_count));
    std::vector<size_t> surface_count(size_t(g.slab_count), 0);
    tbb::parallel_for(0, g.slab_count, [&](int s) {
        std::vector<Decaying>& list = listed[size_t(s)];
        for (int k = 0; k < st.surface_depth[size_t(s)]; ++k) {
            if (!st.surface_layer[size_t(s) * size_t(g.n_d) + size_t(k)])
                continue;
            for (int j = 0; j < g.n_t; ++j)
                for (int i = 0; i < g.n_t; ++i) {
                    const size_t c = g.index(s, i, j, k);
                    if (!(st.flags[c] & kSurface))
                        continue;
                    ++surface_count[size_t(s)];
                    if (st.decay[c] > 0.0f)
                        list.push_back({uint32_t(c), st.decay[c]});
                }
        }
    });
    std::vector<uint32_t> cells;
    std::vector<double> cdf;
    double total = 0.0;
    size_t n_surface = 0;
    for (int s = 0; s < g.slab_count; ++s) {
        n_surface += surface_count[size_t(s)];
        for (const Decaying& d : listed[size_t(s)]) {
            total += d.decay;
            cells.push_back(d.cell);
            cdf.push_back(total);
        }
    }
    if (cells.empty() || !(total > 0.0))
        return;
    Pcg32 rng(hash_values(prm.seed, 0xe705, uint64_t(st.cycles_done)));
    // A fractional expected count becomes one more event with that probability.
    const double expected = prm.erosion_events * double(n_surface);
    size_t events = size_t(expected);
    if (rng.uniform_double() < expected - double(events))
        ++events;

    // The centres are drawn in sequence (one generator); an event's zone stays inside its
    // centre's slab, so the slabs apply their own events in parallel, each in drawing order:
    // the same result as applying them one by one.
    std::vector<std::vector<uint32_t>> centres(size_t(g.slab_count));
    for (size_t e = 0; e < events; ++e) {
        const double x = rng.uniform_double() * total;
        const size_t pick = size_t(std::upper_bound(cdf.begin(), cdf.end(), x) - cdf.begin());
        const uint32_t centre = cells[std::min(pick, cells.size() - 1)];
        centres[centre / g.slab_size].push_back(centre);
    }
    const int r = int(std::ceil(prm.erosion_radius));
    const float amount = float(prm.erosion_amount);
    const auto& w = lat.weights();
    tbb::parallel_for(0, g.slab_count, [&](int s) {
      for (const uint32_t centre : centres[size_t(s)]) {
        const size_t local = centre % g.slab_size;
        const int ci = int(local % g.sx) - 1, cj = int((local / g.sx) % g.sy) - 1,
                  ck = int(local / (size_t(g.sx) * g.sy)) - 1;
        const Imath::V3f pc = lat.position()[centre];
        // Depth step at the centre: the zone's radius is measured in it.
        const float h = 1.0f / std::sqrt(w[2][centre] + w[4][centre] + w[5][centre]);
        const float radius = float(prm.erosion_radius) * h;
        for (int k = std::max(0, ck - r); k <= std::min(g.n_d - 1, ck + r); ++k)
            for (int j = std::max(0, cj - r); j <= std::min(g.n_t - 1, cj + r); ++j)
                for (int i = std::max(0, ci - r); i <= std::min(g.n_t - 1, ci + r); ++i) {
                    const size_t c = g.index(s, i, j, k);
                    const float d = (lat.position()[c] - pc).length();
                    if (d >= radius)
                        continue;
                    st.density[c] = std::max(0.0f, st.density[c] - amount * (1.0f - d / radius));
                    st.density_halo.mark(c, g);
                    if (st.density[c] < 0.5f && (st.flags[c] & kStone)) {
                        // The voxel crumbled: crust and minerals leave with it.
                        for (int m = 0; m < kSpecies; ++m) {
                            st.crust[m][c] = 0.0f;
                            st.dissolved[m][c] = 0.0f;
                        }
                        st.black[c] = 0.0f;
                        st.moisture[c] = 0.0f;
                        st.moisture_halo.mark(c, g);
                        st.flags[c] = 0;
                    }
                }
      }
    });
    update_flags(st);
    // The steps read the moisture's halo in the active layers only (and fill it there).
    lat.fill_halo(st.moisture.data(), &st.active_depth, &st.moisture_halo);
}

} // namespace patina::texgen::stone
