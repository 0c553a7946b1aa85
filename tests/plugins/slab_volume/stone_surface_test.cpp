// stone_surface: reflects F_r^k of the light (Dorsey et al. 1999 §5.1) and refracts the rest;
// index-matched at eta = 1; total internal reflection stays total; reciprocal.
#include "slab_fixture.h"

#include <patina/shading/fresnel.h>
#include <patina/testing/bsdf_checks.h>

#include <gtest/gtest.h>

#include <cmath>

using namespace slab_test;
using patina::shading::fresnel_dielectric;

namespace {

class Surface {
public:
    Surface(float eta, float k, const char* transmission = "refract")
        : instance_(make("stone_surface", "eta = " + std::to_string(eta) +
                                              "\nroughness_exponent = " + std::to_string(k) +
                                              "\ntransmission = \"" + transmission + "\"\n")),
          wl_(wavelengths())
    {
        ctx_.N = {0, 0, 1};
        ctx_.Ng = {0, 0, 1};
        ctx_.mode = PATINA_TRANSPORT_RADIANCE;
    }
    bool sample(Vec3 wo, float u_lobe, PatinaBsdfSample* s, Vec2 u = Vec2(0.3f, 0.6f)) const
    {
        *s = PatinaBsdfSample{};
        return instance_->bsdf()->sample(instance_->get(), &ctx_, wo, u_lobe, u, &wl_, s) != 0;
    }
    float pdf(Vec3 wo, Vec3 wi) const
    {
        return instance_->bsdf()->pdf(instance_->get(), &ctx_, wo, wi, &wl_);
    }
    /// Fraction of u_lobe values that reflect: the reflected fraction R.
    double reflected_fraction(Vec3 wo) const
    {
        const int n = 100000;
        int reflected = 0;
        for (int i = 0; i < n; ++i) {
            PatinaBsdfSample s;
            if (sample(wo, (i + 0.5f) / n, &s) && (s.lobe & PATINA_LOBE_REFLECTION))
                ++reflected;
        }
        return static_cast<double>(reflected) / n;
    }
    /// The instance as patina/testing/bsdf_checks.h calls it.
    patina::test::BsdfCalls calls() const
    {
        patina::test::BsdfCalls c(instance_->bsdf(), instance_->get(), wl_);
        c.ctx = ctx_;
        return c;
    }
    /// Path weight f |cos θi| / pdf of a sample.
    static float weight(const PatinaBsdfSample& s) { return s.f[0] * std::abs(s.wi.z) / s.pdf; }
    void set_mode(PatinaTransportMode m) { ctx_.mode = m; }
    float eval0(Vec3 wo, Vec3 wi) const
    {
        Spectrum f{};
        instance_->bsdf()->eval(instance_->get(), &ctx_, wo, wi, &wl_, f.data());
        return f[0];
    }

private:
    std::shared_ptr<patina::ShaderInstance> instance_;
    PatinaWavelengths wl_;
    PatinaShadingContext ctx_{};
};

Vec3 at_cos(float c)
{
    return {std::sqrt(1.0f - c * c), 0.0f, c};
}

} // namespace

TEST(StoneSurface, ReflectsFresnelToThePowerK)
{
    // R = F_r(θ)^k: §5.1. F_r at normal incidence for η = 1.5 is 0.04 (Born & Wolf §1.5.2)
    for (float k : {1.0f, 2.0f, 5.0f}) {
        const Surface s(1.5f, k);
        for (float c : {1.0f, 0.5f, 0.1f}) {
            const double expected = std::pow(fresnel_dielectric(c, 1.5f), k);
            EXPECT_NEAR(s.reflected_fraction(at_cos(c)), expected, 2e-5) << "k " << k << " cos " << c;
        }
    }
    EXPECT_NEAR(std::pow(fresnel_dielectric(1.0f, 1.5f), 2.0f), 0.0016, 1e-6);
    // A rougher surface (larger k) reflects less and lets more into the stone, most near
    // the normal
    const Surface smooth(1.5f, 1.0f), rough(1.5f, 4.0f);
    EXPECT_LT(rough.reflected_fraction(at_cos(0.9f)), 0.01 * smooth.reflected_fraction(at_cos(0.9f)));
    EXPECT_GT(rough.reflected_fraction(at_cos(0.05f)), 0.3 * smooth.reflected_fraction(at_cos(0.05f)));
}

TEST(StoneSurface, SampledDirectionsAndWeights)
{
    Surface s(1.5f, 3.0f);
    const Vec3 wo = at_cos(0.6f);
    PatinaBsdfSample r, t;
    ASSERT_TRUE(s.sample(wo, 0.0f, &r));
    ASSERT_TRUE(s.sample(wo, 0.999f, &t));
    // Reflection: the mirror direction, weight 1 (R / R)
    EXPECT_TRUE(r.lobe & PATINA_LOBE_SPECULAR);
    EXPECT_NEAR(r.wi.x, -wo.x, 1e-6f);
    EXPECT_NEAR(r.wi.z, wo.z, 1e-6f);
    EXPECT_NEAR(Surface::weight(r), 1.0f, 1e-5f);
    // Transmission: Snell (sin θt = sin θi / 1.5), weight 1 in both transport modes (the
    // η'² radiance factors of a closed stone cancel in pairs and are left out)
    EXPECT_TRUE(t.lobe & PATINA_LOBE_TRANSMISSION);
    EXPECT_LT(t.wi.z, 0.0f);
    EXPECT_NEAR(t.wi.x, -0.8f / 1.5f, 1e-5f);
    EXPECT_FLOAT_EQ(t.eta, 1.5f);
    EXPECT_NEAR(Surface::weight(t), 1.0f, 1e-5f);
    s.set_mode(PATINA_TRANSPORT_IMPORTANCE);
    ASSERT_TRUE(s.sample(wo, 0.999f, &t));
    EXPECT_NEAR(Surface::weight(t), 1.0f, 1e-5f);
    // Delta lobes only: eval is 0 everywhere
    EXPECT_EQ(s.eval0(wo, at_cos(0.3f)), 0.0f);
}

TEST(StoneSurface, IndexMatchedBoundaryPassesLightStraightThrough)
{
    const Surface s(1.0f, 4.0f);
    for (float c : {1.0f, 0.4f, -0.7f}) {
        const Vec3 wo = at_cos(c);
        EXPECT_EQ(s.reflected_fraction(wo), 0.0);
        PatinaBsdfSample t;
        ASSERT_TRUE(s.sample(wo, 0.0f, &t));
        EXPECT_NEAR(t.wi.x, -wo.x, 1e-6f);
        EXPECT_NEAR(t.wi.z, -wo.z, 1e-6f);
        EXPECT_NEAR(Surface::weight(t), 1.0f, 1e-6f);
    }
}

TEST(StoneSurface, InsideTheStoneTotalReflectionAndReciprocity)
{
    const Surface s(1.5f, 3.0f);
    // Beyond the critical angle (sin θ > 1/1.5) every k reflects everything
    EXPECT_EQ(s.reflected_fraction(at_cos(-0.5f)), 1.0);
    // A refracted pair of directions reflects the same fraction from either side:
    // outside at cos 0.6, inside at cos θt with sin θt = 0.8/1.5
    const float sin_t = 0.8f / 1.5f;
    const float cos_t = std::sqrt(1.0f - sin_t * sin_t);
    EXPECT_NEAR(s.reflected_fraction(at_cos(0.6f)), s.reflected_fraction(at_cos(-cos_t)), 2e-5);
}

TEST(StoneSurface, DiffuseTransmissionIsConsistentAndConservesEnergy)
{
    const Surface s(1.5f, 2.0f, "diffuse");
    for (float c : {0.8f, 0.3f, -0.9f, -0.2f}) {
        const Vec3 wo = at_cos(c);
        const double R = std::pow(fresnel_dielectric(c, 1.5f), 2.0f);
        // Reflection stays the delta lobe F_r^k
        EXPECT_NEAR(s.reflected_fraction(wo), R >= 1.0 ? 1.0 : R, 2e-5) << "cos " << c;
        // ∫ f |cos θi| dωi over the other side = 1 − R (midpoint rule in cos θ)
        const int n = 4000;
        double integral = 0.0;
        for (int i = 0; i < n; ++i) {
            const float ci = (i + 0.5f) / n;
            const Vec3 wi = at_cos(c > 0.0f ? -ci : ci);
            integral += s.eval0(wo, wi) * ci * (1.0 / n) * 2.0 * M_PI;
        }
        EXPECT_NEAR(R + integral, 1.0, 1e-4) << "cos " << c;
        // Same-side directions get nothing from eval
        EXPECT_EQ(s.eval0(wo, at_cos(c > 0.0f ? 0.5f : -0.5f)), 0.0f);
        // Sampled transmissions: pdf() and eval() at the sampled direction match the sample
        for (int i = 0; i < 64; ++i) {
            PatinaBsdfSample t;
            if (!s.sample(wo, 0.9999f, &t, Vec2((i + 0.5f) / 64.0f, 0.37f)))
                continue;
            if (R >= 1.0) {
                // Total internal reflection: nothing crosses
                EXPECT_TRUE(t.lobe & PATINA_LOBE_REFLECTION);
                continue;
            }
            ASSERT_TRUE(t.lobe & PATINA_LOBE_TRANSMISSION);
            EXPECT_LT(t.wi.z * wo.z, 0.0f);
            EXPECT_NEAR(t.pdf, s.pdf(wo, t.wi), 1e-6f * std::max(1.0f, t.pdf));
            EXPECT_NEAR(t.f[0], s.eval0(wo, t.wi), 1e-6f);
            EXPECT_NEAR(Surface::weight(t), 1.0f, 1e-4f);
        }
    }
}

TEST(StoneSurface, WhiteFurnace)
{
    // A lossless boundary: what is not reflected (F_r^k, §5.1) crosses, so the directional
    // albedo by its own importance samples is 1 from either side, for both transmissions.
    for (const char* transmission : {"refract", "diffuse"}) {
        const Surface s(1.5f, 2.0f, transmission);
        for (float c : {0.9f, 0.4f, -0.3f, -0.8f}) {
            const auto albedo = patina::test::albedo_by_sampling(s.calls(), at_cos(c), 64);
            EXPECT_NEAR(albedo[0], 1.0, 1e-4) << transmission << " cos " << c;
        }
    }
}
