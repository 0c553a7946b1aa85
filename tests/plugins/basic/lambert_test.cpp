// lambert: closed form f = R/π, white furnace, reciprocity, both sides, bad values.
#include "basic_plugin.h"

namespace patina::test {
namespace {

    using shading::kInvPi;

    TEST(Lambert, EvalIsReflectanceOverPi)
    {
        ParamSet params(shader("lambert"));
        params.set_color("reflectance", 0.8f, 0.4f, 0.2f);
        const PatinaRgbSpectrum r = params.data()[0].color;
        const Bsdf bsdf("lambert", params);
        ASSERT_TRUE(bsdf);
        const Vec3 wo = direction(0.4f, 1.0f), wi = direction(1.2f, -2.0f);
        const auto f = bsdf.f(wo, wi);
        const auto a = bsdf.albedo(wo);
        for (int i = 0; i < bsdf.wl().count; ++i) {
            // Lambertian BRDF f = R(λ)/π (pbrt-v4 §9.2), R the exact uplifted spectrum
            const float expected = patina_rgb_spectrum_eval(&r, bsdf.wl().lambda_nm[i]) * kInvPi;
            EXPECT_NEAR(f[i], expected, 1e-6f) << "wavelength " << bsdf.wl().lambda_nm[i];
            EXPECT_NEAR(a[i], expected / kInvPi, 1e-6f);
        }
        // A grey is exactly constant over wavelength
        ParamSet grey(shader("lambert"));
        grey.set_color("reflectance", 0.3f, 0.3f, 0.3f);
        const Bsdf g("lambert", grey);
        const auto gf = g.f(wo, wi);
        for (int i = 0; i < g.wl().count; ++i)
            EXPECT_FLOAT_EQ(gf[i], 0.3f * kInvPi);
    }

    TEST(Lambert, ReflectsOnBothSidesAndTransmitsNothing)
    {
        ParamSet params(shader("lambert"));
        const Bsdf bsdf("lambert", params);
        const Vec3 wo = direction(0.5f, 0.3f), wi = direction(1.0f, 2.0f);
        const Vec3 wo_below(wo.x, wo.y, -wo.z), wi_below(wi.x, wi.y, -wi.z);
        EXPECT_FLOAT_EQ(bsdf.f0(wo, wi), 0.5f * kInvPi);
        EXPECT_FLOAT_EQ(bsdf.f0(wo_below, wi_below), 0.5f * kInvPi);
        EXPECT_EQ(bsdf.f0(wo, wi_below), 0.0f);
        EXPECT_EQ(bsdf.pdf(wo, wi_below), 0.0f);
        EXPECT_EQ(bsdf.f0(wo_below, wi), 0.0f);
        PatinaBsdfSample s;
        ASSERT_TRUE(bsdf.sample(wo_below, 0.5f, Vec2(0.3f, 0.7f), &s));
        EXPECT_LT(s.wi.z, 0.0f);
        EXPECT_EQ(s.lobe, PATINA_LOBE_REFLECTION | PATINA_LOBE_DIFFUSE);
    }

    TEST(Lambert, WhiteFurnaceAlbedoIsOne)
    {
        ParamSet params(shader("lambert"));
        params.set_color("reflectance", 1.0f, 1.0f, 1.0f);
        const Bsdf bsdf("lambert", params);
        for (float theta : {0.0f, 0.7f, 1.4f, 1.56f, 2.5f}) {
            const Vec3 wo = direction(theta, 0.3f);
            // ∫ (1/π) |cos θi| dωi over the hemisphere = 1, by quadrature (no sampling involved)
            EXPECT_NEAR(albedo_by_quadrature(bsdf, wo, 256), 1.0, 5e-3) << "theta " << theta;
            // and every importance sample weighs exactly R = 1
            EXPECT_NEAR(albedo_by_sampling(bsdf, wo, 10000), 1.0, 1e-5) << "theta " << theta;
        }
    }

    TEST(Lambert, IsReciprocal)
    {
        ParamSet params(shader("lambert"));
        params.set_color("reflectance", 0.9f, 0.5f, 0.1f);
        const Bsdf bsdf("lambert", params);
        Pcg32 rng(3);
        for (int k = 0; k < 1000; ++k) {
            const Vec3 wo = direction(1.5f * rng.next_float(), 6.28f * rng.next_float());
            const Vec3 wi = direction(1.5f * rng.next_float(), 6.28f * rng.next_float());
            EXPECT_EQ(reciprocity_error(bsdf.calls(), wo, wi), 0.0);
        }
    }

    TEST(Lambert, RejectsWhatItCannotHonour)
    {
        const PatinaShaderDesc& desc = shader("lambert");
        auto expect_rejected = [&](ParamSet& params, const char* what) {
            Instance instance(desc, params);
            EXPECT_FALSE(instance) << what;
            ASSERT_FALSE(test_host().errors.empty()) << what << ": no error message";
            EXPECT_NE(test_host().errors.front().find("reflectance"), std::string::npos)
                << test_host().errors.front();
        };
        {
            ParamSet p(desc);
            p.set_color("reflectance", 1.5f, 0.5f, 0.5f); // an albedo above 1 creates energy
            expect_rejected(p, "rgb above 1");
        }
        {
            ParamSet p(desc);
            p.set_color("reflectance", std::nanf(""), 0.5f, 0.5f);
            expect_rejected(p, "NaN");
        }
        {
            ParamSet p(desc);
            p.set_color_spectrum("reflectance",
                                 PatinaRgbSpectrum{0.0f, 0.0f, 0.0f, 3.0f, 0}); // 1.5
            expect_rejected(p, "spectrum above 1");
        }
        {
            ParamSet p(desc);
            p.set_color_spectrum("reflectance", PatinaRgbSpectrum{0.0f, 0.0f, 0.0f, 1.0f, 1});
            expect_rejected(p, "illuminant spectrum");
        }
        {
            ParamSet p(desc);
            p.set_color_spectrum("reflectance",
                                 PatinaRgbSpectrum{std::nanf(""), 0.0f, 0.0f, 1.0f, 0});
            expect_rejected(p, "NaN coefficient");
        }
    }

} // namespace
} // namespace patina::test
