// The polynomial cos/sin of patina/shading/fast_trig.h against libm, and the warps on them
// against the libm-based warps of patina/shading/sampling.h.
#include <patina/shading/fast_trig.h>
#include <patina/shading/sampling.h>

#include <gtest/gtest.h>

#include <cmath>

namespace patina::shading {
namespace {

    TEST(FastTrigTest, QuarterMatchesLibm)
    {
        for (int i = 0; i <= 2000; ++i) {
            const float a = kPiOver4 * (static_cast<float>(i) / 1000.0f - 1.0f);
            float c, s;
            sincos_quarter(a, c, s);
            EXPECT_NEAR(c, std::cos(static_cast<double>(a)), 3e-7) << a;
            EXPECT_NEAR(s, std::sin(static_cast<double>(a)), 3e-7) << a;
        }
    }

    TEST(FastTrigTest, TurnMatchesLibmInEveryQuarter)
    {
        for (int i = 0; i < 4096; ++i) {
            const float t = static_cast<float>(i) / 4096.0f + 1.0f / 8192.0f;
            float c, s;
            sincos_turn(t, c, s);
            const double phi = 2.0 * 3.14159265358979323846 * static_cast<double>(t);
            EXPECT_NEAR(c, std::cos(phi), 1e-6) << t;
            EXPECT_NEAR(s, std::sin(phi), 1e-6) << t;
        }
        float c, s;
        sincos_turn(0.0f, c, s);
        EXPECT_EQ(c, 1.0f);
        EXPECT_EQ(s, 0.0f);
        sincos_turn(0x1.fffffep-1f, c, s);
        EXPECT_NEAR(c, 1.0f, 1e-6f);
        EXPECT_NEAR(s, 0.0f, 1e-6f);
    }

    TEST(FastTrigTest, WarpsMatchTheLibmWarps)
    {
        for (int i = 0; i < 64; ++i)
            for (int j = 0; j < 64; ++j) {
                const Vec2 u((static_cast<float>(i) + 0.37f) / 64.0f,
                             (static_cast<float>(j) + 0.61f) / 64.0f);
                const Vec2 a = sample_uniform_disk_concentric(u);
                const Vec2 b = sample_uniform_disk_concentric_poly(u);
                EXPECT_NEAR(a.x, b.x, 5e-7f);
                EXPECT_NEAR(a.y, b.y, 5e-7f);
                const Vec3 h = sample_cosine_hemisphere_poly(u);
                EXPECT_GE(h.z, 0.0f);
                EXPECT_NEAR(h.x * h.x + h.y * h.y + h.z * h.z, 1.0f, 2e-6f);
            }
        EXPECT_EQ(sample_uniform_disk_concentric_poly(Vec2(0.5f, 0.5f)).x, 0.0f);
    }

}  // namespace
}  // namespace patina::shading
