// Slabs (Dorsey et al. 1999 §4.1): the shell of a closed mesh, its world <-> slab mapping and
// the connections between slabs.
#include "stone_test_util.h"

#include "core/sampling.h"
#include "texgen/slabs/slab_mapping.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstring>

namespace patina::texgen::stone {
namespace {

using Imath::V3d;

double slab_size(const SlabCorners& c)
{
    double s = 0.0;
    for (int i = 0; i < 8; ++i)
        for (int j = i + 1; j < 8; ++j)
            s = std::max(s, (c[i] - c[j]).length());
    return s;
}

TEST(SlabShell, BoxMakesThreeSlabsPerTriangleAllConnected)
{
    const TriangleMesh box = make_box(Imath::V3f(0.0f), Imath::V3f(1.0f, 0.6f, 0.8f));
    ShellOptions o;
    o.depth = 0.1;
    const SlabShell shell = build_slab_shell(box, o);
    EXPECT_EQ(shell.slabs.size(), 3 * box.triangle_count());
    // A closed mesh: every slab has a neighbour across each of its four sides (the box's
    // duplicated face vertices are welded).
    for (const auto& n : shell.neighbours)
        for (int side = 0; side < 4; ++side)
            EXPECT_GE(n[side], 0);
    // The inner face lies `depth` below the flat faces' centres.
    for (size_t s = 0; s < shell.slabs.size(); ++s) {
        const V3d outer = slab_to_world(shell.slabs[s], V3d(0.5, 0.5, 0.0));
        const V3d inner = slab_to_world(shell.slabs[s], V3d(0.5, 0.5, 1.0));
        EXPECT_LE((outer - inner).length(), 0.1 + 1e-9);
        EXPECT_GT((outer - inner).length(), 0.02);
    }
}

TEST(SlabMapping, WorldToSlabRoundTripsWithinATenMillionthOfTheSlab)
{
    const TriangleMesh blob = test::concave_blob(0.5f, 0.08f, 16, 32);
    ShellOptions o;
    o.depth = 0.12;
    o.outer_margin = 0.01;
    const SlabShell shell = build_slab_shell(blob, o);
    const SlabLocator locator(shell.slabs);
    Pcg32 rng(7);
    double worst = 0.0;
    int found_other = 0;
    for (size_t s = 0; s < shell.slabs.size(); s += 3)
        for (int n = 0; n < 8; ++n) {
            const V3d uvw(rng.uniform_double(), rng.uniform_double(), rng.uniform_double());
            const V3d p = slab_to_world(shell.slabs[s], uvw);
            const auto at = locator.locate(p);
            ASSERT_TRUE(at.has_value()) << "slab " << s;
            if (at->slab != int(s))
                ++found_other; // on a shared face within the tolerance
            const V3d back = slab_to_world(shell.slabs[size_t(at->slab)], at->uvw);
            worst = std::max(worst, (back - p).length() / slab_size(shell.slabs[s]));
            if (at->slab == int(s)) {
                EXPECT_LT((at->uvw - uvw).length(), 1e-6);
            }
        }
    // Task: world -> slab -> world within 1e-5 of the slab size.
    EXPECT_LT(worst, 1e-5);
    EXPECT_LE(found_other, 2);
    std::printf("round trip: worst error %.3g of the slab size\n", worst);
}

TEST(SlabShell, ConcaveMeshShellNeitherFoldsNorOverlaps)
{
    // A torus: concave inside its ring, tube radius 0.2 m; a shell asked 0.18 m deep must be
    // limited (by the opposite wall and the tube's curvature) not to overlap.
    const TriangleMesh blob = test::torus();
    ShellOptions o;
    o.depth = 0.18;
    o.outer_margin = 0.02;
    const SlabShell shell = build_slab_shell(blob, o);
    // No fold: the Jacobian keeps its (negative) sign on a 5^3 grid of every slab.
    for (size_t s = 0; s < shell.slabs.size(); ++s)
        for (int i = 0; i < 125; ++i) {
            const V3d uvw(0.25 * (i % 5), 0.25 * ((i / 5) % 5), 0.25 * (i / 25));
            ASSERT_LT(slab_jacobian_determinant(shell.slabs[s], uvw), 0.0) << "slab " << s;
        }
    // No overlap: a point inside one slab lies in no other one.
    const SlabLocator locator(shell.slabs);
    Pcg32 rng(11);
    int overlaps = 0, points = 0;
    for (size_t s = 0; s < shell.slabs.size(); ++s)
        for (int n = 0; n < 6; ++n) {
            const V3d uvw(0.02 + 0.96 * rng.uniform_double(), 0.02 + 0.96 * rng.uniform_double(),
                          0.02 + 0.96 * rng.uniform_double());
            const auto all = locator.locate_all(slab_to_world(shell.slabs[s], uvw), 0.0);
            ++points;
            if (all.size() != 1)
                ++overlaps;
        }
    EXPECT_EQ(overlaps, 0) << "of " << points << " points";
    // The limits did act: some point is shallower than asked.
    EXPECT_LT(*std::min_element(shell.depths.begin(), shell.depths.end()), 0.18);
}

TEST(SlabLattice, GhostsConnectSlabsSoALinearFieldCrossesSeamsExactly)
{
    const TriangleMesh box = make_box(Imath::V3f(0.0f), Imath::V3f(1.0f));
    const auto t = test::make_lattice(box, 6, 4, 0.2);
    const SlabLattice& lat = *t.lattice;
    const SlabGrid& g = lat.grid();
    // A linear function of position in the voxels; the ghosts interpolate it.
    std::vector<float> f(g.cell_count(), 0.0f);
    auto fn = [](const Imath::V3f& p) { return 1.0f + 2.0f * p.x - p.y + 0.5f * p.z; };
    for (int s = 0; s < g.slab_count; ++s)
        for (int k = 0; k < g.n_d; ++k)
            for (int j = 0; j < g.n_t; ++j)
                for (int i = 0; i < g.n_t; ++i)
                    f[g.index(s, i, j, k)] = fn(lat.position()[g.index(s, i, j, k)]);
    lat.fill_halo(f.data());
    // Side ghosts of flat faces away from the box's edges lie in a coplanar neighbour whose
    // lattice is the same: the ghost equals the function there.
    int checked = 0;
    for (int s = 0; s < g.slab_count; ++s)
        for (int k = 0; k < g.n_d; ++k)
            for (int j = 0; j < g.n_t; ++j) {
                const V3d p = slab_to_world(lat.slabs()[size_t(s)], g.uvw(-1, j, k));
                const auto at = lat.locator().locate(p, 1e-6);
                if (!at)
                    continue;
                const Imath::V3f pf(float(p.x), float(p.y), float(p.z));
                EXPECT_NEAR(f[g.index(s, -1, j, k)], fn(pf), 0.2f);
                ++checked;
            }
    EXPECT_GT(checked, g.slab_count * g.n_d);
    EXPECT_LT(lat.unconnected_ghosts(), size_t(g.slab_count) * 4 * g.n_t * g.n_d / 2);
}


TEST(SlabLattice, HaloFillThatSkipsUnchangedGhostsMatchesAFullFill)
{
    const TriangleMesh box = make_box(Imath::V3f(0.0f), Imath::V3f(1.0f));
    const auto t = test::make_lattice(box, 6, 5, 0.2);
    const SlabLattice& lat = *t.lattice;
    const SlabGrid& g = lat.grid();
    Pcg32 rng(11);
    std::vector<float> f(g.cell_count(), 0.0f);
    auto randomise = [&](int s, int j, int k, HaloChanges* changes) {
        for (int i = 0; i < g.n_t; ++i)
            f[g.index(s, i, j, k)] = rng.uniform_float();
        // Both ways of marking a row (a cell of it, or the row itself) are exercised.
        if (changes && (j + k) % 2)
            changes->mark(g.index(s, 0, j, k), g);
        else if (changes)
            changes->mark_row(s, j, k, g);
    };
    for (int s = 0; s < g.slab_count; ++s)
        for (int k = 0; k < g.n_d; ++k)
            for (int j = 0; j < g.n_t; ++j)
                randomise(s, j, k, nullptr);
    // Active depths that grow between fills: ghosts in layers the last fill did not cover
    // must be filled even though their sources are unmarked.
    std::vector<int> active(size_t(g.slab_count), 1);
    HaloChanges changes;
    std::vector<float> tracked = f;
    for (int round = 0; round < 6; ++round) {
        for (int e = 0; e < 12; ++e)
            randomise(int(rng.uniform_float() * float(g.slab_count)) % g.slab_count,
                      int(rng.uniform_float() * float(g.n_t)) % g.n_t,
                      int(rng.uniform_float() * float(g.n_d)) % g.n_d, &changes);
        for (int s = 0; s < g.slab_count; ++s)
            active[size_t(s)] = std::min(g.n_d - 1, round / 2 + s % 2);
        // The interior of `tracked` follows f; its halo only through the skipping fills.
        for (int s = 0; s < g.slab_count; ++s)
            for (int k = 0; k < g.n_d; ++k)
                for (int j = 0; j < g.n_t; ++j)
                    for (int i = 0; i < g.n_t; ++i)
                        tracked[g.index(s, i, j, k)] = f[g.index(s, i, j, k)];
        lat.fill_halo(tracked.data(), &active, &changes);
        std::vector<float> full = f;
        lat.fill_halo(full.data(), &active);
        // Every ghost of the layers a step reads (k <= active) and the whole halo above the
        // shell (k = -1, a copy of the first layer made only when it changed) are the full
        // fill's, bit for bit.
        int compared = 0;
        for (int s = 0; s < g.slab_count; ++s)
            for (int k = -1; k <= active[size_t(s)]; ++k)
                for (int j = -1; j <= g.n_t; ++j)
                    for (int i = -1; i <= g.n_t; ++i) {
                        if (k >= 0 && i >= 0 && j >= 0 && i < g.n_t && j < g.n_t)
                            continue;
                        const size_t c = g.index(s, i, j, k);
                        ASSERT_EQ(0, std::memcmp(&tracked[c], &full[c], sizeof(float)))
                            << "round " << round << " slab " << s << " ghost " << i << ' ' << j
                            << ' ' << k;
                        ++compared;
                    }
        EXPECT_GT(compared, g.slab_count * 4 * g.n_t);
    }
}


TEST(SlabLattice, GhostSourcesAreTheVoxelsThatFeedTheGhost)
{
    // ghost_sources(cell) finds a ghost's block from its cell (the seam pass of transport.cpp
    // goes from the ghosts that received back to their sources): each source of nonzero
    // weight of a connected ghost must list that ghost among its feeds, with the same weight
    // (and no source of weight 0 may), and the weights of a ghost sum to 1 (trilinear).
    const TriangleMesh box = make_box(Imath::V3f(0.0f), Imath::V3f(1.0f));
    const auto t = test::make_lattice(box, 5, 3, 0.2);
    const SlabLattice& lat = *t.lattice;
    const SlabGrid& g = lat.grid();
    const auto& begin = lat.feed_begin();
    const auto& feeds = lat.feeds();
    int checked = 0;
    for (int s = 0; s < g.slab_count; ++s)
        for (int k = 0; k < g.n_d; ++k)
            for (int j = -1; j <= g.n_t; ++j)
                for (int i = -1; i <= g.n_t; ++i) {
                    if (i >= 0 && j >= 0 && i < g.n_t && j < g.n_t)
                        continue;
                    const size_t ghost = g.index(s, i, j, k);
                    if (!lat.flux_partner(ghost))
                        continue;
                    float sum = 0.0f;
                    for (const GhostSource& source : lat.ghost_sources(ghost)) {
                        sum += source.weight;
                        bool listed = false;
                        for (uint32_t e = begin[source.cell]; e < begin[source.cell + 1]; ++e)
                            listed |= feeds[e].ghost == ghost && feeds[e].weight == source.weight;
                        ASSERT_EQ(listed, source.weight != 0.0f)
                            << "slab " << s << " ghost " << i << ' ' << j << ' ' << k
                            << ": source " << source.cell << " of weight " << source.weight;
                    }
                    EXPECT_NEAR(sum, 1.0f, 1e-5f);
                    ++checked;
                }
    EXPECT_GT(checked, g.slab_count * 4 * g.n_t * g.n_d / 2);
}

TEST(SlabLattice, MarkingARowMarksWhatMarkingAnyOfItsCellsMarks)
{
    const SlabGrid g(5, 4, 3);
    HaloChanges by_cell, by_row;
    const size_t rows = g.cell_count() / size_t(g.sx);
    for (HaloChanges* h : {&by_cell, &by_row}) {
        h->row_changed.assign(rows, 0);
        h->layer_changed.assign(rows / size_t(g.sy), 0);
    }
    for (int s = 0; s < g.slab_count; ++s)
        for (int k = 0; k < g.n_d; ++k)
            for (int j = 0; j < g.n_t; ++j) {
                if ((s + 2 * j + 3 * k) % 4)  // leave some rows unmarked
                    continue;
                by_row.mark_row(s, j, k, g);
                by_cell.mark(g.index(s, (j + k) % g.n_t, j, k), g);
            }
    EXPECT_EQ(by_cell.row_changed, by_row.row_changed);
    EXPECT_EQ(by_cell.layer_changed, by_row.layer_changed);
    EXPECT_GT(std::count(by_row.row_changed.begin(), by_row.row_changed.end(), 1), 10);
}

} // namespace
} // namespace patina::texgen::stone
