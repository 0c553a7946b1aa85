#include "texgen/patina/heightfield_offset.h"
#include "texgen/patina/operators.h"

#include "ops_test_util.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace patina::texgen {
namespace {

    using test::message_of;
    using test::random_values;
    using test::same_bits;

    // A strip profile (the same in every row), 1 µm cells, a ball of 8 µm, on ground 50 µm
    // above the base:
    //   a narrow V-groove at x = 40, 3 cells to either side and 3 µm deep (45-degree walls):
    //     the ball rests on its rims and cannot enter;
    //   a wide V-groove at x = 120, 40 cells to either side (a right-angled crease): the
    //     ball slides down its walls until it touches both, at r sin 45 from the axis;
    //   a ridge at x = 215, 20 cells to either side and 20 µm high (convex);
    //   flat ground everywhere else.
    constexpr int kWidth = 260;
    constexpr int kRows = 5;
    constexpr float kCell = 1.0f;
    constexpr float kRadius = 8.0f;
    constexpr float kGround = 50.0f;
    constexpr int kNarrow = 40, kNarrowHalf = 3;
    constexpr int kWide = 120, kWideHalf = 40;
    constexpr int kRidge = 215, kRidgeHalf = 20;

    float profile(int x)
    {
        return kGround - float(std::max(0, kNarrowHalf - std::abs(x - kNarrow))) -
               float(std::max(0, kWideHalf - std::abs(x - kWide))) +
               float(std::max(0, kRidgeHalf - std::abs(x - kRidge)));
    }

    std::vector<float> groove_field()
    {
        std::vector<float> h(size_t(kWidth) * kRows);
        for (int y = 0; y < kRows; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                h[size_t(y) * kWidth + x] = profile(x);
            }
        }
        return h;
    }

    /// Flat ground at least `margin` cells from a groove's rim (a convex edge) and out of
    /// reach of the ridge's feet: each foot is a concave 135-degree crease, which an r-ball
    /// touching both faces meets r tan 22.5 = 3.3 cells from the edge; nearer the foot the
    /// ground is rightly filled.
    bool flat(int x, int margin)
    {
        return std::abs(x - kNarrow) >= kNarrowHalf + margin &&
               std::abs(x - kWide) >= kWideHalf + margin && std::abs(x - kRidge) >= kRidgeHalf + 4;
    }

    /// Middle row of a field.
    float mid(const std::vector<float>& f, int x)
    {
        return f[size_t(kRows / 2) * kWidth + x];
    }

    TEST(ClosingFill, FillsTheNarrowGrooveOnlyAndNotFlatGroundOrWideWalls)
    {
        const std::vector<float> h = groove_field();
        const std::vector<float> fill = closing_fill(h, kWidth, kRows, kCell, kRadius);
        // Rows are identical, so is the fill.
        for (int y = 0; y < kRows; ++y) {
            for (int x = 0; x < kWidth; ++x) {
                ASSERT_EQ(fill[size_t(y) * kWidth + x], mid(fill, x)) << x << "," << y;
            }
        }
        for (int x = 0; x < kWidth; ++x) {
            if (flat(x, 0)) {
                EXPECT_EQ(mid(fill, x), 0.0f) << "flat ground at x = " << x;
            }
        }
        // Narrow groove: the ball rests on the rims (x = 40 +- 3) with its centre
        // sqrt(r^2 - 3^2) above them; the closed surface is its lower side,
        // z = ground + sqrt(r^2 - 9) - sqrt(r^2 - dx^2), and the ball's centre lies over a
        // cell, so the grid closing is exact.
        for (int dx = -kNarrowHalf + 1; dx <= kNarrowHalf - 1; ++dx) {
            const double ball = kGround + std::sqrt(64.0 - 9.0) - std::sqrt(64.0 - dx * dx);
            EXPECT_NEAR(mid(fill, kNarrow + dx), ball - profile(kNarrow + dx), 1e-4)
                << "narrow groove dx = " << dx;
            EXPECT_GT(mid(fill, kNarrow + dx), 0.5f);
        }
        // Wide groove: walls the ball touches (|dx| > r sin 45 = 5.66) get nothing (the ball's
        // centre sits over a cell, which could leave O(cell^2 / r); measured: 0).
        for (int dx = 7; dx < kWideHalf; ++dx) {
            EXPECT_LE(mid(fill, kWide + dx), 1e-4f) << "wide wall dx = " << dx;
            EXPECT_LE(mid(fill, kWide - dx), 1e-4f) << "wide wall dx = " << -dx;
        }
        // ... and its bottom, where the walls meet closer than the ball, is filled: the ball
        // touching both 45-degree walls has its centre r / cos 45 above the crease, so the
        // crease is filled r (sqrt 2 - 1) = 3.314 deep (measured 3.292: the grid ball rests on
        // samples, not on the walls between them).
        EXPECT_NEAR(mid(fill, kWide), kRadius * (std::sqrt(2.0) - 1.0), 0.05);
        for (int dx = -5; dx <= 5; ++dx) {
            EXPECT_GT(mid(fill, kWide + dx), 0.0f) << "wide crease dx = " << dx;
        }
        // Convex ridge: the ball touches it everywhere away from its concave feet.
        for (int dx = -(kRidgeHalf - 8); dx <= kRidgeHalf - 8; ++dx) {
            EXPECT_LE(mid(fill, kRidge + dx), 1e-4f) << "ridge dx = " << dx;
        }
    }

    /// The closing by its definition, in double, cell by cell: the lowest point over p of
    /// every ball resting on the field (continued by its edge values), each ball's centre
    /// as low as the field lets it be over its cell.
    std::vector<double> brute_force_closing(const std::vector<float>& h, int w, int ht, double cell,
                                            double r)
    {
        const int R = int(std::floor(r / cell));
        const auto at = [&](int x, int y) {
            return double(h[size_t(std::clamp(y, 0, ht - 1)) * w + std::clamp(x, 0, w - 1)]);
        };
        const auto cap = [&](int dx, int dy) {
            const double d2 = (dx * dx + dy * dy) * cell * cell;
            return d2 <= r * r ? std::sqrt(r * r - d2) : -1.0;
        };
        std::vector<double> closed(h.size());
        for (int y = 0; y < ht; ++y) {
            for (int x = 0; x < w; ++x) {
                double lowest = 1e300;
                for (int dy = -R; dy <= R; ++dy) {
                    for (int dx = -R; dx <= R; ++dx) {
                        const double c_pq = cap(dx, dy);
                        if (c_pq < 0.0) {
                            continue;
                        }
                        // The centre height of the ball over q = p + (dx, dy).
                        double centre = -1e300;
                        for (int ey = -R; ey <= R; ++ey) {
                            for (int ex = -R; ex <= R; ++ex) {
                                const double c_qs = cap(ex, ey);
                                if (c_qs >= 0.0) {
                                    centre = std::max(centre, at(x + dx + ex, y + dy + ey) + c_qs);
                                }
                            }
                        }
                        lowest = std::min(lowest, centre - c_pq);
                    }
                }
                closed[size_t(y) * w + x] = lowest;
            }
        }
        return closed;
    }

    TEST(ClosingFill, EqualsABruteForceBallClosing)
    {
        const int w = 23, ht = 17;
        const float cell = 1.5f, r = 6.2f;  // 4 cells and a bit
        const std::vector<float> h = random_values(size_t(w) * ht, 0.0f, 12.0f, 21);
        const std::vector<float> fill = closing_fill(h, w, ht, cell, r);
        const std::vector<double> closed = brute_force_closing(h, w, ht, cell, r);
        double largest = 0.0;
        for (size_t i = 0; i < h.size(); ++i) {
            EXPECT_NEAR(fill[i], std::max(0.0, closed[i] - h[i]), 2e-5) << "cell " << i;
            largest = std::max(largest, double(fill[i]));
        }
        EXPECT_GT(largest, 1.0) << "a rough field has crevices the ball cannot enter";
    }

    // A closed surface is closed: closing it again adds nothing (closing is idempotent).
    // Exactly so at the cells 2R or more from the border, whose second closing reads only
    // cells of the first; nearer the border the first closing is continued by its edge
    // values, which is not the closing of the continued field, so it may differ there.
    TEST(ClosingFill, ClosingTheClosedSurfaceAddsNothing)
    {
        const int w = 64, ht = 48, R = 5;
        const std::vector<float> h = random_values(size_t(w) * ht, 0.0f, 6.0f, 22);
        const std::vector<float> fill = closing_fill(h, w, ht, 1.0f, float(R));
        std::vector<float> closed(h.size());
        for (size_t i = 0; i < h.size(); ++i) {
            closed[i] = h[i] + fill[i];
        }
        const std::vector<float> again = closing_fill(closed, w, ht, 1.0f, float(R));
        float largest = 0.0f;
        for (int y = 2 * R; y < ht - 2 * R; ++y) {
            for (int x = 2 * R; x < w - 2 * R; ++x) {
                largest = std::max(largest, again[size_t(y) * w + x]);
            }
        }
        EXPECT_LE(largest, 1e-5f);
        EXPECT_GT(*std::max_element(fill.begin(), fill.end()), 1.0f) << "the first closing fills";
    }

    TEST(TangentSphere, RadiusInARightAngledCreaseIsTheDistanceFromTheEdge)
    {
        const std::vector<float> h = groove_field();
        const std::vector<float> rho = tangent_sphere_radius(h, kWidth, kRows, kCell, 30.0f);
        // The wide groove is a right-angled crease: the circle tangent to one wall at
        // distance s from the edge and touching the other has radius s tan 45 = s, and a
        // wall cell dx from the axis lies s = dx sqrt 2 from the edge. The sampled surface
        // can only let a larger sphere in (its samples lie on the walls).
        for (int dx = 2; dx <= 12; ++dx) {
            const double s = dx * std::sqrt(2.0);
            EXPECT_GE(mid(rho, kWide + dx), s - 1e-4) << "dx = " << dx;
            EXPECT_LE(mid(rho, kWide + dx), s + 1e-3) << "dx = " << dx;
            EXPECT_NEAR(mid(rho, kWide - dx), mid(rho, kWide + dx), 1e-4);
        }
        // The crease itself: the nearest samples (1, 1) above it bound the sphere to one
        // cell, |q - p|^2 / (2 n.(q - p)) = 2 / 2.
        EXPECT_NEAR(mid(rho, kWide), 1.0, 1e-6);
        // Flat ground and the convex ridge top reach the cap.
        EXPECT_EQ(mid(rho, 60), 30.0f);
        EXPECT_EQ(mid(rho, kRidge), 30.0f);
    }

    TEST(TangentSphereFill, FillsTheNarrowGrooveOnlyAndNotFlatGroundOrWideWalls)
    {
        const std::vector<float> h = groove_field();
        const std::vector<float> fill = tangent_sphere_fill(h, kWidth, kRows, kCell, kRadius);
        for (int x = 0; x < kWidth; ++x) {
            if (flat(x, 1)) {
                EXPECT_EQ(mid(fill, x), 0.0f) << "flat ground at x = " << x;
            }
        }
        for (int dx = -kNarrowHalf + 1; dx <= kNarrowHalf - 1; ++dx) {
            EXPECT_GT(mid(fill, kNarrow + dx), 1.0f) << "narrow groove dx = " << dx;
        }
        // Wide walls where the tangent sphere reaches r (dx sqrt 2 >= 8): nothing.
        for (int dx = 6; dx < kWideHalf - 1; ++dx) {
            EXPECT_EQ(mid(fill, kWide + dx), 0.0f) << "wide wall dx = " << dx;
            EXPECT_EQ(mid(fill, kWide - dx), 0.0f) << "wide wall dx = " << -dx;
        }
        // Its crease (rho = 1 cell) is filled: r - sqrt(rho (2 r - rho)) = 8 - sqrt(15).
        EXPECT_NEAR(mid(fill, kWide), 8.0 - std::sqrt(15.0), 1e-5);
        // The convex ridge, away from its obtuse (135-degree) feet, where the tangent
        // sphere at s from the foot along the slope has radius s tan 67.5 >= r for
        // s >= 3.3 (dx <= 17).
        for (int dx = -17; dx <= 17; ++dx) {
            EXPECT_EQ(mid(fill, kRidge + dx), 0.0f) << "ridge dx = " << dx;
        }
    }

    // fill_from_tangent_radius is the fillet an r-ball leaves in a right-angled crease,
    // measured along the wall's normal. Check it against that geometry directly: walls
    // z = |x| (crease at 0), the ball touching both has its centre at (0, r sqrt 2); cast
    // the wall normal (-1, 1)/sqrt 2 from the wall point (x, x) to the ball's lower side.
    TEST(FillFromTangentRadius, IsTheFilletOfARightAngledCrease)
    {
        const double r = 8.0;
        for (double x = 0.0; x <= r / std::sqrt(2.0); x += 0.25) {
            const double px = x, pz = x;
            const double nx = -1.0 / std::sqrt(2.0), nz = 1.0 / std::sqrt(2.0);
            const double cx = 0.0, cz = r * std::sqrt(2.0);
            // |p + t n - c|^2 = r^2: t^2 + 2 t n.(p - c) + |p - c|^2 - r^2 = 0, smaller root.
            const double b = nx * (px - cx) + nz * (pz - cz);
            const double c = (px - cx) * (px - cx) + (pz - cz) * (pz - cz) - r * r;
            const double t = -b - std::sqrt(std::max(0.0, b * b - c));  // grazes at x = 0
            const double rho = x * std::sqrt(2.0);  // tangent radius s tan 45 = s
            EXPECT_NEAR(fill_from_tangent_radius(float(rho), float(r)), t, 1e-5) << "x " << x;
        }
        EXPECT_FLOAT_EQ(fill_from_tangent_radius(0.0f, 8.0f), 8.0f);
        EXPECT_EQ(fill_from_tangent_radius(8.0f, 8.0f), 0.0f);
        EXPECT_EQ(fill_from_tangent_radius(100.0f, 8.0f), 0.0f);
        EXPECT_EQ(fill_from_tangent_radius(0.0f, 0.0f), 0.0f);
        float last = 9.0f;
        for (float rho = 0.0f; rho <= 8.0f; rho += 0.1f) {
            const float f = fill_from_tangent_radius(rho, 8.0f);
            EXPECT_LE(f, last) << "falls as the tangent sphere grows";
            last = f;
        }
    }

    TEST(HeightfieldOffset, OffsetAddsTheClosingAsALayer)
    {
        const std::vector<float> h = groove_field();
        LayerStack s = new_stack(0, h.size());
        coat(s, 1, 1.0f, h);  // the grooved surface as one layer
        const std::vector<float> fill =
            closing_fill(s.total_heights(), kWidth, kRows, kCell, kRadius);
        offset(s, 2, fill);
        EXPECT_EQ(s.exposed_material(size_t(kRows / 2) * kWidth + kNarrow), 2);
        EXPECT_EQ(s.exposed_material(size_t(kRows / 2) * kWidth + 10), 1);
        EXPECT_TRUE(same_bits(s.layers[1].thickness_um, fill));
    }

    TEST(HeightfieldOffset, ZeroRadiusFillsNothingAndBadArgumentsAreRejected)
    {
        const std::vector<float> h = groove_field();
        const std::vector<float> zeros(h.size(), 0.0f);
        EXPECT_TRUE(same_bits(closing_fill(h, kWidth, kRows, kCell, 0.0f), zeros));
        EXPECT_TRUE(same_bits(tangent_sphere_fill(h, kWidth, kRows, kCell, 0.0f), zeros));
        // A ball smaller than a cell fits between any two samples.
        EXPECT_TRUE(same_bits(closing_fill(h, kWidth, kRows, kCell, 0.9f), zeros));
        const auto msg = [](auto f) { return message_of<std::invalid_argument>(f); };
        EXPECT_NE(msg([&] {
                      closing_fill(h, kWidth, kRows, kCell, -1.0f);
                  }).find("offset: radius -1 um is negative"),
                  std::string::npos);
        EXPECT_NE(msg([&] {
                      tangent_sphere_fill(h, kWidth, kRows, kCell, -1.0f);
                  }).find("offset: radius -1 um is negative"),
                  std::string::npos);
        EXPECT_NE(
            msg([&] { closing_fill(h, kWidth, kRows, 0.0f, 1.0f); }).find("offset: cell size 0"),
            std::string::npos);
        EXPECT_NE(msg([&] {
                      closing_fill(h, kWidth + 1, kRows, kCell, 1.0f);
                  }).find("offset: the height field has"),
                  std::string::npos);
        EXPECT_NE(msg([&] { closing_fill(h, kWidth, kRows, kCell, 500.0f); }).find("at most 128"),
                  std::string::npos);
        EXPECT_NE(msg([] { fill_from_tangent_radius(1.0f, -2.0f); }).find("offset: radius -2"),
                  std::string::npos);
    }

    TEST(HeightfieldOffset, SameBitsForAnyThreadCount)
    {
        const int w = 200, ht = 150;
        const std::vector<float> h = random_values(size_t(w) * ht, 0.0f, 5.0f, 23);
        const auto run = [&] {
            std::vector<float> a = closing_fill(h, w, ht, 1.0f, 6.0f);
            const std::vector<float> b = tangent_sphere_fill(h, w, ht, 1.0f, 6.0f);
            a.insert(a.end(), b.begin(), b.end());
            return a;
        };
        EXPECT_TRUE(same_bits(test::with_threads(1, run), test::with_threads(2, run)));
    }

}  // namespace
}  // namespace patina::texgen
