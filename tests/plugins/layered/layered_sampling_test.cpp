// Sampling of the layered shader: chi-square test of `sample` against `pdf`
// (patina/testing/chi2.h, as every BSDF's), and sample returning exactly what eval and pdf
// say.
#include "layered_fixture.h"

#include <patina/testing/chi2.h>

namespace patina::test {
namespace {

    using namespace patina::shading;

    const TestMaterial kCopper{"copper", true, 0, -1, 0, 0.9f, 0.15f, 0.27f, 3.4f};
    const TestMaterial kGreen{"green", false, 0.6f, 0.1f, 0.35f, 0.04f, 0.5f};
    const TestMaterial kBrown{"brown", false, 1.5f, 0.8f, 1.2f, 0.08f, 0.25f};
    const TestMaterial kDirt{"dirt", false, 0.4f, -1, 0.35f, 0.05f, 0.8f};

    /// A small deterministic generator (SplitMix64).
    struct Rng {
        uint64_t s;
        float next()
        {
            uint64_t z = (s += 0x9e3779b97f4a7c15ULL);
            z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
            z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
            return static_cast<float>((z ^ (z >> 31)) >> 40) * 0x1p-24f;
        }
    };

    struct Case {
        std::string name;
        TestStack stack;
        float theta;
    };

    std::vector<Case> cases()
    {
        const std::vector<TestMaterial> m = {kCopper, kGreen, kBrown, kDirt};
        return {
            {"bare_copper", {"copper", {}, m}, 40.0f},
            {"thin_brown", {"copper", {{"brown", 0.3f}}, m}, 20.0f},
            {"three_layers", {"copper", {{"brown", 0.4f}, {"green", 1.0f}, {"dirt", 0.3f}}, m}, 60.0f},
            {"dielectric_base", {"dirt", {{"green", 0.8f}}, m}, 75.0f},
        };
    }

}  // namespace

TEST(LayeredSampling, ChiSquareSampleMatchesPdf)
{
    const std::vector<Case> all = cases();
    for (const Case& c : all) {
        const Layered l(write_stack("chi2_" + c.name, c.stack));
        ASSERT_TRUE(l) << l.errors();
        const Vec3 wo = direction_deg(c.theta, 30.0f);
        chi2::Options opt;
        opt.sample_count = 200000;
        opt.test_count = static_cast<int>(all.size());
        Rng rng{7};
        const chi2::Result r = chi2::run(
            opt,
            [&](Vec3* w) {
                PatinaBsdfSample s;
                const float u_lobe = rng.next();
                const Vec2 u(rng.next(), rng.next());
                if (!l.sample(wo, u_lobe, u, &s))
                    return false;
                *w = s.wi;
                return true;
            },
            [&](Vec3 w) { return l.pdf(wo, w); });
        EXPECT_TRUE(r.passed) << c.name << ": " << r.message << " p = " << r.p_value;
    }
}

TEST(LayeredSampling, SampleReturnsEvalAndPdfExactly)
{
    for (const Case& c : cases()) {
        const Layered l(write_stack("agree_" + c.name, c.stack));
        Rng rng{11};
        for (int k = 0; k < 500; ++k) {
            const Vec3 wo = direction_deg(89.0f * rng.next(), 360.0f * rng.next());
            PatinaBsdfSample s;
            if (!l.sample(wo, rng.next(), Vec2(rng.next(), rng.next()), &s))
                continue;
            EXPECT_GT(s.wi.z, 0.0f);
            EXPECT_EQ(s.pdf, l.pdf(wo, s.wi)) << c.name;
            const Spectrum f = l.f(wo, s.wi);
            for (int i = 0; i < 8; ++i) {
                EXPECT_EQ(s.f[i], f[i]) << c.name;
                EXPECT_TRUE(std::isfinite(s.f[i]) && s.f[i] >= 0.0f);
            }
        }
    }
}

TEST(LayeredSampling, NoNanAtGrazingAndBelow)
{
    const Layered l(write_stack("grazing", cases()[2].stack));
    for (const Vec3 wo : {Vec3(1, 0, 0), Vec3(0.99999f, 0, 0.0044f), Vec3(0, 0, 1), Vec3(0, 0, -1)})
        for (const Vec3 wi : {Vec3(-1, 0, 0), Vec3(0, 0.9999f, 0.014f), Vec3(0, 0, 1),
                              Vec3(0, 0, -1), Vec3(-0.6f, 0, -0.8f)}) {
            const Spectrum f = l.f(wo, wi);
            for (float v : f)
                EXPECT_TRUE(std::isfinite(v) && v >= 0.0f);
            EXPECT_TRUE(std::isfinite(l.pdf(wo, wi)));
        }
    // Different sides: nothing is transmitted.
    EXPECT_EQ(l.f(Vec3(0, 0, 1), Vec3(0, 0, -1))[0], 0.0f);
    // Both below: the stack reflects alike on both sides.
    const Vec3 a = direction_deg(30, 0), b = direction_deg(50, 120);
    EXPECT_EQ(l.f(a, b)[2], l.f(Vec3(a.x, a.y, -a.z), Vec3(b.x, b.y, -b.z))[2]);
}

}  // namespace patina::test
