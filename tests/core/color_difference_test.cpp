// CIELAB and CIEDE2000 against published values.
#include "core/color_difference.h"

#include <gtest/gtest.h>

namespace patina {
namespace {

// Sharma, Wu and Dalal 2005, Table 1: pairs of CIELAB colours and their ΔE00, chosen by the
// authors to exercise every branch (hue wrap-around, the mean hue, neutral colours).
struct Pair {
    Lab a, b;
    double de;
};
const Pair kSharma[] = {
    {{50.0000, 2.6772, -79.7751}, {50.0000, 0.0000, -82.7485}, 2.0425},   // pair 1
    {{50.0000, 3.1571, -77.2803}, {50.0000, 0.0000, -82.7485}, 2.8615},   // pair 2
    {{50.0000, 2.8361, -74.0200}, {50.0000, 0.0000, -82.7485}, 3.4412},   // pair 3
    {{50.0000, -1.3802, -84.2814}, {50.0000, 0.0000, -82.7485}, 1.0000},  // pair 4
    {{50.0000, -1.1848, -84.8006}, {50.0000, 0.0000, -82.7485}, 1.0000},  // pair 5
    {{50.0000, -0.9009, -85.5211}, {50.0000, 0.0000, -82.7485}, 1.0000},  // pair 6
    {{50.0000, 0.0000, 0.0000}, {50.0000, -1.0000, 2.0000}, 2.3669},      // pair 7
    {{50.0000, 2.5000, 0.0000}, {73.0000, 25.0000, -18.0000}, 27.1492},   // pair 17
    {{50.0000, 2.5000, 0.0000}, {61.0000, -5.0000, 29.0000}, 22.8977},    // pair 18
    {{50.0000, 2.5000, 0.0000}, {56.0000, -27.0000, -3.0000}, 31.9030},   // pair 19
    {{50.0000, 2.5000, 0.0000}, {58.0000, 24.0000, 15.0000}, 19.4535},    // pair 20
    {{60.2574, -34.0099, 36.2677}, {60.4626, -34.1751, 39.4387}, 1.2644}, // pair 25
};

TEST(ColorDifference, CiedeTwoThousandMatchesSharmaTable1)
{
    for (const Pair& p : kSharma) {
        EXPECT_NEAR(delta_e2000(p.a, p.b), p.de, 5e-5) << p.a.L << " " << p.a.a << " " << p.a.b;
        EXPECT_NEAR(delta_e2000(p.b, p.a), p.de, 5e-5);  // symmetric
    }
    EXPECT_EQ(delta_e2000({40.0, 10.0, -5.0}, {40.0, 10.0, -5.0}), 0.0);
}

TEST(ColorDifference, LabOfTheWhiteAndOfMidGrey)
{
    const Imath::V3d d65(0.95047, 1.0, 1.08883);
    const Lab white = xyz_to_lab(d65, d65);
    EXPECT_NEAR(white.L, 100.0, 1e-12);
    EXPECT_NEAR(white.a, 0.0, 1e-12);
    EXPECT_NEAR(white.b, 0.0, 1e-12);
    // Y = 0.18: L* = 116 · 0.18^(1/3) − 16 = 49.496 (CIE 15:2004 Eq. 8.1).
    EXPECT_NEAR(xyz_to_lab(0.18 * d65, d65).L, 49.4961, 1e-4);
    // Below (6/29)^3 the linear segment: Y = 0.001 gives L* = 903.3 · 0.001 = 0.9033.
    EXPECT_NEAR(xyz_to_lab(0.001 * d65, d65).L, 0.9033, 1e-4);
}

}  // namespace
}  // namespace patina
