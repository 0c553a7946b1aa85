// The two-lobe Schlick phase function of the slab_volume medium (Dorsey et al. 1999 §5.1):
// normalised, sampled with exactly its own density (chi-square), pdf equal to the value,
// the closed-form cdf against quadrature, and reciprocity.
#include "slab_fixture.h"

#include <patina/testing/chi2.h>

#include <patina/volume/schlick_phase.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace slab_test;
namespace chi2 = patina::test::chi2;
using patina::volume::schlick_cdf;
using patina::volume::schlick_phase;

namespace {

struct Lobes {
    float forward_k, backward_k, forward_weight;
};
const Lobes kLobes[] = {{0.6f, -0.3f, 0.8f}, {0.9f, -0.7f, 0.5f}, {0.0f, 0.0f, 0.3f},
                        {0.3f, -0.95f, 0.0f}};

Medium medium_with(const Lobes& l)
{
    static const fs::path file = write_volume("phase", 2, 2, 2, Vec3(0, 0, 0), Vec3(1, 1, 1),
                                              uniform(Voxel{}));
    return Medium(make("slab_volume", "file = \"phase.exr\"\nforward_k = " +
                                          std::to_string(l.forward_k) + "\nbackward_k = " +
                                          std::to_string(l.backward_k) + "\nforward_weight = " +
                                          std::to_string(l.forward_weight) + "\n"));
}

Vec3 direction(float theta, float phi)
{
    return {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)};
}

} // namespace

TEST(SchlickPhase, EachLobeIsNormalisedAndItsCdfIsExact)
{
    for (double k : {-0.95, -0.5, 0.0, 0.3, 0.9}) {
        // 2π ∫ p_k(c) dc over [−1, c] by Simpson, against the closed form
        for (double c : {-0.5, 0.0, 0.7, 1.0}) {
            const double numeric =
                2.0 * M_PI *
                chi2::adaptive_simpson([&](double x) { return schlick_phase(x, k); }, -1.0, c, 1e-11, 40);
            EXPECT_NEAR(schlick_cdf(c, k), numeric, 1e-7) << "k " << k << " c " << c;
        }
        EXPECT_NEAR(schlick_cdf(1.0, k), 1.0, 1e-12);
        // Its inverse: sample_schlick_cos_theta(k, cdf(c)) == c
        for (double c : {-0.9, -0.2, 0.4, 0.95})
            EXPECT_NEAR(patina::volume::sample_schlick_cos_theta(k, schlick_cdf(c, k)), c, 1e-9);
    }
    // Forward scattering for k > 0: the peak is at wi = −wo (cos θ = −1), of height
    // (1 + k)/(4π (1 − k)) (Blasi et al. 1993)
    EXPECT_NEAR(schlick_phase(-1.0, 0.6), 1.6 / (4.0 * M_PI * 0.4), 1e-12);
}

TEST(SchlickPhase, TwoLobePhaseIntegratesToOneAndIsReciprocal)
{
    for (const Lobes& l : kLobes) {
        const Medium m = medium_with(l);
        const Vec3 wo = direction(0.8f, 0.3f);
        // ∫ p dω over the sphere by the midpoint rule about wo's own axis
        const patina::shading::Frame frame = patina::shading::Frame::from_z(wo);
        const int n = 2000;
        double sum = 0.0;
        for (int i = 0; i < n; ++i) {
            const double theta = (i + 0.5) * M_PI / n;
            const Vec3 wi = frame.from_local(direction(static_cast<float>(theta), 0.7f));
            sum += m.phase(wo, wi) * std::sin(theta) * (M_PI / n) * 2.0 * M_PI;
        }
        EXPECT_NEAR(sum, 1.0, 2e-3) << "k " << l.forward_k << ", " << l.backward_k;
        const Vec3 wi = direction(2.1f, -1.0f);
        EXPECT_FLOAT_EQ(m.phase(wo, wi), m.phase(wi, wo));
    }
}

TEST(SchlickPhase, SamplingPassesChiSquareAndPdfMatchesEval)
{
    const Vec3 wos[] = {direction(0.7f, 1.1f), direction(2.8f, -0.4f)};
    const int tests = static_cast<int>(std::size(kLobes) * std::size(wos));
    for (const Lobes& l : kLobes) {
        const Medium m = medium_with(l);
        for (const Vec3& wo : wos) {
            chi2::Options opt;
            opt.test_count = tests;
            opt.sample_count = 200000;
            uint32_t state = 12345u;
            auto next = [&] {
                state = state * 1664525u + 1013904223u;
                return static_cast<float>(state >> 8) * 0x1p-24f;
            };
            const chi2::Result r = chi2::run(
                opt,
                [&](Vec3* w) {
                    Spectrum p;
                    const float u0 = next();
                    const float pdf = m.phase_sample(wo, Vec2(u0, next()), w, &p);
                    // The returned pdf is the phase function there, and p equals it
                    EXPECT_NEAR(pdf, m.phase(wo, *w), 1e-5f * std::max(1.0f, pdf));
                    EXPECT_EQ(p[0], pdf);
                    return pdf > 0.0f;
                },
                [&](Vec3 w) { return m.phase(wo, w); });
            EXPECT_TRUE(r.passed) << "k " << l.forward_k << ", " << l.backward_k << ": "
                                  << r.message;
            EXPECT_NEAR(r.pdf_integral, 1.0, 1e-3);
            EXPECT_EQ(r.sampled_fraction, 1.0);
        }
    }
}
