// bench_stone_sim: voxel updates per second of the stone simulation's moisture and transport
// step (Dorsey et al. 1999 §4.3) on a grid of the paper's size (the sphinx: 281 slabs of 32^3
// voxels), against a memory-bandwidth bound measured in the same run: a streaming copy of the
// arrays the step touches. Prints the ratio (target >= 0.3) and the projected time of 1000
// wet/dry cycles (target < 10 minutes on 2 cores), from whole cycles timed with their
// erosion events (the default parameters, as `patina-texgen stone` runs them).
//
//   bench_stone_sim [--tangential N] [--depth N] [--threads N] [--warm-cycles N]
//                   [--cycles N]     run N timed cycles, the moist depth every N/10
//                                    (--warm-cycles 0 --cycles 1000: the whole run the
//                                    issue's target is about, measured, not projected)
//                   [--check N]      run N cycles and print a hash of the state (to compare
//                                    builds bit for bit) and totals of the weathering, then exit
//                   [--deposit D]    a deposit map of D per unit area on every column (black
//                                    crust and salt supply; default 0)
//                   [--transport-interval N]  moisture steps per transport step (default:
//                                    the solutes' stability limit; 1 gives the results of the
//                                    code before the transport had its own step)
#include "core/mesh.h"
#include "texgen/stone/quarry.h"
#include "texgen/slabs/slab_lattice.h"
#include "texgen/stone/stone_state.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <ctime>
#include <string>
#include <vector>

using namespace patina;
using namespace patina::texgen::stone;
using Clock = std::chrono::steady_clock;

static double seconds_since(Clock::time_point t)
{
    return std::chrono::duration<double>(Clock::now() - t).count();
}

/// CPU time of the process (all threads), in seconds.
static double cpu_seconds()
{
    timespec t{};
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// FNV-1a over the interior voxels of every field that carries the simulation's state
/// (pressure only where it is used: moist stone voxels).
static uint64_t state_hash(const StoneState& st)
{
    const SlabGrid& g = st.lattice->grid();
    uint64_t h = 1469598103934665603ull;
    auto mix = [&](float v) {
        uint32_t bits;
        std::memcpy(&bits, &v, 4);
        for (int b = 0; b < 4; ++b)
            h = (h ^ ((bits >> (8 * b)) & 0xffu)) * 1099511628211ull;
    };
    std::vector<const std::vector<float>*> fields = {&st.density, &st.moisture, &st.black,
                                                     &st.decay, &st.wet_time};
    for (int m = 0; m < kSpecies; ++m)
        for (auto* f : {&st.solid[m], &st.dissolved[m], &st.crust[m]})
            fields.push_back(f);
    for (int s = 0; s < g.slab_count; ++s)
        for (int k = 0; k < g.n_d; ++k)
            for (int j = 0; j < g.n_t; ++j)
                for (int i = 0; i < g.n_t; ++i) {
                    const size_t c = g.index(s, i, j, k);
                    for (auto* f : fields)
                        mix((*f)[c]);
                    if ((st.flags[c] & kStone) && st.moisture[c] >= 0.5f)
                        mix(st.pressure[c]);
                }
    return h;
}

/// What the weathering has done so far, summed over the stone (to compare runs that differ
/// in their bits, e.g. --transport-interval).
static void print_totals(const StoneState& st)
{
    const SlabGrid& g = st.lattice->grid();
    const auto& vol = st.lattice->volume();
    double black = 0.0, decay = 0.0, lost = 0.0, volume = 0.0;
    std::array<double, kSpecies> crust{}, dissolved{};
    for (int s = 0; s < g.slab_count; ++s)
        for (int k = 0; k < g.n_d; ++k)
            for (int j = 0; j < g.n_t; ++j)
                for (int i = 0; i < g.n_t; ++i) {
                    const size_t c = g.index(s, i, j, k);
                    const double v = vol[c];
                    black += v * st.black[c];
                    decay += v * st.decay[c];
                    lost += v * (1.0 - st.density[c]);
                    volume += v;
                    for (int m = 0; m < kSpecies; ++m) {
                        crust[size_t(m)] += v * st.crust[m][c];
                        dissolved[size_t(m)] += v * st.dissolved[m][c];
                    }
                }
    std::printf("totals (volume-weighted means): black crust %.4g, decay %.4g, density lost "
                "%.4g; crust binder/iron/salt %.4g %.4g %.4g; dissolved %.4g %.4g %.4g\n",
                black / volume, decay / volume, lost / volume, crust[0] / volume,
                crust[1] / volume, crust[2] / volume, dissolved[0] / volume,
                dissolved[1] / volume, dissolved[2] / volume);
}

/// Mean and largest active depth (layers a step works on) over the slabs.
static void print_activity(const StoneState& st, const char* when)
{
    const SlabGrid& g = st.lattice->grid();
    double sum = 0.0;
    int top = 0;
    for (int a : st.active_depth) {
        sum += a;
        top = std::max(top, a);
    }
    // Slabs per active depth: a few slabs with a deep surface (eroded, or cut at a slant)
    // carry most of the active layers.
    std::vector<int> slabs_at(size_t(g.n_d) + 1);
    for (int a : st.active_depth)
        ++slabs_at[size_t(a)];
    std::printf("  slabs per active depth:");
    for (int k = 0; k <= g.n_d; ++k)
        if (slabs_at[size_t(k)])
            std::printf(" %d:%d", k, slabs_at[size_t(k)]);
    std::printf("\n");
    size_t moist = 0;
    for (size_t c = 0; c < st.moisture.size(); ++c)
        moist += (st.flags[c] & kStone) && st.moisture[c] >= 0.5f;
    // What a step would visit with a depth per column instead of per slab: each column down
    // to 2 layers below the deepest moist or surface voxel of itself and its 4 face
    // neighbours (edge columns: the slab's depth, their neighbours lie across a seam).
    double column_layers = 0.0;
    {
        std::vector<int> deepest(size_t(g.n_t) * g.n_t);
        for (int s = 0; s < g.slab_count; ++s) {
            for (int j = 0; j < g.n_t; ++j)
                for (int i = 0; i < g.n_t; ++i) {
                    int d = 0;
                    for (int k = 0; k < g.n_d; ++k) {
                        const size_t c = g.index(s, i, j, k);
                        const bool moist = (st.flags[c] & kStone) && st.moisture[c] >= 0.5f;
                        if ((st.flags[c] & kSurface) || moist)
                            d = k + 1;
                    }
                    deepest[size_t(j) * g.n_t + size_t(i)] = d;
                }
            for (int j = 0; j < g.n_t; ++j)
                for (int i = 0; i < g.n_t; ++i) {
                    if (i == 0 || j == 0 || i == g.n_t - 1 || j == g.n_t - 1) {
                        column_layers += st.active_depth[size_t(s)];
                        continue;
                    }
                    int d = deepest[size_t(j) * g.n_t + size_t(i)];
                    d = std::max({d, deepest[size_t(j) * g.n_t + size_t(i - 1)],
                                  deepest[size_t(j) * g.n_t + size_t(i + 1)],
                                  deepest[size_t(j - 1) * g.n_t + size_t(i)],
                                  deepest[size_t(j + 1) * g.n_t + size_t(i)]});
                    column_layers += std::min(g.n_d, d + 2);
                }
        }
    }
    // Rows (along u) of the active layers that hold a moist or surface voxel: the rows the
    // steps work on (texgen/stone_rows/live_rows.h); the others are only streamed past.
    size_t rows = 0, live_rows = 0;
    for (int s = 0; s < g.slab_count; ++s)
        for (int k = 0; k < st.active_depth[size_t(s)]; ++k)
            for (int j = 0; j < g.n_t; ++j) {
                ++rows;
                for (int i = 0; i < g.n_t; ++i) {
                    const size_t c = g.index(s, i, j, k);
                    if ((st.flags[c] & kSurface) || st.moisture[c] >= 0.5f) {
                        ++live_rows;
                        break;
                    }
                }
            }
    std::printf("  live rows: %.1f%% of the active layers' rows\n",
                100.0 * double(live_rows) / double(std::max<size_t>(rows, 1)));
    std::printf("  layers per column if per column: mean %.2f\n",
                column_layers / (double(g.slab_count) * g.n_t * g.n_t));
    std::printf("%s: moist depth %.3g m, %zu moist voxels (%.1f%%), active layers per slab "
                "mean %.2f, max %d of %d\n", when, moist_depth(st), moist,
                100.0 * double(moist) / double(g.voxel_count()), sum / g.slab_count, top, g.n_d);
}

int main(int argc, char** argv)
{
    int n_t = 32, n_d = 32, threads = 2, warm = 20, cycles = 3, check = 0, transport_interval = 0;
    double deposit = 0.0;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        const int v = std::atoi(argv[i + 1]);
        if (a == "--tangential") n_t = v;
        else if (a == "--depth") n_d = v;
        else if (a == "--threads") threads = v;
        else if (a == "--warm-cycles") warm = v;
        else if (a == "--cycles") cycles = std::max(1, v);
        else if (a == "--check") check = v;
        else if (a == "--transport-interval") transport_interval = v;
        else if (a == "--deposit") deposit = std::atof(argv[i + 1]);
        else {
            std::fprintf(stderr, "bench_stone_sim: unknown option '%s'\n", a.c_str());
            return 2;
        }
    }
    tbb::global_control control(tbb::global_control::max_allowed_parallelism, threads);

    // A sandstone column-like blob: a uv sphere of 8 x 7 (94 triangles after the poles'
    // collapsed ones are dropped -> ~282 slabs), 1 m across.
    const auto t_setup = Clock::now();
    const TriangleMesh mesh = make_uv_sphere(Imath::V3f(0.0f), 0.5f, 7, 8);
    ShellOptions so;
    so.depth = 0.15;
    so.outer_margin = 1.5 * so.depth / n_d;
    so.depth += so.outer_margin;
    const SlabShell shell = build_slab_shell(mesh, so);
    const SlabLattice lattice(shell, n_t, n_d);
    QuarryOptions q;
    q.kind = StoneKind::sandstone;
    q.feature_size = 0.05;
    // The default parameters (erosion events included), rain from above and the side as the
    // wetness baker's inclination term gives it: 0.3 on vertical faces, 1 on top, 0.3 below.
    StoneParameters params;
    StoneState st;
    initialise_state(st, lattice, mesh, Quarry(q), params);
    for (size_t c = 0; c < st.columns.size(); ++c)
        st.column_wetness[c] = 0.3f + 0.7f * std::max(0.0f, st.columns[c].N.y);
    if (deposit > 0.0) {
        std::fill(st.column_deposit.begin(), st.column_deposit.end(), float(deposit));
        st.params.salt_supply = 0.01;
    }
    if (transport_interval > 0)
        st.transport_interval = transport_interval;
    const SlabGrid& g = lattice.grid();
    std::printf("grid: %d slabs of %d x %d x %d = %zu voxels (%zu cells with halo); set-up %.1f s\n",
                g.slab_count, n_t, n_t, n_d, g.voxel_count(), g.cell_count(),
                seconds_since(t_setup));
    std::printf("dt %.4g, a cycle of %d + %d steps is %.4g time units; a transport step every "
                "%d steps\n", st.dt, params.wet_steps, params.dry_steps,
                st.dt * (params.wet_steps + params.dry_steps), st.transport_interval);

    if (check > 0) {
        for (int c = 0; c < check; ++c)
            run_cycle(st);
        print_activity(st, "after the check cycles");
        print_totals(st);
        std::printf("state hash after %d cycles: %016llx\n", check,
                    (unsigned long long)state_hash(st));
        return 0;
    }

    // Warm up: let the moist zone reach into the stone so the step does its full work.
    const auto t_warm = Clock::now();
    for (int c = 0; c < warm; ++c)
        run_cycle(st);
    std::printf("%d warm-up cycles: %.1f s\n", warm, seconds_since(t_warm));
    print_activity(st, "after warm-up");

    // Timed: wet and dry steps (moisture, and transport every transport_interval steps as
    // run_cycle does), the best of 3 rounds of 8 steps.
    const int steps = 8;
    double best = 1e30;
    for (int round = 0; round < 3; ++round) {
        const auto t = Clock::now();
        for (int s = 0; s < steps; ++s) {
            moisture_step(st, s < steps / 2);
            if ((s + 1) % st.transport_interval == 0)
                transport_step(st, s < steps / 2, st.transport_interval);
        }
        best = std::min(best, seconds_since(t) / steps);
    }
    double active_voxels = 0.0;
    for (int a : st.active_depth)
        active_voxels += double(a) * n_t * n_t;
    const double updates = double(g.voxel_count()) / best;

    // Bound: one streaming copy of every array the step reads or writes, per step.
    std::vector<const std::vector<float>*> arrays = {
        &st.density, &st.porosity, &st.permeability, &st.head, &st.moisture, &st.pressure,
        &st.black, &st.decay, &st.wet_time, &lattice.volume()};
    for (int m = 0; m < kSpecies; ++m)
        for (auto* a : {&st.solid[m], &st.dissolved[m], &st.crust[m], &st.concentration[m]})
            arrays.push_back(a);
    for (const auto& w : lattice.weights())
        arrays.push_back(&w);
    size_t bytes = st.flags.size();
    for (auto* a : arrays)
        bytes += a->size() * sizeof(float);
    std::vector<float> sink(g.cell_count());
    std::vector<uint8_t> flag_sink(st.flags.size());
    double copy_best = 1e30;
    for (int round = 0; round < 3; ++round) {
        const auto t = Clock::now();
        for (auto* a : arrays) {
            const float* src = a->data();
            tbb::parallel_for(tbb::blocked_range<size_t>(0, a->size(), 1 << 16),
                              [&](const tbb::blocked_range<size_t>& r) {
                                  std::memcpy(sink.data() + r.begin(), src + r.begin(),
                                              r.size() * sizeof(float));
                              });
        }
        std::memcpy(flag_sink.data(), st.flags.data(), st.flags.size());
        copy_best = std::min(copy_best, seconds_since(t));
    }
    const double bound = double(g.voxel_count()) / copy_best;
    // The same copy restricted to the active layers: the bound of a step that skips the rest.
    const double active_share = active_voxels / double(g.voxel_count());
    std::printf("step: %.4f s = %.3g voxel updates/s of the whole grid, %.3g of the active "
                "layers (%.1f%% of the grid; moisture + transport, %d threads)\n", best, updates,
                active_voxels / best, 100.0 * active_share, threads);
    std::printf("bound: streaming copy of the step's %zu arrays (%.2f GB) in %.3f s = %.2f GB/s "
                "= %.3g voxel updates/s\n", arrays.size() + 1, bytes * 1e-9, copy_best,
                2.0 * bytes * 1e-9 / copy_best, bound);
    std::printf("ratio step / bound: %.2f over the whole grid (target >= 0.3); %.2f against a "
                "copy of the active layers only\n", updates / bound,
                active_share * copy_best / best);

    // Whole cycles (steps, erosion events, flags), as the command runs them; also the CPU
    // time they take (all threads), which other processes on the machine disturb less.
    const double cpu_start = cpu_seconds();
    const StoneState::PhaseSeconds phase_start = st.phase_seconds;
    const auto t_cycles = Clock::now();
    double reporting = 0.0, reporting_cpu = 0.0;  // print_activity's scans, not timed
    for (int c = 0; c < cycles; ++c) {
        run_cycle(st);
        if (cycles >= 10 && (c + 1) % (cycles / 10) == 0) {
            const auto t_report = Clock::now();
            const double cpu_report = cpu_seconds();
            std::printf("  cycle %d: %.1f s, ", warm + c + 1,
                        seconds_since(t_cycles) - reporting);
            print_activity(st, "state");
            std::fflush(stdout);
            reporting += seconds_since(t_report);
            reporting_cpu += cpu_seconds() - cpu_report;
        }
    }
    const double run_seconds = seconds_since(t_cycles) - reporting;
    const double per_cycle = run_seconds / cycles;
    const double cpu_per_cycle = (cpu_seconds() - cpu_start - reporting_cpu) / cycles;
    std::printf("cycle (%d + %d steps, erosion events): %.3f s over %d cycles (%.3f CPU s per "
                "cycle, %d threads)\n", params.wet_steps, params.dry_steps, per_cycle, cycles,
                cpu_per_cycle, threads);
    const StoneState::PhaseSeconds& ph = st.phase_seconds;
    std::printf("  per cycle: moisture steps %.3f s, transport steps %.3f s, erosion events "
                "and flags %.3f s\n", (ph.moisture - phase_start.moisture) / cycles,
                (ph.transport - phase_start.transport) / cycles,
                (ph.erosion - phase_start.erosion) / cycles);
    // A cycle's cost changes over a run (the surface roughens as it erodes and the moist band
    // spreads over more layers, then the shell erodes through): only a whole run from the
    // initial state measures the target; a few cycles after a warm-up project it.
    if (warm == 0 && cycles == 1000)
        std::printf("1000 wet/dry cycles from the initial state: %.1f min, measured (target < 10)\n",
                    run_seconds / 60.0);
    else
        std::printf("projected 1000 wet/dry cycles: %.1f min from cycles %d-%d (target < 10; "
                    "measure with --warm-cycles 0 --cycles 1000)\n",
                    1000.0 * per_cycle / 60.0, warm + 1, warm + cycles);
    return 0;
}
