// bench_stone_sim: voxel updates per second of the stone simulation's moisture and transport
// step (Dorsey et al. 1999 §4.3) on a grid of the paper's size (the sphinx: 281 slabs of 32^3
// voxels), against a memory-bandwidth bound measured in the same run: a streaming copy of the
// arrays the step touches. Prints the ratio (target >= 0.3) and the projected time of 1000
// wet/dry cycles (target < 10 minutes on 2 cores).
//
//   bench_stone_sim [--tangential N] [--depth N] [--threads N] [--warm-cycles N]
#include "core/mesh.h"
#include "texgen/stone/quarry.h"
#include "texgen/stone/slab_lattice.h"
#include "texgen/stone/stone_state.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

using namespace patina;
using namespace patina::texgen::stone;
using Clock = std::chrono::steady_clock;

static double seconds_since(Clock::time_point t)
{
    return std::chrono::duration<double>(Clock::now() - t).count();
}

int main(int argc, char** argv)
{
    int n_t = 32, n_d = 32, threads = 2, warm = 20;
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string a = argv[i];
        const int v = std::atoi(argv[i + 1]);
        if (a == "--tangential") n_t = v;
        else if (a == "--depth") n_d = v;
        else if (a == "--threads") threads = v;
        else if (a == "--warm-cycles") warm = v;
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
    StoneParameters params;
    params.erosion_events = 0.0;
    StoneState st;
    initialise_state(st, lattice, mesh, Quarry(q), params);
    const SlabGrid& g = lattice.grid();
    std::printf("grid: %d slabs of %d x %d x %d = %zu voxels (%zu cells with halo); set-up %.1f s\n",
                g.slab_count, n_t, n_t, n_d, g.voxel_count(), g.cell_count(),
                seconds_since(t_setup));

    // Warm up: let the moist zone reach into the stone so the step does its full work.
    const auto t_warm = Clock::now();
    for (int c = 0; c < warm; ++c)
        run_cycle(st);
    std::printf("%d warm-up cycles: %.1f s, moist depth %.3g m\n", warm, seconds_since(t_warm),
                moist_depth(st));

    // Timed: wet and dry steps (moisture + transport), the best of 3 rounds of 8 steps.
    const int steps = 8;
    double best = 1e30;
    for (int round = 0; round < 3; ++round) {
        const auto t = Clock::now();
        for (int s = 0; s < steps; ++s) {
            moisture_step(st, s < steps / 2);
            transport_step(st, s < steps / 2);
        }
        best = std::min(best, seconds_since(t) / steps);
    }
    const double updates = double(g.voxel_count()) / best;

    // Bound: one streaming copy of every array the step reads or writes, per step.
    std::vector<const std::vector<float>*> arrays = {
        &st.density, &st.porosity, &st.permeability, &st.head, &st.moisture, &st.pressure,
        &st.scratch, &st.black, &st.decay, &st.wet_time, &lattice.volume()};
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
    const double per_cycle = best * (params.wet_steps + params.dry_steps);
    std::printf("step: %.3f s = %.3g voxel updates/s (moisture + transport, %d threads)\n", best,
                updates, threads);
    std::printf("bound: streaming copy of the step's %zu arrays (%.2f GB) in %.3f s = %.2f GB/s "
                "= %.3g voxel updates/s\n", arrays.size() + 1, bytes * 1e-9, copy_best,
                2.0 * bytes * 1e-9 / copy_best, bound);
    std::printf("ratio step / bound: %.2f (target >= 0.3)\n", updates / bound);
    std::printf("projected 1000 wet/dry cycles (%d + %d steps each): %.1f min (target < 10)\n",
                params.wet_steps, params.dry_steps, 1000.0 * per_cycle / 60.0);
    return 0;
}
