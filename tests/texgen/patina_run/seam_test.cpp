// The seam test: a growth pattern on a cube whose uvs are split into six islands is
// continuous across every seam. Patterns grow on the surface lattice (linked across seams,
// surface_lattice.h); texels on both sides of each cube edge are compared with neighbouring
// texels inside the faces, and with a control lattice whose seam links are cut.
#include "texgen/growth/growth_model.h"
#include "texgen/patina/patina_domain.h"

#include "texgen/texgen_meshes.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using namespace patina::texgen;

namespace {

/// 0..5: the face of the unit cube (centred at the origin) a point lies on.
int face_of(const Imath::V3f& p)
{
    int axis = 0;
    for (int a = 1; a < 3; ++a)
        if (std::abs(p[a]) > std::abs(p[axis]))
            axis = a;
    return 2 * axis + (p[axis] > 0 ? 1 : 0);
}

/// Distance from p to the nearest edge of its face (in the face's plane).
float distance_to_edge(const Imath::V3f& p)
{
    const int axis = face_of(p) / 2;
    float d = 1e9f;
    for (int a = 0; a < 3; ++a)
        if (a != axis)
            d = std::min(d, 0.5f - std::abs(p[a]));
    return d;
}

struct Differences {
    double across = 0, inside = 0;
    size_t across_pairs = 0, inside_pairs = 0;
};

/// Mean |difference| over linked pairs on different faces, and over linked pairs inside a
/// face within `band` of an edge (of the full lattice's links, so both measure the same pairs
/// of the surface whatever `grown_on` cut).
Differences differences(const Lattice& lattice, const std::vector<float>& v, float band)
{
    Differences d;
    for (size_t a = 0; a < lattice.size(); ++a) {
        for (int32_t b : lattice.neighbours[a]) {
            if (b <= static_cast<int32_t>(a))
                continue;
            const double diff = std::abs(v[a] - v[b]);
            if (face_of(lattice.position[a]) != face_of(lattice.position[b])) {
                d.across += diff;
                ++d.across_pairs;
            } else if (distance_to_edge(lattice.position[a]) < band) {
                d.inside += diff;
                ++d.inside_pairs;
            }
        }
    }
    d.across /= static_cast<double>(std::max<size_t>(d.across_pairs, 1));
    d.inside /= static_cast<double>(std::max<size_t>(d.inside_pairs, 1));
    return d;
}

Lattice without_seams(Lattice lattice)
{
    for (size_t a = 0; a < lattice.size(); ++a)
        for (int32_t& b : lattice.neighbours[a])
            if (b >= 0 && face_of(lattice.position[a]) != face_of(lattice.position[b]))
                b = -1;
    return lattice;
}

}  // namespace

TEST(SurfaceGrowth, PatternsAreContinuousAcrossEverySeamOfASixIslandCube)
{
    const patina::TriangleMesh cube = patina::test::make_atlas_cube();
    patina::texgen::RasterOptions raster;
    raster.width = raster.height = 256;  // 80 texels along a cube edge
    const PatinaDomain domain = make_mesh_domain(cube, raster);
    const float band = 4.0f / 80.0f;

    struct Case {
        GrowthModelKind model;
        GrowthParameters parameters;
    };
    GrowthParameters dpd;
    dpd.patch_size = 0.08;  // m: 6 or 7 texels, so patches meet the edges many times
    GrowthParameters rdr;
    rdr.relaxation_radius = 0.05;
    const std::vector<std::pair<const char*, Case>> cases = {
        {"DPD", {GrowthModelKind::DirectedPercolationDepinning, dpd}},
        {"RDR", {GrowthModelKind::RandomDepositionRelaxed, rdr}},
        {"turbulence", {GrowthModelKind::Turbulence, GrowthParameters{}}},
    };
    const Lattice cut = without_seams(domain.lattice);
    for (const auto& [name, c] : cases) {
        GrowthSpec spec;
        spec.model = c.model;
        spec.parameters = c.parameters;
        spec.step = 20;
        spec.total = 40;
        const double f = 0.5;
        const std::vector<float> joined = grow(domain.lattice, spec, 7, {&f, 1}).at(0);
        const std::vector<float> control = grow(cut, spec, 7, {&f, 1}).at(0);
        const Differences d = differences(domain.lattice, joined, band);
        const Differences dc = differences(domain.lattice, control, band);
        std::printf("%-10s across seams %.4f, inside faces near edges %.4f; without seam links "
                    "%.4f across\n",
                    name, d.across, d.inside, dc.across);
        ASSERT_GT(d.across_pairs, 12u * 70u) << name;
        // Continuous: a seam is no rougher than the surface next to it.
        EXPECT_LE(d.across, 1.5 * d.inside + 1e-6) << name;
        // The test can fail: grown without the seam links, the seams are cuts, rougher than
        // the joined surface next to them (except for solid noise, which is continuous in
        // space whatever the lattice).
        if (c.model != GrowthModelKind::Turbulence) {
            EXPECT_GT(dc.across, 1.5 * d.inside) << name;
        }
    }
}
