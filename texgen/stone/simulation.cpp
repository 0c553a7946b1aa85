// Set-up and the cycle driver of the weathering simulation (Dorsey et al. 1999 §4.3).
#include "texgen/stone/stone_state.h"

#include "core/huge_pages.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_reduce.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <stdexcept>

namespace patina::texgen::stone {

using Imath::V3d;

namespace {

    void check_parameters(const StoneParameters& p)
    {
        auto positive = [](double v, const char* name) {
            if (!(v > 0.0) || !std::isfinite(v))
                throw std::runtime_error(fmt::format("stone: {} must be > 0 (got {})", name, v));
        };
        auto non_negative = [](double v, const char* name) {
            if (!(v >= 0.0) || !std::isfinite(v))
                throw std::runtime_error(fmt::format("stone: {} must be >= 0 (got {})", name, v));
        };
        positive(p.pressure_diffusivity, "pressure diffusivity");
        positive(p.viscosity, "viscosity");
        non_negative(p.surface_pressure, "surface pressure");
        non_negative(p.gravity, "gravity");
        non_negative(p.permeability_scale, "permeability scale");
        non_negative(p.evaporation_speed, "evaporation speed");
        for (int i = 0; i < kSpecies; ++i) {
            non_negative(p.solubility[i], "solubility");
            non_negative(p.saturation[i], "saturation");
            non_negative(p.diffusivity[i], "diffusivity");
        }
        non_negative(p.crystallisation_rate, "crystallisation rate");
        non_negative(p.black_crust_rate, "black crust rate");
        non_negative(p.salt_supply, "salt supply");
        non_negative(p.erosion_events, "erosion events");
        positive(p.erosion_radius, "erosion radius");
        non_negative(p.erosion_amount, "erosion amount");
        if (p.wet_steps < 0 || p.dry_steps < 0 || p.wet_steps + p.dry_steps == 0)
            throw std::runtime_error("stone: a cycle needs at least one wet or dry step");
        if (!(p.up.length() > 0.0))
            throw std::runtime_error("stone: the up direction is zero");
    }

} // namespace

void initialise_state(StoneState& st, const SlabLattice& lattice, const TriangleMesh& mesh,
                      const Quarry& quarry, const StoneParameters& params,
                      std::vector<float> wetness, std::vector<float> deposit)
{
    check_parameters(params);
    st = StoneState{};
    st.lattice = &lattice;
    st.params = params;
    const SlabGrid& g = lattice.grid();
    const size_t cells = g.cell_count();
    voxelize(lattice, mesh, st.density, st.columns);
    const size_t n_columns = st.columns.size();
    if (wetness.empty())
        wetness.assign(n_columns, 1.0f);
    if (deposit.empty())
        deposit.assign(n_columns, 0.0f);
    if (wetness.size() != n_columns || deposit.size() != n_columns)
        throw std::runtime_error("stone: wetness and deposit need one value per slab column");
    st.column_wetness = std::move(wetness);
    st.column_deposit = std::move(deposit);

    // The steps read the fields at a layer's distance apart: huge pages (core/huge_pages.h).
    advise_huge_pages(st.density);
    for (std::vector<float>* f : {&st.porosity, &st.permeability, &st.head, &st.moisture,
                                  &st.pressure, &st.black, &st.decay, &st.wet_time}) {
        f->assign(cells, 0.0f);
        advise_huge_pages(*f);
    }
    for (int i = 0; i < kSpecies; ++i)
        for (auto* f : {&st.solid[i], &st.dissolved[i], &st.crust[i], &st.concentration[i]}) {
            f->assign(cells, 0.0f);
            advise_huge_pages(*f);
        }
    st.colour.assign(cells, Imath::V3f(0.0f));
    st.flags.assign(cells, 0);
    advise_huge_pages(st.flags);

    // The quarry at every voxel centre; the head rho g (up . x) for Darcy's gravity term.
    const V3d up = params.up.normalized();
    tbb::parallel_for(0, g.slab_count, [&](int s) {
        for (int k = 0; k < g.n_d; ++k)
            for (int j = 0; j < g.n_t; ++j)
                for (int i = 0; i < g.n_t; ++i) {
                    const size_t c = g.index(s, i, j, k);
                    const Imath::V3f& pf = lattice.position()[c];
                    const V3d p(pf.x, pf.y, pf.z);
                    const StoneSample q = quarry.at(p);
                    st.porosity[c] = std::max(q.porosity, 1e-4f);
                    st.permeability[c] = float(q.permeability * params.permeability_scale);
                    for (int m = 0; m < kSpecies; ++m)
                        st.solid[m][c] = q.mineral[m] * st.density[c];
                    st.colour[c] = q.colour;
                    st.head[c] = float(params.gravity * up.dot(p));
                }
    });
    for (std::vector<float>* f : {&st.porosity, &st.permeability, &st.head})
        lattice.fill_halo(f->data());
    update_flags(st);

    // dt: forward Euler is stable for dt <= 2 / rho(L); Gershgorin bounds rho(L) by
    // |centre| + sum |off-diagonal| = 2 sum c + 2 sum |c|; keep a margin of 0.4. The solutes
    // (transport.cpp) diffuse at alpha D_i phi, at most d_max times the pressure's rate, and
    // their pairwise couplings at most double the Gershgorin sum: still below 2 / rho.
    double g_max = 0.0;
    float phi_max = 0.0f;
    for (size_t c = 0; c < cells; ++c) {
        if (!(st.flags[c] & kStone))
            continue;
        double sum = 0.0, abs_sum = 0.0;
        for (int d = 0; d < 6; ++d) {
            sum += lattice.weights()[d][c];
            abs_sum += std::abs(lattice.weights()[d][c]);
        }
        g_max = std::max(g_max, 2.0 * std::abs(sum) + 2.0 * abs_sum);
        phi_max = std::max(phi_max, st.porosity[c]);
    }
    if (!(g_max > 0.0))
        throw std::runtime_error("stone: no stone voxel inside the slab shell (is the mesh "
                                 "closed and the shell around its surface?)");
    double d_max = 1.0;
    for (double d : params.diffusivity)
        d_max = std::max(d_max, d);
    st.dt = 0.4 * 2.0 / (params.pressure_diffusivity * d_max * phi_max * g_max);
    // The solutes' own limit (transport_bound.cpp): a transport step spans as many moisture
    // steps as a bound on its operator's spectral radius allows (8 on the benchmark's
    // paper-size grid with the default D_i = 0.5: once per phase; the transport, most of a
    // step's cost, runs that much less often). The dt above keeps even a single step
    // stable: d_max covers D_i > 1.
    st.transport_interval = transport_interval_limit(st);
}

void update_flags(StoneState& st)
{
    st.pressure_preset_depth.clear();  // the surface moves: its Dirichlet values too
    const SlabLattice& lat = *st.lattice;
    const SlabGrid& g = lat.grid();
    const size_t layers = size_t(g.slab_count) * size_t(g.n_d);
    // A voxel's flags depend on its density and its six face neighbours': after the first
    // call, only layers with a changed row in them or next to them, or with a changed source
    // of their ghosts, are recomputed (erosion changes a few layers near the surface; it
    // marks what it changes in density_halo).
    const bool first = st.surface_layer.size() != layers || st.density_halo.row_changed.empty();
    std::vector<uint8_t> redo(layers, 1);
    if (!first) {
        const auto& changed = st.density_halo.layer_changed;
        tbb::parallel_for(0, g.slab_count, [&](int s) {
            for (int k = 0; k < g.n_d; ++k) {
                // Haloed layer k + 1 holds layer k.
                const size_t at = size_t(s) * size_t(g.sz) + size_t(k) + 1;
                redo[size_t(s) * size_t(g.n_d) + size_t(k)] =
                    uint8_t(changed[at - 1] | changed[at] | changed[at + 1] |
                            uint8_t(lat.ghost_sources_changed(s, k, st.density_halo)));
            }
        });
    }
    if (first)
        st.surface_layer.assign(layers, 0);
    lat.fill_halo(st.density.data(), nullptr, &st.density_halo);
    st.surface_depth.assign(size_t(g.slab_count), 0);
    const long dj = lat.axis_offset(1), dk = lat.axis_offset(2);
    tbb::parallel_for(0, g.slab_count, [&](int s) {
        for (int k = 0; k < g.n_d; ++k) {
            const size_t layer = size_t(s) * size_t(g.n_d) + size_t(k);
            if (redo[layer]) {
                int any_surface = 0;
                for (int j = 0; j < g.n_t; ++j) {
                    const size_t row = g.index(s, 0, j, k);
                    const float* rho = st.density.data() + row;
                    uint8_t* flags = st.flags.data() + row;
                    // Branch-free over the row, so that it vectorises. A surface voxel
                    // touches air across a face; the outer layer always counts as surface
                    // (above it is air).
                    for (int i = 0; i < g.n_t; ++i) {
                        const int stone = int(rho[i] >= 0.5f);
                        const int air = int(k == 0) | int(rho[i - 1] < 0.5f) |
                                        int(rho[i + 1] < 0.5f) | int(rho[i - dj] < 0.5f) |
                                        int(rho[i + dj] < 0.5f) | int(rho[i - dk] < 0.5f) |
                                        int(rho[i + dk] < 0.5f);
                        const int surface = stone & air;
                        flags[i] = uint8_t(stone * kStone | surface * kSurface);
                        any_surface |= surface;
                    }
                }
                st.surface_layer[layer] = uint8_t(any_surface);
            }
            if (st.surface_layer[layer])
                st.surface_depth[size_t(s)] = k + 1;
        }
    });
    // Erosion never adds moisture (what crumbles dries): the deepest moist layer is no
    // deeper than before, and the scan can start from the old active depth.
    if (first)
        update_active_depth(st);
    else
        refresh_active_depth(st);
}

namespace {

    /// active_depth of every slab, scanning each from layer `from(s)` - 1 up to its surface.
    template <class From>
    void scan_active_depth(StoneState& st, From&& from)
    {
        const SlabGrid& g = st.lattice->grid();
        tbb::parallel_for(0, g.slab_count, [&](int s) {
            int deepest = st.surface_depth.empty() ? g.n_d : st.surface_depth[size_t(s)];
            for (int k = from(s) - 1; k >= deepest; --k) {
                bool moist = false;
                for (int j = 0; j < g.n_t && !moist; ++j)
                    for (int i = 0; i < g.n_t && !moist; ++i)
                        moist = st.moisture[g.index(s, i, j, k)] >= 0.5f;
                if (moist) {
                    deepest = k + 1;
                    break;
                }
            }
            st.active_depth[size_t(s)] = std::min(g.n_d, deepest + 2);
        });
    }

} // namespace

void update_active_depth(StoneState& st)
{
    const SlabGrid& g = st.lattice->grid();
    st.active_depth.resize(size_t(g.slab_count));
    scan_active_depth(st, [&](int) { return g.n_d; });
}

void refresh_active_depth(StoneState& st)
{
    // No moist voxel lies at or below the old active depth (the deepest moist layer + 3
    // before the step, and the front moved at most one layer).
    scan_active_depth(st, [&](int s) { return st.active_depth[size_t(s)]; });
}

double species_mass(const StoneState& st, int m)
{
    const SlabGrid& g = st.lattice->grid();
    const auto& vol = st.lattice->volume();
    return tbb::parallel_deterministic_reduce(
        tbb::blocked_range<int>(0, g.slab_count), 0.0,
        [&](const tbb::blocked_range<int>& r, double acc) {
            for (int s = r.begin(); s < r.end(); ++s)
                for (int k = 0; k < g.n_d; ++k)
                    for (int j = 0; j < g.n_t; ++j)
                        for (int i = 0; i < g.n_t; ++i) {
                            const size_t c = g.index(s, i, j, k);
                            double a = double(st.solid[m][c]) + st.dissolved[m][c] +
                                       st.crust[m][c];
                            if (m == kSoluble)
                                a += st.black[c];
                            acc += a * vol[c];
                        }
            return acc;
        },
        std::plus<double>());
}

void check_state_finite(const StoneState& st)
{
    const SlabGrid& g = st.lattice->grid();
    static const char* const kSpeciesNames[kSpecies] = {"binder", "iron", "salt"};
    auto check = [&](const std::vector<float>& field, const std::string& name) {
        for (int s = 0; s < g.slab_count; ++s)
            for (int k = 0; k < g.n_d; ++k)
                for (int j = 0; j < g.n_t; ++j)
                    for (int i = 0; i < g.n_t; ++i)
                        if (!std::isfinite(field[g.index(s, i, j, k)]))
                            throw std::runtime_error(fmt::format(
                                "stone: the simulation diverged: {} is {} at slab {} voxel "
                                "({}, {}, {}) after {} cycles; nothing written",
                                name, field[g.index(s, i, j, k)], s, i, j, k, st.cycles_done));
    };
    check(st.density, "density");
    check(st.moisture, "moisture");
    check(st.pressure, "pressure");
    check(st.decay, "decay index");
    check(st.black, "black crust");
    for (int m = 0; m < kSpecies; ++m) {
        check(st.solid[m], fmt::format("solid {}", kSpeciesNames[m]));
        check(st.dissolved[m], fmt::format("dissolved {}", kSpeciesNames[m]));
        check(st.crust[m], fmt::format("{} crust", kSpeciesNames[m]));
    }
}

double moist_depth(const StoneState& st, const std::vector<char>* selector)
{
    const SlabLattice& lat = *st.lattice;
    const SlabGrid& g = lat.grid();
    double sum = 0.0;
    size_t n = 0;
    for (int s = 0; s < g.slab_count; ++s)
        for (int j = 0; j < g.n_t; ++j)
            for (int i = 0; i < g.n_t; ++i) {
                const size_t col = column_index(g, s, i, j);
                if (selector && !(*selector)[col])
                    continue;
                // Depth: moist stone voxels times the depth step, along the column.
                double depth = 0.0;
                for (int k = 0; k < g.n_d; ++k) {
                    const size_t c = g.index(s, i, j, k);
                    if ((st.flags[c] & kStone) && st.moisture[c] >= 0.5f) {
                        const float h = 1.0f / std::sqrt(lat.weights()[2][c] +
                                                         lat.weights()[4][c] +
                                                         lat.weights()[5][c]);
                        depth += h;
                    }
                }
                sum += depth;
                ++n;
            }
    return n ? sum / double(n) : 0.0;
}

void run_cycle(StoneState& st)
{
    using Clock = std::chrono::steady_clock;
    auto timed = [](double& total, auto&& work) {
        const auto start = Clock::now();
        work();
        total += std::chrono::duration<double>(Clock::now() - start).count();
    };
    StoneState::PhaseSeconds& sec = st.phase_seconds;
    auto phase = [&](int steps, bool wet) {
        int pending = 0;
        for (int i = 0; i < steps; ++i) {
            timed(sec.moisture, [&] { moisture_step(st, wet); });
            st.time += st.dt;
            if (++pending == st.transport_interval || i + 1 == steps) {
                timed(sec.transport, [&] { transport_step(st, wet, pending); });
                pending = 0;
            }
        }
    };
    phase(st.params.wet_steps, true);
    phase(st.params.dry_steps, false);
    timed(sec.erosion, [&] { erosion_events(st); });
    ++st.cycles_done;
}

} // namespace patina::texgen::stone
