// The weathering simulation (Dorsey et al. 1999 §4.3): conservation, Darcy's front,
// erosion under rain, determinism.
#include "stone_test_util.h"

#include "test_util.h"
#include "core/sampling.h"
#include "texgen/stone_export/eroded_mesh.h"
#include "texgen/stone_rows/live_rows.h"
#include "texgen/stone_export/volume_export.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cstring>

namespace patina::texgen::stone {
namespace {

using Imath::V3d;

struct Scene {
    TriangleMesh mesh;
    test::TestLattice lat;
    StoneState st;
};

/// A sandstone box (0.4 m x 0.3 m x 0.4 m) of 36 slabs, 6 x 6 x 6 voxels each.
std::unique_ptr<Scene> sandstone_box(const StoneParameters& params,
                                     const std::vector<float>& wetness = {}, int n_t = 6,
                                     int n_d = 6)
{
    auto s = std::make_unique<Scene>();
    s->mesh = make_box(Imath::V3f(0.0f), Imath::V3f(0.4f, 0.3f, 0.4f));
    s->lat = test::make_lattice(s->mesh, n_t, n_d, 0.1);
    QuarryOptions q;
    q.kind = StoneKind::sandstone;
    q.feature_size = 0.05;
    initialise_state(s->st, *s->lat.lattice, s->mesh, Quarry(q), params, wetness);
    return s;
}

StoneParameters no_erosion()
{
    StoneParameters p;
    p.erosion_events = 0.0;
    return p;
}

/// `mesh` in stone of `kind` (feature size 5 cm) on a lattice of n_t x n_t x n_d voxels per
/// slab in a shell `depth` deep.
std::unique_ptr<Scene> stone_scene(TriangleMesh mesh, StoneKind kind, int n_t, int n_d,
                                   double depth, const StoneParameters& params)
{
    auto s = std::make_unique<Scene>();
    s->mesh = std::move(mesh);
    s->lat = test::make_lattice(s->mesh, n_t, n_d, depth);
    QuarryOptions q;
    q.kind = kind;
    q.feature_size = 0.05;
    initialise_state(s->st, *s->lat.lattice, s->mesh, Quarry(q), params);
    return s;
}

TEST(StoneSimulation, DissolvedMineralsPlusCrustConserveMass)
{
    auto s = sandstone_box(no_erosion());
    StoneState& st = s->st;
    double before[kSpecies];
    for (int m = 0; m < kSpecies; ++m)
        before[m] = species_mass(st, m);
    for (int c = 0; c < 20; ++c)
        run_cycle(st);
    double moved = 0.0;
    for (int m = 0; m < kSpecies; ++m) {
        const double after = species_mass(st, m);
        double dissolved = 0.0, crust = 0.0;
        for (size_t c = 0; c < st.density.size(); ++c) {
            dissolved += double(st.dissolved[m][c]) * st.lattice->volume()[c];
            crust += double(st.crust[m][c]) * st.lattice->volume()[c];
        }
        moved += dissolved + crust;
        std::printf("species %d: mass %.6g -> %.6g (relative change %.2e), dissolved %.3g, "
                    "crust %.3g\n", m, before[m], after, (after - before[m]) / before[m],
                    dissolved, crust);
        // Conservative fluxes, seams included (transport.cpp); what is left is the rounding
        // of float amounts (~1e-7 relative per update).
        EXPECT_NEAR(after, before[m], 1e-5 * before[m]) << "species " << m; // float rounding
    }
    EXPECT_GT(moved, 0.0) << "nothing dissolved: the test would be vacuous";
}

TEST(StoneSimulation, FrontMovesFasterWithHigherPermeability)
{
    double depth[2];
    for (int run = 0; run < 2; ++run) {
        StoneParameters p = no_erosion();
        p.permeability_scale = run == 0 ? 1.0 : 4.0;
        p.dry_steps = 0; // wet only: the front only advances
        auto s = sandstone_box(p);
        for (int c = 0; c < 6; ++c)
            run_cycle(s->st);
        depth[run] = moist_depth(s->st);
    }
    std::printf("moist depth: K x1 %.4g m, K x4 %.4g m\n", depth[0], depth[1]);
    EXPECT_GT(depth[1], 1.2 * depth[0]); // Darcy: v proportional to K (§4.3.2)
}

TEST(StoneSimulation, HorizontalSurfaceUnderRainErodesMoreThanAVerticalOne)
{
    StoneParameters p;
    p.seed = 3;
    // Rain falling straight down, as the wetness baker's inclination term makes it: the top
    // gets all of it, vertical faces the splash and run-off of 0.3.
    auto probe = sandstone_box(no_erosion());
    std::vector<float> wetness(probe->st.columns.size());
    for (size_t c = 0; c < wetness.size(); ++c)
        wetness[c] = 0.3f + 0.7f * std::max(0.0f, probe->st.columns[c].N.y);
    auto s = sandstone_box(p, wetness);
    StoneState& st = s->st;
    const std::vector<float> initial = st.density;
    for (int c = 0; c < 30; ++c)
        run_cycle(st);
    const SlabGrid& g = st.lattice->grid();
    double loss[2] = {0, 0}, area[2] = {0, 0};
    for (int sl = 0; sl < g.slab_count; ++sl)
        for (int j = 0; j < g.n_t; ++j)
            for (int i = 0; i < g.n_t; ++i) {
                const Imath::V3f N = st.columns[column_index(g, sl, i, j)].N;
                const int kind = N.y > 0.9f ? 0 : std::abs(N.y) < 0.1f ? 1 : -1;
                if (kind < 0)
                    continue;
                for (int k = 0; k < g.n_d; ++k) {
                    const size_t cell = g.index(sl, i, j, k);
                    loss[kind] += double(initial[cell] - st.density[cell]) *
                                  st.lattice->volume()[cell];
                }
                area[kind] += 1.0;
            }
    const double top = loss[0] / area[0], side = loss[1] / area[1];
    std::printf("density lost per column: top %.4g, sides %.4g\n", top, side);
    EXPECT_GT(side, 0.0); // the sides weather too, only less
    EXPECT_GT(top, 1.5 * side);
}

// The explicit transport step must stay bounded in a low-porosity stone where the moist
// zone is cut into ragged pieces: before the solutes' diffusivity was tied to the pressure's
// step limit and negative stencil couplings were clamped at cut stencils (transport.cpp),
// the marble statue's salt grew to 1e38 and then NaN after 20 cycles.
TEST(StoneSimulation, TransportStaysBoundedInMarbleWithARaggedMoistZone)
{
    StoneParameters p = no_erosion();
    p.solubility = {0.0, 0.0, 0.0}; // transport only: nothing dissolves
    // Marble: porosity 0.01-0.04.
    auto s = stone_scene(make_box(Imath::V3f(0.0f), Imath::V3f(0.4f, 0.3f, 0.4f)),
                         StoneKind::marble, 6, 6, 0.1, p);
    StoneState& st = s->st;
    // A random moist mask (30 %: small clusters, some joined only by a negative stencil
    // weight) and random dissolved salt, concentration in [0, 1].
    Pcg32 rng(7);
    double c_max = 0.0;
    for (size_t c = 0; c < st.density.size(); ++c) {
        if (!(st.flags[c] & kStone))
            continue;
        st.moisture[c] = rng.uniform_float() < 0.5f ? 1.0f : 0.0f;
        const float conc = rng.uniform_float();
        st.dissolved[kSalt][c] = conc * st.porosity[c] * st.density[c];
        c_max = std::max<double>(c_max, conc);
    }
    st.lattice->fill_halo(st.moisture.data());
    update_active_depth(st);
    // Steps of the span the simulation uses (transport_interval x dt: the solutes' limit).
    ASSERT_GE(st.transport_interval, 1);
    for (int step = 0; step < 400; ++step)
        transport_step(st, true, st.transport_interval);
    double worst = 0.0;
    for (size_t c = 0; c < st.density.size(); ++c)
        if (st.flags[c] & kStone) {
            const double water = double(st.porosity[c]) * st.density[c];
            worst = std::max(worst, std::abs(st.dissolved[kSalt][c] / water));
        }
    std::printf("largest |concentration| after 400 steps: %.4g (initially <= %.4g)\n", worst,
                c_max);
    ASSERT_TRUE(std::isfinite(worst));
    // Diffusion with the 13-point stencil's negative weights has no strict maximum principle,
    // but it must not amplify: allow a 10 % overshoot of the initial range.
    EXPECT_LT(worst, 1.1 * c_max);
}

/// The transport's diffusion operator L in the salt concentrations of the moist voxels
/// `moist` picks (C' = C - span L C), applied through transport_step itself: nothing
/// dissolves and no water moves (no gravity, pressure 0).
class TransportOperator {
public:
    TransportOperator(StoneState& st, const std::vector<char>& moist) : st_(st)
    {
        st.params.solubility = {0.0, 0.0, 0.0};
        std::fill(st.pressure.begin(), st.pressure.end(), 0.0f);
        std::fill(st.head.begin(), st.head.end(), 0.0f);
        for (size_t c = 0; c < st.density.size(); ++c) {
            st.moisture[c] = moist[c] ? 1.0f : 0.0f;
            if (moist[c])
                voxels_.push_back(c);
        }
        st.lattice->fill_halo(st.moisture.data());
        update_active_depth(st);
    }

    size_t size() const { return voxels_.size(); }

    /// C after one transport step of `steps` x dt.
    std::vector<double> step(const std::vector<double>& C, int steps)
    {
        for (size_t n = 0; n < voxels_.size(); ++n)
            st_.dissolved[kSalt][voxels_[n]] = float(C[n] * water(n));
        transport_step(st_, true, steps);
        std::vector<double> out(voxels_.size());
        for (size_t n = 0; n < voxels_.size(); ++n)
            out[n] = st_.dissolved[kSalt][voxels_[n]] / water(n);
        return out;
    }

    /// Norm weighted by the water volumes (L is symmetric in it away from the seams).
    double norm(const std::vector<double>& v) const
    {
        double sum = 0.0;
        for (size_t n = 0; n < voxels_.size(); ++n)
            sum += st_.lattice->volume()[voxels_[n]] * water(n) * v[n] * v[n];
        return std::sqrt(sum);
    }

private:
    double water(size_t n) const
    {
        return double(st_.porosity[voxels_[n]]) * st_.density[voxels_[n]];
    }

    StoneState& st_;
    std::vector<size_t> voxels_;
};

// transport_interval_limit bounds the spectral radius of the transport operator in every
// state (transport_bound.cpp: a majorant of |L|, seams included, and its Collatz-Wielandt
// ratio after a few products) and keeps the step at 0.9 of the limit 2 / rho(L). Checked
// against rho(L) itself, found by power iteration through transport_step: the bound must lie
// above it, each product may only sharpen it, the step must stay within 0.9 of the true
// limit, and a step beyond the limit must amplify the mode found, so that rho is real and
// the check is not vacuous.
TEST(StoneSimulation, TransportIntervalKeepsTheStepWithinItsStabilityLimit)
{
    struct Case {
        const char* name;
        std::unique_ptr<Scene> scene;
        bool ragged;
    };
    std::vector<Case> cases;
    // The benchmark's blob (bench/stone_sim.cpp) at a small resolution: slabs of every shape
    // meet at its seams. All moist, it is the state the bound must cover at its tightest.
    cases.push_back({"sandstone blob, all stone moist",
                     stone_scene(make_uv_sphere(Imath::V3f(0.0f), 0.5f, 7, 8),
                                 StoneKind::sandstone, 8, 8, 0.15, no_erosion()),
                     false});
    cases.push_back({"marble box, ragged moist zone",
                     stone_scene(make_box(Imath::V3f(0.0f), Imath::V3f(0.4f, 0.3f, 0.4f)),
                                 StoneKind::marble, 6, 6, 0.1, no_erosion()),
                     true});
    for (Case& cs : cases) {
        StoneState& st = cs.scene->st;
        // The first bound, 2 alpha D_max phi_max g_max, allowed 2 steps of dt for the default
        // D_i = 0.5, and the largest Gershgorin row 4-5; a whole phase (8 steps) here.
        EXPECT_GE(st.transport_interval, 8) << cs.name;
        const double gershgorin = transport_rate_bound(st, 1);
        const double sharper = transport_rate_bound(st, kTransportBoundProducts);
        EXPECT_LE(sharper, gershgorin) << cs.name;
        Pcg32 rng(5);
        std::vector<char> moist(st.density.size(), 0);
        for (size_t c = 0; c < moist.size(); ++c)
            moist[c] = (st.flags[c] & kStone) && (!cs.ragged || rng.uniform_float() < 0.5f);
        TransportOperator L(st, moist);
        ASSERT_GT(L.size(), 100u);
        std::vector<double> C(L.size());
        for (double& x : C)
            x = rng.uniform_float() - 0.5;
        double rho = 0.0;
        for (int it = 0; it < 150; ++it) {
            const double scale = L.norm(C);
            for (double& x : C)
                x /= scale;
            const std::vector<double> after = L.step(C, 1);
            std::vector<double> LC(C.size());
            for (size_t n = 0; n < C.size(); ++n)
                LC[n] = (C[n] - after[n]) / st.dt;
            rho = L.norm(LC);  // |C| = 1
            C = std::move(LC);
        }
        const double span = st.transport_interval * st.dt;
        std::printf("%s: rho(L) %.4g, bound %.4g (Gershgorin %.4g); transport interval %d, "
                    "span x rho(L) = %.3f (stable below 2; the bound keeps <= 1.8)\n",
                    cs.name, rho, sharper, gershgorin, st.transport_interval, span * rho);
        EXPECT_LE(rho, sharper) << cs.name;
        // And not far above it where everything is moist (1.39 on the blob here; the bound's
        // limit rho(M) is 1.36 times rho at 8^3 and 12^3 per slab: |L| against L, the
        // densities at their worst across seams); the largest Gershgorin row is 1.9 times
        // rho on the paper-size grid.
        if (!cs.ragged) {
            EXPECT_LE(sharper, 1.5 * rho) << cs.name;
        }
        EXPECT_LE(span * rho, 1.8) << cs.name;
        // Beyond the limit: a step of 2.4 / rho takes the mode to -1.4 times itself.
        const int beyond = int(std::ceil(2.4 / (rho * st.dt)));
        const double scale = L.norm(C);
        for (double& x : C)
            x /= scale;
        const double growth = L.norm(L.step(C, beyond));
        std::printf("  a step of %d dt (span x rho = %.2f) scales that mode by %.3f\n", beyond,
                    beyond * st.dt * rho, growth);
        EXPECT_GT(growth, 1.2) << cs.name;
    }
}

TEST(StoneSimulation, ANonFiniteStateIsRefusedWithItsFieldAndVoxel)
{
    auto s = sandstone_box(no_erosion());
    EXPECT_NO_THROW(check_state_finite(s->st));
    const SlabGrid& g = s->st.lattice->grid();
    s->st.dissolved[kSalt][g.index(2, 1, 3, 4)] = std::nanf("");
    const std::string m = patina::test::message_of([&] { check_state_finite(s->st); });
    EXPECT_NE(m.find("dissolved salt"), std::string::npos) << m;
    EXPECT_NE(m.find("slab 2 voxel (1, 3, 4)"), std::string::npos) << m;
}

// Figure 9: sandstone's bedding planes carry more iron (quarry.cpp: 0.01 + 0.05 x plane),
// and the iron channel of the outputs must show them before any weathering.
TEST(StoneVolume, FreshSandstoneShowsItsIronRichBeddingPlanes)
{
    auto s = sandstone_box(no_erosion());
    const StoneState& st = s->st;
    std::vector<float> crust, iron, salt;
    output_fractions(st, crust, iron, salt);
    float lo = 1.0f, hi = 0.0f;
    for (size_t c = 0; c < st.density.size(); ++c) {
        if (!(st.flags[c] & kStone) || st.density[c] < 1.0f)
            continue;
        // No crust yet: the channel is the mineral iron over its scale.
        EXPECT_NEAR(iron[c], std::min(1.0, st.solid[kIron][c] / st.params.mineral_iron_scale),
                    1e-6);
        lo = std::min(lo, iron[c]);
        hi = std::max(hi, iron[c]);
    }
    std::printf("iron channel of fresh sandstone: %.3f (matrix) to %.3f (planes)\n", lo, hi);
    EXPECT_LT(lo, 0.15f); // matrix: 0.01 / 0.1
    EXPECT_GT(hi, 0.45f); // plane centres: 0.06 / 0.1
}

TEST(StoneSimulation, LiveRowsHoldAMoistVoxelOrASurfaceVoxelWhenAsked)
{
    auto sc = sandstone_box(no_erosion());
    StoneState& st = sc->st;
    const SlabGrid& g = st.lattice->grid();
    const int s = 0, last = g.n_d - 1;
    for (int k = -1; k <= g.n_d; ++k)
        for (int j = -1; j <= g.n_t; ++j)
            for (int i = -1; i <= g.n_t; ++i)
                st.moisture[g.index(s, i, j, k)] = 0.0f;
    LiveRows with_surface, moist_only;
    with_surface.scan(st, s, last);
    moist_only.scan(st, s, last, false);
    int surface_rows = 0;
    for (int k = 0; k <= last; ++k)
        for (int j = 0; j < g.n_t; ++j) {
            bool surface = false;
            for (int i = 0; i < g.n_t; ++i)
                surface |= (st.flags[g.index(s, i, j, k)] & kSurface) != 0;
            EXPECT_EQ(surface, with_surface.live(j, k)) << j << ' ' << k;
            EXPECT_FALSE(moist_only.live(j, k)) << j << ' ' << k;
            surface_rows += surface;
        }
    EXPECT_GT(surface_rows, 0);
    // One moist voxel (at the row's last cell, which a vector loop reaches last) makes its
    // row live, and only that row.
    st.moisture[g.index(s, g.n_t - 1, 2, 1)] = 0.5f;
    moist_only.scan(st, s, last, false);
    for (int k = 0; k <= last; ++k)
        for (int j = 0; j < g.n_t; ++j)
            EXPECT_EQ(j == 2 && k == 1, moist_only.live(j, k)) << j << ' ' << k;
}

// The pressure's Dirichlet values (moisture.cpp) are set once per phase and kept while the
// surface stays where it is: after every step, erosion and a deepening moist zone included,
// each air or surface voxel of the active layers holds its phase's value (erosion events
// within a wet phase move the surface under it).
TEST(StoneSimulation, AirAndSurfaceVoxelsHoldTheirPhasesPressureAfterEveryStep)
{
    StoneParameters p;
    p.erosion_events = 0.3;  // the surface moves every cycle
    p.erosion_amount = 0.8;
    auto sc = sandstone_box(p);
    StoneState& st = sc->st;
    const SlabGrid& g = st.lattice->grid();
    for (size_t c = 0; c < st.column_wetness.size(); ++c)
        st.column_wetness[c] = 0.25f + 0.5f * float(c % 3);
    st.pressure_preset_depth.clear();  // the wetness changed (StoneState's contract)
    int checked = 0, eroded = 0;
    for (int cycle = 0; cycle < 6; ++cycle) {
        for (int step = 0; step < 2 * st.params.wet_steps; ++step) {
            const bool wet = step < st.params.wet_steps;
            moisture_step(st, wet);
            for (int s = 0; s < g.slab_count; ++s)
                for (int k = 0; k < st.active_depth[size_t(s)]; ++k)
                    for (int j = 0; j < g.n_t; ++j)
                        for (int i = 0; i < g.n_t; ++i) {
                            const size_t c = g.index(s, i, j, k);
                            if ((st.flags[c] & kStone) && !(st.flags[c] & kSurface))
                                continue;
                            const float expected =
                                wet ? float(st.params.surface_pressure) *
                                          st.column_wetness[column_index(g, s, i, j)]
                                    : 0.0f;
                            ASSERT_EQ(expected, st.pressure[c])
                                << "cycle " << cycle << " step " << step << " slab " << s
                                << " voxel " << i << ' ' << j << ' ' << k;
                            ++checked;
                        }
            transport_step(st, wet, 1);  // the decay index that erosion events follow
            if (step == 3) {  // within a phase, as well as between cycles
                const std::vector<uint8_t> before = st.flags;
                erosion_events(st);
                eroded += st.flags != before;
            }
        }
        erosion_events(st);
    }
    EXPECT_GT(checked, 1000);
    EXPECT_GT(eroded, 0);
}

TEST(StoneSimulation, SameBitsForAnyThreadCount)
{
    std::vector<float> density[2], moisture[2], iron[2];
    for (int run = 0; run < 2; ++run) {
        tbb::global_control threads(tbb::global_control::max_allowed_parallelism, run == 0 ? 1 : 3);
        auto s = sandstone_box(StoneParameters{});
        for (int c = 0; c < 4; ++c)
            run_cycle(s->st);
        density[run] = s->st.density;
        moisture[run] = s->st.moisture;
        iron[run] = s->st.crust[kIron];
    }
    EXPECT_EQ(0, std::memcmp(density[0].data(), density[1].data(), density[0].size() * 4));
    EXPECT_EQ(0, std::memcmp(moisture[0].data(), moisture[1].data(), moisture[0].size() * 4));
    EXPECT_EQ(0, std::memcmp(iron[0].data(), iron[1].data(), iron[0].size() * 4));
}

TEST(StoneVolume, WorldVolumeFileRoundTrips)
{
    auto s = sandstone_box(StoneParameters{});
    for (int c = 0; c < 2; ++c)
        run_cycle(s->st);
    const WorldVolume v = resample_to_world(s->st, s->mesh, 20);
    // The box is inside the grid; the corner voxel is air, the centre fresh stone.
    EXPECT_EQ(v.density[v.index(0, 0, 0)], 0.0f);
    EXPECT_EQ(v.density[v.index(v.nx / 2, v.ny / 2, v.nz / 2)], 1.0f);
    const auto path = std::filesystem::path(PATINA_TEST_BUILD_DIR) / "stone_volume_test.exr";
    write_world_volume(path, v, {{"patina:test", 1}});
    const WorldVolume r = read_world_volume(path);
    ASSERT_EQ(r.nx, v.nx);
    ASSERT_EQ(r.ny, v.ny);
    ASSERT_EQ(r.nz, v.nz);
    for (int a = 0; a < 3; ++a) {
        EXPECT_FLOAT_EQ(float(r.bounds.min[a]), float(v.bounds.min[a]));
        EXPECT_FLOAT_EQ(float(r.bounds.max[a]), float(v.bounds.max[a]));
    }
    EXPECT_EQ(r.density, v.density);
    EXPECT_EQ(r.crust, v.crust);
    EXPECT_EQ(r.iron, v.iron);
    EXPECT_EQ(r.salt, v.salt);
    // Voxel (i, j, k) is pixel (i, k ny + j) of part 0: check one off-diagonal voxel by hand.
    const int i = 3, j = v.ny / 2, k = v.nz / 2 + 1;
    EXPECT_EQ(r.density[r.index(i, j, k)], v.density[size_t(i) + size_t(v.nx) * (size_t(k) * v.ny + j)]);
    EXPECT_THROW(read_world_volume(path.string() + ".missing"), std::runtime_error);
}

TEST(StoneVolume, FreshStoneBelowTheShellCarriesTheQuarrysIron)
{
    auto s = sandstone_box(no_erosion());
    QuarryOptions q;
    q.kind = StoneKind::sandstone;
    q.feature_size = 0.05;
    const Quarry quarry(q);
    const WorldVolume v = resample_to_world(s->st, s->mesh, 40, &quarry);
    const WorldVolume bare = resample_to_world(s->st, s->mesh, 40);
    // Below the shell, the iron of the quarry's bedding planes (0.01 to 0.06 over the scale
    // 0.1); without the quarry, none.
    float lo = 1.0f, hi = 0.0f;
    int interior = 0;
    for (int k = 0; k < v.nz; ++k)
        for (int j = 0; j < v.ny; ++j)
            for (int i = 0; i < v.nx; ++i) {
                const size_t c = v.index(i, j, k);
                if (v.density[c] != 1.0f || bare.iron[c] != 0.0f)
                    continue; // air, or in the shell (the slabs' own values)
                ++interior;
                const float expected =
                    std::min(1.0f, quarry.at(v.centre(i, j, k)).mineral[kIron] / 0.1f);
                EXPECT_NEAR(v.iron[c], expected, 1e-6f);
                lo = std::min(lo, v.iron[c]);
                hi = std::max(hi, v.iron[c]);
            }
    std::printf("%d interior voxels, iron %.3f to %.3f\n", interior, lo, hi);
    ASSERT_GT(interior, 100);
    EXPECT_GT(hi - lo, 0.2f); // bands, not a constant
}

TEST(StoneVolume, ErodedSurfaceEnclosesTheStoneOutwardWound)
{
    auto s = sandstone_box(no_erosion());
    const WorldVolume v = resample_to_world(s->st, s->mesh, 40);
    const TriangleMesh m = extract_eroded_surface(v);
    // Signed volume (divergence theorem): positive for outward winding, close to the box's
    // 0.4 x 0.3 x 0.4 = 0.048 m^3 (surface nets round the edges by up to a voxel).
    double volume = 0.0;
    for (size_t t = 0; t < m.triangle_count(); ++t) {
        const Imath::V3f& a = m.positions[m.indices[3 * t]];
        const Imath::V3f& b = m.positions[m.indices[3 * t + 1]];
        const Imath::V3f& c = m.positions[m.indices[3 * t + 2]];
        volume += double(a.dot(b.cross(c))) / 6.0;
    }
    std::printf("eroded surface of the fresh box: %zu triangles, volume %.5f m^3\n",
                m.triangle_count(), volume);
    EXPECT_NEAR(volume, 0.048, 0.048 * 0.1);
}

} // namespace
} // namespace patina::texgen::stone
