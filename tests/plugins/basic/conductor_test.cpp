// conductor: closed-form Fresnel at normal incidence (copper, Johnson & Christy 1972), the
// smooth limit, white furnace with a perfect reflector, reciprocity, anisotropy, bad values.
#include "basic_plugin.h"

#include <patina/shading/fresnel.h>

namespace patina::test {
namespace {

    /// Copper n, k at some of Johnson & Christy's own wavelengths (P. B. Johnson and
    /// R. W. Christy, Phys. Rev. B 6, 4370 (1972), via refractiveindex.info), so that the
    /// plugin's table is hit at its nodes and no interpolation enters the comparison.
    struct NK {
        float lambda_nm, n, k;
    };
    constexpr NK kCopper[] = {{367.9f, 1.36f, 1.975f}, {413.3f, 1.28f, 2.207f},
                              {450.9f, 1.24f, 2.397f}, {520.9f, 1.18f, 2.608f},
                              {548.6f, 1.02f, 2.577f}, {616.8f, 0.30f, 3.205f},
                              {659.5f, 0.22f, 3.747f}, {821.1f, 0.26f, 5.180f}};

    /// Reflectance of a conductor at normal incidence: ((n−1)² + k²) / ((n+1)² + k²)
    /// (Born & Wolf, Principles of Optics, §14.2).
    double normal_reflectance(double n, double k)
    {
        return ((n - 1) * (n - 1) + k * k) / ((n + 1) * (n + 1) + k * k);
    }

    PatinaWavelengths copper_wavelengths()
    {
        std::vector<float> l;
        for (const NK& c : kCopper)
            l.push_back(c.lambda_nm);
        return wavelengths(l);
    }

    TEST(Conductor, SmoothCopperAtNormalIncidenceMatchesClosedForm)
    {
        ParamSet params(shader("conductor"));
        params.set_float("roughness", 0.0f);
        Bsdf bsdf("conductor", params);
        ASSERT_TRUE(bsdf);
        bsdf.set_wavelengths(copper_wavelengths());
        const Vec3 wo(0.0f, 0.0f, 1.0f);
        PatinaBsdfSample s;
        ASSERT_TRUE(bsdf.sample(wo, 0.3f, Vec2(0.2f, 0.9f), &s));
        EXPECT_EQ(s.lobe, PATINA_LOBE_REFLECTION | PATINA_LOBE_SPECULAR);
        EXPECT_FLOAT_EQ(s.pdf, 1.0f);
        EXPECT_NEAR(s.wi.z, 1.0f, 1e-7f);
        const auto albedo = bsdf.albedo(wo);
        for (int i = 0; i < 8; ++i) {
            const double r = normal_reflectance(kCopper[i].n, kCopper[i].k);
            EXPECT_NEAR(s.f[i] * s.wi.z / s.pdf, r, 2e-6) << kCopper[i].lambda_nm << " nm";
            EXPECT_NEAR(albedo[i], r, 2e-6) << kCopper[i].lambda_nm << " nm";
        }
        // Copper is red: it reflects 659.5 nm far better than 450.9 nm (J&C: 0.94 vs 0.54)
        EXPECT_GT(s.f[6], s.f[2] + 0.3f);
        // A delta lobe: eval and pdf never return it
        EXPECT_EQ(bsdf.f0(wo, s.wi), 0.0f);
        EXPECT_EQ(bsdf.pdf(wo, s.wi), 0.0f);
    }

    TEST(Conductor, SmoothReflectsMirrorDirectionWithExactFresnelOnBothSides)
    {
        ParamSet params(shader("conductor"));
        params.set_float("roughness", 0.0f).set_constant("eta", 0.2f).set_constant("k", 3.5f);
        const Bsdf bsdf("conductor", params);
        for (float theta : {0.3f, 1.0f, 1.5f, 2.0f, 2.9f}) {
            const Vec3 wo = direction(theta, 0.7f);
            PatinaBsdfSample s;
            ASSERT_TRUE(bsdf.sample(wo, 0.5f, Vec2(0.5f, 0.5f), &s));
            EXPECT_NEAR(s.wi.x, -wo.x, 1e-6f);
            EXPECT_NEAR(s.wi.y, -wo.y, 1e-6f);
            EXPECT_NEAR(s.wi.z, wo.z, 1e-6f);
            const float expected = shading::fresnel_conductor(std::abs(wo.z), 0.2f, 3.5f);
            EXPECT_NEAR(s.f[0] * std::abs(s.wi.z) / s.pdf, expected, 1e-6f) << "theta " << theta;
        }
        EXPECT_NEAR(shading::fresnel_conductor(1.0f, 0.2f, 3.5f), normal_reflectance(0.2, 3.5),
                    1e-6);
    }

    TEST(Conductor, NearlySmoothApproachesTheMirror)
    {
        // roughness 0.05 (alpha 0.0025): the sampled weights average to F at normal incidence
        ParamSet params(shader("conductor"));
        params.set_float("roughness", 0.05f);
        Bsdf bsdf("conductor", params);
        bsdf.set_wavelengths(copper_wavelengths());
        const double mc = albedo_by_sampling(bsdf, Vec3(0.0f, 0.0f, 1.0f), 20000);
        EXPECT_NEAR(mc, normal_reflectance(kCopper[0].n, kCopper[0].k), 5e-3);
    }

    TEST(Conductor, WhiteFurnaceNeverCreatesEnergy)
    {
        // n + ik = 0 + 1i reflects everything (|r| = 1 at every angle): what remains is the
        // microfacet model's own energy balance, which must not exceed 1
        for (float roughness : {0.2f, 0.5f, 1.0f}) {
            ParamSet params(shader("conductor"));
            params.set_float("roughness", roughness)
                .set_constant("eta", 0.0f)
                .set_constant("k", 1.0f);
            Bsdf bsdf("conductor", params);
            ASSERT_TRUE(bsdf);
            bsdf.set_wavelengths(wavelengths({550.0f}));
            for (float theta : {0.0f, 0.8f, 1.4f, 2.2f}) {
                SCOPED_TRACE("roughness " + std::to_string(roughness) + " theta " +
                             std::to_string(theta));
                const Vec3 wo = direction(theta, 0.4f);
                const double quadrature = albedo_by_quadrature(bsdf, wo, 384);
                const double sampled = albedo_by_sampling(bsdf, wo, 20000);
                EXPECT_LE(quadrature, 1.0 + 2e-3);
                EXPECT_LE(sampled, 1.0 + 1e-6); // every weight is G2/G1 <= 1
                EXPECT_NEAR(quadrature, sampled, 1e-2);
                std::printf(
                    "[ furnace  ] conductor r %.1f theta %.1f: quadrature %.5f, sampled %.5f\n",
                    roughness, theta, quadrature, sampled);
                if (roughness == 0.2f && theta == 0.0f) {
                    EXPECT_GT(quadrature, 0.97);
                }
            }
        }
    }

    TEST(Conductor, IsReciprocal)
    {
        for (float anisotropy : {0.0f, 0.9f}) {
            ParamSet params(shader("conductor"));
            params.set_float("roughness", 0.4f).set_float("anisotropy", anisotropy);
            const Bsdf bsdf("conductor", params);
            Pcg32 rng(17);
            for (int k = 0; k < 2000; ++k) {
                const float side = k % 2 ? 1.0f : -1.0f;
                Vec3 wo = direction(1.5f * rng.next_float(), 6.28f * rng.next_float());
                Vec3 wi = direction(1.5f * rng.next_float(), 6.28f * rng.next_float());
                wo.z *= side;
                wi.z *= side;
                ASSERT_LT(reciprocity_error(bsdf.calls(), wo, wi, 1e-7), 1e-5);
            }
        }
    }

    TEST(Conductor, AnisotropyStretchesTheLobeAlongDpdu)
    {
        ParamSet iso_params(shader("conductor"));
        iso_params.set_float("roughness", 0.3f);
        ParamSet aniso_params(shader("conductor"));
        aniso_params.set_float("roughness", 0.3f).set_float("anisotropy", 1.0f);
        const Bsdf iso("conductor", iso_params), aniso("conductor", aniso_params);
        const Vec3 wo(0.0f, 0.0f, 1.0f);
        const Vec3 tilt_x = direction(0.3f, 0.0f), tilt_y = direction(0.3f, shading::kPiOver2);
        EXPECT_NEAR(iso.f0(wo, tilt_x), iso.f0(wo, tilt_y), 1e-4f * iso.f0(wo, tilt_x));
        // Wider along x (alpha_x > alpha_y): more light reflected towards a tilt along x
        EXPECT_GT(aniso.f0(wo, tilt_x), 2.0f * aniso.f0(wo, tilt_y));
    }

    TEST(Conductor, RejectsWhatItCannotHonour)
    {
        const PatinaShaderDesc& desc = shader("conductor");
        auto expect_rejected = [&](ParamSet& params, const char* what, const char* mentions) {
            Instance instance(desc, params);
            EXPECT_FALSE(instance) << what;
            ASSERT_FALSE(test_host().errors.empty()) << what << ": no error message";
            EXPECT_NE(test_host().errors.front().find(mentions), std::string::npos)
                << what << ": " << test_host().errors.front();
        };
        const float nan = std::nanf("");
        {
            ParamSet p(desc);
            p.set_float("roughness", 1.5f);
            expect_rejected(p, "roughness > 1", "roughness");
        }
        {
            ParamSet p(desc);
            p.set_float("roughness", nan);
            expect_rejected(p, "roughness NaN", "roughness");
        }
        {
            ParamSet p(desc);
            p.set_float("anisotropy", -0.1f);
            expect_rejected(p, "anisotropy < 0", "anisotropy");
        }
        {
            ParamSet p(desc);
            p.set_spectrum("eta", {400, 500, 600}, {1, -0.5f, 1});
            expect_rejected(p, "negative eta", "eta:");
        }
        {
            ParamSet p(desc);
            p.set_spectrum("k", {400, 500, 600}, {1, nan, 1});
            expect_rejected(p, "NaN k", "k:");
        }
        {
            ParamSet p(desc);
            p.set_spectrum("eta", {500, 400, 600}, {1, 1, 1});
            expect_rejected(p, "unsorted", "increasing");
        }
        {
            ParamSet p(desc);
            p.set_spectrum("k", {}, {});
            expect_rejected(p, "empty table", "k:");
        }
        {
            ParamSet p(desc);
            p.set_constant("eta", 0.0f).set_constant("k", 0.0f);
            expect_rejected(p, "n + ik = 0", "vanish");
        }
        {
            // Both vanish at 500 nm only
            ParamSet p(desc);
            p.set_spectrum("eta", {400, 500, 600}, {1, 0, 1})
                .set_spectrum("k", {450, 500, 550}, {1, 0, 1});
            expect_rejected(p, "n + ik = 0 at 500 nm", "vanish");
        }
    }

} // namespace
} // namespace patina::test
