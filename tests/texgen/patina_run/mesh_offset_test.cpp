// `offset` on a mesh: Miller's accessibility (both variants) baked on the base surface fills
// a crease narrower than the ball and leaves open ground bare (D&H 1996 §3.2).
#include "texgen/patina/interpreter.h"
#include "texgen/patina/script_parser.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace fs = std::filesystem;
using namespace patina::texgen;

namespace {

/// A right-angled groove: face 1 is y = 0 (0 <= x <= 1, normal +y), face 2 is x = 0
/// (0 <= y <= 1, normal +x); both |z| <= 0.5. Each face is its own uv island.
patina::TriangleMesh make_right_angle_groove()
{
    patina::TriangleMesh m;
    m.name = "groove";
    m.positions = {{0, 0, -0.5f}, {1, 0, -0.5f}, {1, 0, 0.5f}, {0, 0, 0.5f},
                   {0, 0, -0.5f}, {0, 1, -0.5f}, {0, 1, 0.5f}, {0, 0, 0.5f}};
    m.uvs = {{0.0f, 0.0f},  {0.49f, 0.0f}, {0.49f, 1.0f}, {0.0f, 1.0f},
             {0.51f, 0.0f}, {1.0f, 0.0f},  {1.0f, 1.0f},  {0.51f, 1.0f}};
    // Face 1 wound for +y, face 2 for +x.
    m.indices = {0, 2, 1, 0, 3, 2, 4, 5, 6, 4, 6, 7};
    return m;
}

std::vector<float> offset_fill(const std::string& variant, const PatinaDomain& domain)
{
    patina::ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio" / "config.ocio");
    MaterialLibrary library;
    library.load(fs::path(PATINA_SOURCE_DIR) / "shaders/patina/copper.toml", colors);
    const Script script = parse_script("new copper\noffset dirt 0.1 " + variant + "\n",
                                       "offset.patina", library.names());
    InterpreterOptions options;
    options.times_years = {1.0};
    return run_patina_script(script, library, domain, options).at(0).layers.at(0).thickness_um;
}

}  // namespace

TEST(MeshOffset, FillsOnlyTheCreaseNarrowerThanTheBall)
{
    const patina::TriangleMesh groove = make_right_angle_groove();
    RasterOptions raster;
    raster.width = raster.height = 128;
    const PatinaDomain domain = make_mesh_domain(groove, raster);
    const double r = 0.1;  // m
    for (const std::string variant : {"tangent", "closing"}) {
        const std::vector<float> fill = offset_fill(variant, domain);
        int checked = 0;
        ASSERT_EQ(domain.grids.size(), 1u);
        for (size_t i = 0; i < domain.size(); ++i) {
            const Imath::V3f& p = domain.position[i];
            // Samples on face 1 (y = 0), away from the groove's open ends in z.
            if (p.y > 1e-4f || std::abs(p.z) > 0.3f)
                continue;
            // The bakers average over a texel's samples: its mean distance from the crease.
            const SampleGroups& groups = domain.grids.at(0).groups;
            double d = 0.0;
            for (uint32_t k = groups.offsets[i]; k < groups.offsets[i + 1]; ++k)
                d += groups.samples[k].P.x;
            d /= static_cast<double>(groups.group_size(i));
            // The fillet of a ball of radius r resting in the right-angled crease, which
            // touches face 1 at x = r: r - sqrt(r^2 - (r - d)^2) = r - sqrt(d (2r - d)) thick
            // (closing). The tangent variant's fillet r - sqrt(rho (2r - rho))
            // (heightfield_offset.h) is the same curve: the largest tangent sphere at d has
            // radius rho = d.
            auto fillet_um = [r](double x) {
                x = std::clamp(x, 0.0, r);
                return 1e6 * (r - std::sqrt(x * (2.0 * r - x)));
            };
            if (d > 0.35) {
                if (variant == "tangent")
                    EXPECT_EQ(fill[i], 0.0f) << "open ground at x = " << d;
                else  // the voxel closing leaves float noise far below a voxel
                    EXPECT_LT(fill[i], 1e-3 * r * 1e6) << "open ground at x = " << d;
            } else if (d < 0.08) {
                if (variant == "tangent") {
                    // The tangent radius of the texel is the mean of its samples' (= d).
                    EXPECT_NEAR(fill[i], fillet_um(d), 1e-3 * r * 1e6) << "tangent at x = " << d;
                } else {
                    // The closing is voxelised (1/256 m here): within two voxels of the
                    // curve, horizontally or vertically.
                    const double v = 1.0 / 256.0;
                    EXPECT_GE(fill[i], fillet_um(d + 2 * v) - 1e6 * v) << "closing at x = " << d;
                    EXPECT_LE(fill[i], fillet_um(d - 2 * v) + 1e6 * v) << "closing at x = " << d;
                }
                ++checked;
            }
        }
        EXPECT_GT(checked, 50) << variant;
    }
}
