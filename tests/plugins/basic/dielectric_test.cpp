// dielectric: Fresnel closed forms and Snell's law of the smooth interface, radiance vs
// importance scaling, white furnace (reflection + transmission), generalised reciprocity,
// the invisible eta = 1 boundary, bad values.
#include "basic_plugin.h"

namespace patina::test {
namespace {

    /// Textbook Fresnel reflectance of unpolarised light from a medium of index n1 into n2
    /// (Hecht, Optics, 4th ed., §4.6.2), written independently of <patina/shading/fresnel.h>.
    double fresnel_textbook(double cos_i, double n1, double n2)
    {
        const double sin_t = n1 / n2 * std::sqrt(std::max(0.0, 1.0 - cos_i * cos_i));
        if (sin_t >= 1.0)
            return 1.0;
        const double cos_t = std::sqrt(1.0 - sin_t * sin_t);
        const double rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
        const double rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
        return 0.5 * (rs * rs + rp * rp);
    }

    Bsdf make(float eta, float roughness, PatinaTransportMode mode = PATINA_TRANSPORT_RADIANCE)
    {
        ParamSet params(shader("dielectric"));
        params.set_float("eta", eta).set_float("roughness", roughness);
        return Bsdf("dielectric", params, mode);
    }

    TEST(Dielectric, SmoothNormalIncidenceReflectsFresnelR0)
    {
        for (float eta : {1.33f, 1.5f, 2.4f}) {
            // R at normal incidence ((η − 1)/(η + 1))²: Hecht §4.6.2
            const float r0 = ((eta - 1.0f) / (eta + 1.0f)) * ((eta - 1.0f) / (eta + 1.0f));
            const float t0 = 1.0f - r0;
            for (const PatinaTransportMode mode :
                 {PATINA_TRANSPORT_RADIANCE, PATINA_TRANSPORT_IMPORTANCE}) {
                const Bsdf bsdf = make(eta, 0.0f, mode);
                ASSERT_TRUE(bsdf);
                const bool radiance = mode == PATINA_TRANSPORT_RADIANCE;
                for (const float side : {1.0f, -1.0f}) {
                    SCOPED_TRACE("eta " + std::to_string(eta) +
                                 (radiance ? " radiance" : " importance") +
                                 (side > 0 ? " outside" : " inside"));
                    const Vec3 wo(0.0f, 0.0f, side);
                    PatinaBsdfSample s;
                    // Reflection, chosen with probability R
                    ASSERT_TRUE(bsdf.sample(wo, 0.0f, Vec2(0.5f, 0.5f), &s));
                    EXPECT_EQ(s.lobe, PATINA_LOBE_REFLECTION | PATINA_LOBE_SPECULAR);
                    EXPECT_NEAR(s.pdf, r0, 1e-6f);
                    EXPECT_NEAR(s.f[0] * std::abs(s.wi.z), r0, 1e-6f);
                    EXPECT_EQ(s.wi.z, side);
                    EXPECT_EQ(s.eta, 1.0f);
                    // Transmission, chosen with probability T; radiance scales by 1/η'²
                    ASSERT_TRUE(bsdf.sample(wo, 0.9f, Vec2(0.5f, 0.5f), &s));
                    EXPECT_EQ(s.lobe, PATINA_LOBE_TRANSMISSION | PATINA_LOBE_SPECULAR);
                    EXPECT_NEAR(s.pdf, t0, 1e-6f);
                    EXPECT_NEAR(s.wi.z, -side, 1e-7f);
                    const float etap = side > 0 ? eta : 1.0f / eta;
                    EXPECT_NEAR(s.eta, etap, 1e-6f);
                    const float expected = radiance ? t0 / (etap * etap) : t0;
                    EXPECT_NEAR(s.f[0] * std::abs(s.wi.z), expected, 1e-5f * expected);
                }
            }
        }
    }

    TEST(Dielectric, SmoothObliqueFollowsSnellAndFresnel)
    {
        const float eta = 1.5f;
        const Bsdf bsdf = make(eta, 0.0f);
        for (float theta_deg : {10.0f, 35.0f, 60.0f, 85.0f}) {
            const float theta = theta_deg * shading::kPi / 180.0f;
            // From outside (air, n1 = 1) into glass (n2 = 1.5)
            const Vec3 wo = direction(theta, 0.5f);
            const double r = fresnel_textbook(std::cos(theta), 1.0, eta);
            PatinaBsdfSample s;
            ASSERT_TRUE(bsdf.sample(wo, 0.0f, Vec2(0.1f, 0.1f), &s));
            EXPECT_NEAR(s.pdf, r, 1e-5) << theta_deg;
            ASSERT_TRUE(bsdf.sample(wo, 0.999f, Vec2(0.1f, 0.1f), &s));
            EXPECT_NEAR(s.pdf, 1.0 - r, 1e-5) << theta_deg;
            // Snell: sin θt = sin θi / η, in the plane of incidence, on the other side
            const float sin_t = std::sqrt(s.wi.x * s.wi.x + s.wi.y * s.wi.y);
            EXPECT_NEAR(sin_t, std::sin(theta) / eta, 1e-6f) << theta_deg;
            EXPECT_LT(s.wi.z, 0.0f);
            EXPECT_NEAR(s.wi.x * wo.y - s.wi.y * wo.x, 0.0f, 1e-6f);
            EXPECT_LT(s.wi.x * wo.x + s.wi.y * wo.y, 0.0f);
        }
        // From inside beyond the critical angle asin(1/1.5) = 41.8°: total internal reflection
        const Vec3 inside = direction(shading::kPi - 50.0f * shading::kPi / 180.0f, 0.2f);
        for (float u_lobe : {0.0f, 0.5f, 0.999f}) {
            PatinaBsdfSample s;
            ASSERT_TRUE(bsdf.sample(inside, u_lobe, Vec2(0.5f, 0.5f), &s));
            EXPECT_EQ(s.lobe, PATINA_LOBE_REFLECTION | PATINA_LOBE_SPECULAR);
            EXPECT_FLOAT_EQ(s.pdf, 1.0f);
            EXPECT_NEAR(s.f[0] * std::abs(s.wi.z), 1.0f, 1e-6f);
        }
        // Inside below the critical angle, R from glass into air
        const Vec3 inside30 = direction(shading::kPi - 30.0f * shading::kPi / 180.0f, 0.2f);
        PatinaBsdfSample s;
        ASSERT_TRUE(bsdf.sample(inside30, 0.0f, Vec2(0.5f, 0.5f), &s));
        EXPECT_NEAR(s.pdf, fresnel_textbook(std::cos(30.0 * M_PI / 180.0), eta, 1.0), 1e-5);
    }

    TEST(Dielectric, EtaOneIsAnInvisibleBoundary)
    {
        for (float roughness : {0.0f, 0.5f}) {
            const Bsdf bsdf = make(1.0f, roughness);
            const Vec3 wo = direction(0.9f, 2.0f);
            PatinaBsdfSample s;
            ASSERT_TRUE(bsdf.sample(wo, 0.3f, Vec2(0.7f, 0.1f), &s));
            EXPECT_EQ(s.lobe, PATINA_LOBE_TRANSMISSION | PATINA_LOBE_SPECULAR);
            EXPECT_NEAR(s.wi.x, -wo.x, 1e-6f);
            EXPECT_NEAR(s.wi.y, -wo.y, 1e-6f);
            EXPECT_NEAR(s.wi.z, -wo.z, 1e-6f);
            EXPECT_NEAR(s.f[0] * std::abs(s.wi.z) / s.pdf, 1.0f, 1e-6f);
            EXPECT_EQ(bsdf.f0(wo, s.wi), 0.0f);
        }
    }

    TEST(Dielectric, WhiteFurnaceReflectionPlusTransmission)
    {
        // Importance mode: what arrives is reflected or transmitted, never more (a smooth
        // interface exactly 1, a rough one loses what single scattering cannot account for)
        for (float theta : {0.0f, 0.9f, 2.0f, 2.9f}) {
            const Bsdf smooth = make(1.5f, 0.0f, PATINA_TRANSPORT_IMPORTANCE);
            EXPECT_NEAR(albedo_by_sampling(smooth, direction(theta, 0.3f), 2000), 1.0, 1e-5);
        }
        for (float roughness : {0.3f, 0.6f}) {
            Bsdf bsdf = make(1.5f, roughness, PATINA_TRANSPORT_IMPORTANCE);
            bsdf.set_wavelengths(wavelengths({550.0f}));
            for (float theta : {0.0f, 0.9f, 1.4f, 2.0f, 2.9f}) {
                SCOPED_TRACE("roughness " + std::to_string(roughness) + " theta " +
                             std::to_string(theta));
                const Vec3 wo = direction(theta, 0.3f);
                const double quadrature = albedo_by_quadrature(bsdf, wo, 384);
                const double sampled = albedo_by_sampling(bsdf, wo, 20000);
                std::printf("[ furnace  ] dielectric eta 1.5 r %.1f theta %.1f: quadrature %.5f, "
                            "sampled %.5f\n",
                            roughness, theta, quadrature, sampled);
                EXPECT_LE(quadrature, 1.0 + 3e-3);
                EXPECT_NEAR(quadrature, sampled, 1.5e-2);
            }
        }
        // Nearly smooth: close to the smooth interface's 1
        const Bsdf nearly = make(1.5f, 0.05f, PATINA_TRANSPORT_IMPORTANCE);
        EXPECT_GT(albedo_by_sampling(nearly, direction(0.3f, 0.0f), 20000), 0.98);
    }

    TEST(Dielectric, RadianceModeScalesTransmissionByInverseEtaSquared)
    {
        const Bsdf radiance = make(1.5f, 0.4f, PATINA_TRANSPORT_RADIANCE);
        const Bsdf importance = make(1.5f, 0.4f, PATINA_TRANSPORT_IMPORTANCE);
        const Vec3 wo = direction(0.5f, 0.0f);
        const Vec3 wi = direction(shading::kPi - 0.4f, shading::kPi); // refracted side, inside
        const float fr = radiance.f0(wo, wi), fi = importance.f0(wo, wi);
        ASSERT_GT(fi, 0.0f);
        EXPECT_NEAR(fr, fi / (1.5f * 1.5f), 1e-6f * fi);
        // Reflection does not depend on the mode; neither does the pdf
        const Vec3 wr = direction(0.6f, shading::kPi);
        EXPECT_EQ(radiance.f0(wo, wr), importance.f0(wo, wr));
        EXPECT_EQ(radiance.pdf(wo, wi), importance.pdf(wo, wi));
    }

    TEST(Dielectric, GeneralisedReciprocity)
    {
        // Reflection: f(wo, wi) = f(wi, wo). Transmission in radiance mode:
        // f(wo, wi) / η_o² = f(wi, wo) / η_i² (Veach 1997, §5.2), η_o, η_i the indices on the
        // sides of wo and wi; and the adjoint: f_importance(wo, wi) = f_radiance(wi, wo)
        const float eta = 1.5f;
        for (float roughness : {0.2f, 0.5f}) {
            const Bsdf radiance = make(eta, roughness, PATINA_TRANSPORT_RADIANCE);
            const Bsdf importance = make(eta, roughness, PATINA_TRANSPORT_IMPORTANCE);
            Pcg32 rng(23);
            int transmissions = 0;
            for (int k = 0; k < 4000; ++k) {
                const Vec3 wo = direction(3.14f * rng.next_float(), 6.28f * rng.next_float());
                const Vec3 wi = direction(3.14f * rng.next_float(), 6.28f * rng.next_float());
                const float f_oi = radiance.f0(wo, wi), f_io = radiance.f0(wi, wo);
                if (wo.z * wi.z > 0.0f) {
                    ASSERT_NEAR(f_oi, f_io, 1e-4f * f_oi + 1e-9f);
                } else {
                    const float eta_o = wo.z > 0.0f ? 1.0f : eta, eta_i = wi.z > 0.0f ? 1.0f : eta;
                    // Near the critical angle 1 − F is ill-conditioned in float: 3e-3 relative,
                    // 1e-6 absolute (f itself is of order 1 and more)
                    ASSERT_NEAR(f_oi / (eta_o * eta_o), f_io / (eta_i * eta_i),
                                3e-3f * f_oi + 1e-6f);
                    transmissions += f_oi > 0.0f;
                }
                ASSERT_NEAR(importance.f0(wo, wi), f_io, 3e-3f * f_io + 1e-6f);
            }
            EXPECT_GT(transmissions, 200);
        }
    }

    TEST(Dielectric, RejectsWhatItCannotHonour)
    {
        const PatinaShaderDesc& desc = shader("dielectric");
        auto expect_rejected = [&](float eta, float roughness, const char* mentions) {
            ParamSet params(desc);
            params.set_float("eta", eta).set_float("roughness", roughness);
            Instance instance(desc, params);
            EXPECT_FALSE(instance) << eta << " " << roughness;
            ASSERT_FALSE(test_host().errors.empty()) << "no error message";
            EXPECT_NE(test_host().errors.front().find(mentions), std::string::npos)
                << test_host().errors.front();
        };
        expect_rejected(0.9f, 0.1f, "eta");
        expect_rejected(4.5f, 0.1f, "eta");
        expect_rejected(std::nanf(""), 0.1f, "eta");
        expect_rejected(1.5f, -0.1f, "roughness");
        expect_rejected(1.5f, std::nanf(""), "roughness");
    }

} // namespace
} // namespace patina::test
