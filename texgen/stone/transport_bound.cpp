// How long a transport step may be (transport.cpp): a bound on the spectral radius of its
// diffusion operator that holds in every state the simulation can reach, computed once per
// run.
//
// The diffusive part of a step, in the concentrations C (amount / water) of the moist voxels,
// is C' = C - span L C with L = V^-1 K: K the couplings kappa, V the water volumes
// (phi rho vol). L diffuses (its eigenvalues are real and >= 0 away from the seams, where it
// is symmetric in the water-weighted product), and forward Euler is stable when
// span rho(L) <= 2. The step keeps 0.9 of that on a bound that is itself 1.3-1.4 times
// rho(L) where all the stone is moist (the test), so every mode's factor 1 - span lambda
// stays in [-0.8, 1] (the largest Gershgorin row, 1.9 times rho on the paper-size grid, was
// kept at 0.8 of the limit). rho(L) <= rho(|L|) <= rho(M) for any matrix
// M >= |L| entry by entry (Perron-Frobenius), and for any positive vector d
// rho(M) <= max_c (M d)_c / d_c (Collatz-Wielandt). M here bounds |L| in every state, with
// kappa = alpha D_i / 2 (w_c + w_y) min(phi) min(V_c, V_y) (transport_rows.cpp) and h the
// largest alpha D_i / 2, as the sum of one term per exchange:
// - a partner y in the slab: |kappa| / V_c <= h |w_c + w_y| min(phi_c, phi_y), on the
//   diagonal and in y's column;
// - a ghost partner g (each end takes half): h |2 w_c| min(phi) / 2 on the diagonal and
//   |omega_i| times that in the column of each of g's sources i;
// - the other side of a seam: a voxel x whose ghost g' has c as a source of weight omega
//   hands c omega/2 of its exchange kappa' (C_g' - C_x), with
//   kappa' <= h |2 w_x| min(phi_x, phi_g')^2 vol_x (density <= 1) and V_c >= phi_c vol_c / 2
//   (a moist voxel has density >= 1/2), in x's column and, times |omega_j|, in those of g''s
//   sources j.
// Only stone voxels (density >= 1/2) can be moist, and density only falls, so only the
// columns of the voxels that are stone at the start count.
//
// d = 1 gives the largest row sum of M (Gershgorin). Each product with M smooths d over the
// stencil, so that max (M d)_c / d_c falls towards rho(M) (it never rises: Collatz-Wielandt's
// max ratio is non-increasing under power iteration of a non-negative matrix); the largest
// rows sit in the shell's innermost layer, where the voxels are smallest, and the smoothing
// spreads them over the layers beside it. Advection is capped per step at a tenth of the
// smaller water volume (transport_rows.cpp), whatever the span.
#include "texgen/stone/stone_state.h"
#include "texgen/stone_rows/transport_rows.h"

#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace patina::texgen::stone {

namespace {

    /// M (above), over h, applied to vectors over the cells (0 off the stone voxels).
    class TransportMajorant {
    public:
        explicit TransportMajorant(const StoneState& st)
            : st_(st), lat_(*st.lattice), g_(lat_.grid()), w_(lat_.weights()),
              vol_(lat_.volume()), phi_(st.porosity)
        {
        }

        /// out = M d / h on the stone voxels (the other cells of `out` are left as they are).
        void apply(const std::vector<double>& d, std::vector<double>& out) const
        {
            // Per ghost: sum |omega_i| d_i over its sources, and the seam terms of the voxels
            // that have it as a partner, without omega and V_c. A slab's ghosts are partners
            // of its own voxels only (those on its sides), so slabs run in parallel.
            std::vector<double> seam(g_.cell_count(), 0.0), spread(g_.cell_count(), -1.0);
            tbb::parallel_for(0, g_.slab_count, [&](int s) {
                for_each_voxel(s, true, [](size_t) {},
                               [&](size_t x, size_t dir, size_t y, bool ghost) {
                                   if (!ghost)
                                       return;
                                   if (spread[y] < 0.0)
                                       spread[y] = spread_of(y, d);
                                   const double p = std::min(phi_[x], phi_[y]);
                                   seam[y] += std::abs(2.0 * w_[dir][x]) * p * p * vol_[x] *
                                              0.5 * (d[x] + spread[y]);
                               });
            });
            // Every voxel's row: its own partners, then the seams it feeds.
            const auto& begin = lat_.feed_begin();
            const auto& feeds = lat_.feeds();
            tbb::parallel_for(0, g_.slab_count, [&](int s) {
                double row = 0.0;
                auto partner = [&](size_t c, size_t dir, size_t y, bool ghost) {
                    const double p = std::min(phi_[c], phi_[y]);
                    row += ghost ? std::abs(2.0 * w_[dir][c]) * p * 0.5 * (d[c] + spread[y])
                                 : std::abs(double(w_[dir][c]) + w_[dir][y]) * p * (d[c] + d[y]);
                };
                auto voxel = [&](size_t c) {
                    double other = 0.0;
                    for (uint32_t e = begin[c]; e < begin[c + 1]; ++e)
                        other += std::abs(double(feeds[e].weight)) * seam[feeds[e].ghost];
                    out[c] = row + other / (0.5 * phi_[c] * vol_[c]);
                    row = 0.0;
                };
                for_each_voxel(s, false, voxel, partner);
            });
        }

        /// Whether cell c is a stone voxel (a column of M).
        bool stone(size_t c) const { return (st_.flags[c] & kStone) != 0; }

    private:
        /// For every stone voxel c of slab s: partner(c, d, y, ghost) for each of its flux
        /// partners y (direction d), then voxel(c). With `sides_only`, only the voxels on the
        /// slab's sides, the only ones whose partners can be ghosts.
        template <class Voxel, class Partner>
        void for_each_voxel(int s, bool sides_only, Voxel&& voxel, Partner&& partner) const
        {
            const int last = g_.n_t - 1;
            for (int k = 0; k < g_.n_d; ++k) {
                const Partners pt(lat_, s, k);  // as the transport kernel sees them
                for (int j = 0; j < g_.n_t; ++j)
                    for (int i = 0; i < g_.n_t; ++i) {
                        if (sides_only && j != 0 && j != last && i != 0 && i != last)
                            continue;
                        const size_t c = g_.index(s, i, j, k);
                        if (!stone(c))
                            continue;
                        for (size_t e = 0; e < 12; ++e) {
                            const size_t y = size_t(long(c) + pt.offset[e]);
                            if (pt.inside[e] && lat_.flux_partner(y))
                                partner(c, e / 2, y, vol_[y] == 0.0f);
                        }
                        voxel(c);
                    }
            }
        }

        /// sum |omega_i| d_i over a ghost's sources.
        double spread_of(size_t ghost, const std::vector<double>& d) const
        {
            double sum = 0.0;
            for (const GhostSource& source : lat_.ghost_sources(ghost))
                sum += std::abs(double(source.weight)) * d[source.cell];
            return sum;
        }

        const StoneState& st_;
        const SlabLattice& lat_;
        const SlabGrid& g_;
        const std::array<std::vector<float>, 6>& w_;
        const std::vector<float>& vol_;
        const std::vector<float>& phi_;
    };

} // namespace

double transport_rate_bound(const StoneState& st, int products)
{
    double d_max = 0.0;
    for (double d : st.params.diffusivity)
        d_max = std::max(d_max, d);
    const double h = 0.5 * st.params.pressure_diffusivity * d_max;
    const TransportMajorant M(st);
    const size_t n = st.lattice->grid().cell_count();
    std::vector<double> d(n, 0.0), Md(n, 0.0);
    for (size_t c = 0; c < n; ++c)
        d[c] = M.stone(c) ? 1.0 : 0.0;
    double bound = 0.0;
    for (int it = 0;; ++it) {
        M.apply(d, Md);
        const double ratio = tbb::parallel_reduce(
            tbb::blocked_range<size_t>(0, n), 0.0,
            [&](const tbb::blocked_range<size_t>& r, double worst) {
                for (size_t c = r.begin(); c < r.end(); ++c)
                    if (d[c] > 0.0)
                        worst = std::max(worst, Md[c] / d[c]);
                return worst;
            },
            [](double a, double b) { return std::max(a, b); });
        bound = it == 0 ? ratio : std::min(bound, ratio);
        if (it + 1 >= products || !(ratio > 0.0))
            break;
        // d <- (M + sigma) d, scaled to a largest entry of 1: the shift keeps every stone
        // voxel's entry positive (a voxel without partners has a zero row); the ratios are
        // taken with M itself.
        const double sigma = 0.01 * ratio;
        double top = 0.0;
        for (size_t c = 0; c < n; ++c)
            if (d[c] > 0.0) {
                d[c] = Md[c] + sigma * d[c];
                top = std::max(top, d[c]);
            }
        for (double& x : d)
            x /= top;
    }
    return h * bound;
}

int transport_interval_limit(const StoneState& st)
{
    const double rate = transport_rate_bound(st, kTransportBoundProducts);
    if (!(rate > 0.0))
        return 1;
    const double span = 1.8 / rate;  // 0.9 of the limit 2 / rho(L)
    return std::max(1, int(std::min(span / st.dt, 1e6)));
}

} // namespace patina::texgen::stone
