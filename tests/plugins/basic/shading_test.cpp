// The header-only helpers in <patina/shading/...>: Fresnel against independent formulas,
// normalisation of the microfacet distributions and of their visible normals, masking
// bounds, erfinv, refraction, frames, and the spectral helpers. (Their sampling routines
// are chi-square tested in chi2_test.cpp.)
#include "basic_plugin.h"

#include <patina/shading/fresnel.h>
#include <patina/shading/frame.h>
#include <patina/shading/microfacet.h>
#include <patina/shading/sampling.h>
#include <patina/shading/spectral.h>

namespace patina::test {
namespace {

    using namespace patina::shading;

    TEST(ShadingFresnel, ConductorMatchesTheRealFormulation)
    {
        const std::pair<float, float> indices[] = {{1.02f, 2.577f}, {0.22f, 3.747f}, {0.05f, 4.0f},
                                                   {2.5f, 0.3f},    {1.5f, 0.0f},    {0.0f, 1.0f}};
        for (const auto& [eta, k] : indices) {
            for (int i = 0; i <= 40; ++i) {
                const float c = std::max(1e-3f, i / 40.0f);
                // Two formulations (complex and real, fresnel.h) of Born & Wolf §14.2
                EXPECT_NEAR(fresnel_conductor(c, eta, k), fresnel_conductor_real(c, eta, k), 2e-6)
                    << "eta " << eta << " k " << k << " cos " << c;
            }
            EXPECT_NEAR(fresnel_conductor(1.0f, eta, k), fresnel_conductor_normal(eta, k), 1e-6);
            // Grazing incidence reflects everything
            EXPECT_NEAR(fresnel_conductor(0.0f, eta, k), 1.0f, 1e-6f);
        }
        // n = 0: a perfect reflector at every angle
        for (float c : {0.1f, 0.5f, 0.9f})
            EXPECT_NEAR(fresnel_conductor(c, 0.0f, 2.0f), 1.0f, 1e-6f);
    }

    TEST(ShadingFresnel, ConductorWithoutAbsorptionIsTheDielectric)
    {
        for (float eta : {1.2f, 1.5f, 2.4f})
            for (int i = 1; i <= 20; ++i) {
                const float c = i / 20.0f;
                EXPECT_NEAR(fresnel_conductor(c, eta, 0.0f), fresnel_dielectric(c, eta), 1e-6f);
            }
    }

    TEST(ShadingFresnel, DielectricClosedFormsAndSymmetry)
    {
        EXPECT_NEAR(fresnel_dielectric(1.0f, 1.5f), 0.04f, 1e-7f);
        EXPECT_NEAR(fresnel_dielectric_normal(1.5f), 0.04f, 1e-7f);
        EXPECT_NEAR(fresnel_dielectric(-1.0f, 1.5f), 0.04f, 1e-7f);
        EXPECT_EQ(fresnel_dielectric(1.0f, 1.0f), 0.0f);
        // Brewster's angle tan θB = η: only s-polarised light is reflected
        const float theta_b = std::atan(1.5f);
        const float rs = std::pow((std::cos(theta_b) - 1.5f * std::cos(kPiOver2 - theta_b)) /
                                      (std::cos(theta_b) + 1.5f * std::cos(kPiOver2 - theta_b)),
                                  2.0f);
        EXPECT_NEAR(fresnel_dielectric(std::cos(theta_b), 1.5f), 0.5f * rs, 1e-6f);
        // Light from inside beyond the critical angle is totally reflected
        EXPECT_EQ(fresnel_dielectric(-std::cos(0.8f), 1.5f), 1.0f);
        // Same reflectance seen from either side of a refraction pair (Stokes relations)
        for (float theta : {0.1f, 0.5f, 0.9f, 1.3f}) {
            const float sin_t = std::sin(theta) / 1.5f;
            const float cos_t = std::sqrt(1.0f - sin_t * sin_t);
            EXPECT_NEAR(fresnel_dielectric(std::cos(theta), 1.5f), fresnel_dielectric(-cos_t, 1.5f),
                        1e-6f);
        }
    }

    TEST(ShadingFrame, RefractFollowsSnellAndReportsTotalInternalReflection)
    {
        const Vec3 n(0, 0, 1);
        const Vec3 wi = direction(0.7f, 0.3f);
        Vec3 wt;
        float etap = 0.0f;
        ASSERT_TRUE(refract(wi, n, 1.5f, &etap, &wt));
        EXPECT_EQ(etap, 1.5f);
        EXPECT_NEAR(length(wt), 1.0f, 1e-6f);
        EXPECT_NEAR(sin_theta(wt), std::sin(0.7f) / 1.5f, 1e-6f);
        EXPECT_LT(wt.z, 0.0f);
        // Back through the interface: the original direction
        Vec3 back;
        ASSERT_TRUE(refract(wt, n, 1.5f, &etap, &back));
        EXPECT_NEAR(etap, 1.0f / 1.5f, 1e-7f);
        EXPECT_NEAR(back.x, wi.x, 1e-6f);
        EXPECT_NEAR(back.y, wi.y, 1e-6f);
        EXPECT_NEAR(back.z, wi.z, 1e-6f);
        // From inside at 50° > asin(1/1.5): no refraction
        EXPECT_FALSE(refract(direction(kPi - 0.87f, 0.0f), n, 1.5f, &etap, &wt));
        // reflect keeps the angle and the plane
        const Vec3 r = reflect(wi, n);
        EXPECT_NEAR(r.x, -wi.x, 1e-7f);
        EXPECT_NEAR(r.z, wi.z, 1e-7f);
    }

    TEST(ShadingFrame, FramesAreOrthonormalAndRoundTrip)
    {
        Pcg32 rng(8);
        for (int k = 0; k < 200; ++k) {
            const Vec3 n = sample_uniform_sphere(rng.next_vec2());
            const Frame f = Frame::from_z(n);
            EXPECT_NEAR(dot(f.x, f.y), 0.0f, 1e-6f);
            EXPECT_NEAR(dot(f.x, f.z), 0.0f, 1e-6f);
            EXPECT_NEAR(length(f.x), 1.0f, 1e-6f);
            EXPECT_NEAR(length(f.y), 1.0f, 1e-6f);
            const Vec3 c = cross(f.x, f.y); // right-handed
            EXPECT_NEAR(dot(c, n), 1.0f, 1e-5f);
            const Vec3 v = sample_uniform_sphere(rng.next_vec2());
            const Vec3 back = f.from_local(f.to_local(v));
            EXPECT_NEAR(length(back - v), 0.0f, 1e-5f);
        }
        const Frame s = Frame::from_xz(Vec3(2, 0, 1), Vec3(0, 0, 1));
        EXPECT_NEAR(s.x.x, 1.0f, 1e-7f);
        EXPECT_NEAR(s.y.y, 1.0f, 1e-7f);
    }

    TEST(ShadingSampling, WarpsStayInTheirDomains)
    {
        Pcg32 rng(2);
        for (int k = 0; k < 10000; ++k) {
            const Vec2 u = rng.next_vec2();
            EXPECT_LE(length(sample_uniform_disk_concentric(u)), 1.0f + 1e-6f);
            const Vec3 h = sample_cosine_hemisphere(u);
            EXPECT_GE(h.z, 0.0f);
            EXPECT_NEAR(length(h), 1.0f, 1e-5f);
            EXPECT_NEAR(length(sample_uniform_sphere(u)), 1.0f, 1e-5f);
        }
    }

    /// ∫ g(w) dω over the upper hemisphere by the midpoint rule in (θ, φ).
    template <typename G> double integrate_hemisphere(const G& g, int theta_res = 400)
    {
        const int phi_res = 2 * theta_res;
        const double dtheta = 0.5 * M_PI / theta_res, dphi = 2.0 * M_PI / phi_res;
        double sum = 0.0;
        for (int i = 0; i < theta_res; ++i) {
            const double theta = (i + 0.5) * dtheta;
            for (int j = 0; j < phi_res; ++j) {
                const Vec3 w =
                    direction(static_cast<float>(theta), static_cast<float>((j + 0.5) * dphi));
                sum += g(w) * std::sin(theta);
            }
        }
        return sum * dtheta * dphi;
    }

    template <typename Distribution> void expect_normalised(const Distribution& d, const char* name)
    {
        SCOPED_TRACE(name);
        // Projected area of the microsurface is 1: ∫ D(wm) cos θm dωm = 1 (Heitz 2014)
        EXPECT_NEAR(integrate_hemisphere([&](Vec3 wm) { return d.d(wm) * wm.z; }), 1.0, 2e-3);
        // Visible normals integrate to 1, which holds only with the matching Λ (Heitz 2014)
        for (float theta : {0.0f, 0.6f, 1.2f, 1.5f, 2.4f}) {
            const Vec3 w = direction(theta, 0.7f);
            EXPECT_NEAR(integrate_hemisphere([&](Vec3 wm) { return d.d_visible(w, wm); }), 1.0,
                        2e-3)
                << "theta " << theta;
        }
        // Masking bounds: G1(wo) G1(wi) <= G2(wo, wi) <= min(G1(wo), G1(wi)) <= 1
        Pcg32 rng(4);
        for (int k = 0; k < 200; ++k) {
            const Vec3 wo = sample_uniform_sphere(rng.next_vec2()),
                       wi = sample_uniform_sphere(rng.next_vec2());
            const float g2 = d.g(wo, wi), g1o = d.g1(wo), g1i = d.g1(wi);
            EXPECT_LE(g1o * g1i, g2 + 1e-6f);
            EXPECT_LE(g2, std::min(g1o, g1i) + 1e-6f);
            EXPECT_LE(g1o, 1.0f);
        }
        EXPECT_EQ(d.g1(Vec3(0, 0, 1)), 1.0f);
        EXPECT_EQ(d.g1(Vec3(1, 0, 0)), 0.0f);
        EXPECT_EQ(d.d(Vec3(0, 0, -1)), 0.0f);
    }

    TEST(ShadingMicrofacet, DistributionsAndVisibleNormalsAreNormalised)
    {
        expect_normalised(TrowbridgeReitz(0.3f, 0.3f), "ggx 0.3");
        expect_normalised(TrowbridgeReitz(0.15f, 0.6f), "ggx 0.15 x 0.6");
        expect_normalised(TrowbridgeReitz(1.0f, 1.0f), "ggx 1");
        expect_normalised(Beckmann(0.3f, 0.3f), "beckmann 0.3");
        expect_normalised(Beckmann(0.2f, 0.7f), "beckmann 0.2 x 0.7");
        expect_normalised(Beckmann(1.0f, 1.0f), "beckmann 1");
    }

    TEST(ShadingMicrofacet, ClosedFormsAtTheNormal)
    {
        // D(n) = 1/(π α²) for both distributions
        EXPECT_NEAR(TrowbridgeReitz(0.5f, 0.5f).d(Vec3(0, 0, 1)), 1.0f / (kPi * 0.25f), 1e-6f);
        EXPECT_NEAR(Beckmann(0.5f, 0.5f).d(Vec3(0, 0, 1)), 1.0f / (kPi * 0.25f), 1e-6f);
        // GGX Λ at tan θ = 1/α: (−1 + √2)/2; Beckmann Λ at a = 1: (erf(1) − 1)/2 + e⁻¹/(2√π)
        const float a = 0.5f, theta = std::atan(1.0f / a);
        const Vec3 w = direction(theta, 0.3f);
        EXPECT_NEAR(TrowbridgeReitz(a, a).lambda(w), (std::sqrt(2.0f) - 1.0f) / 2.0f, 1e-6f);
        EXPECT_NEAR(Beckmann(a, a).lambda(w),
                    (std::erf(1.0) - 1.0) / 2.0 + std::exp(-1.0) / (2.0 * std::sqrt(M_PI)), 1e-6);
        // Tiny widths stay finite
        const TrowbridgeReitz sharp(1e-6f, 1e-6f);
        EXPECT_TRUE(std::isfinite(sharp.d(Vec3(0, 0, 1))));
        EXPECT_TRUE(is_finite(sharp.sample_wm(direction(0.5f, 0.1f), Vec2(0.3f, 0.3f))));
        EXPECT_LT(sharp.d(direction(0.1f, 0.0f)), 1e-6f); // 0.1 rad off: negligible
    }

    TEST(ShadingMicrofacet, ErfinvInvertsErf)
    {
        for (double x = -0.999999; x < 1.0; x += 0.0123)
            EXPECT_NEAR(std::erf(detail::erfinv(x)), x, 1e-13) << x;
        EXPECT_TRUE(std::isinf(detail::erfinv(1.0)));
    }

    TEST(ShadingSpectral, HelpersEvaluateLikeTheAbi)
    {
        const float lambda[] = {400.0f, 500.0f, 700.0f};
        const float value[] = {0.1f, 0.5f, 0.2f};
        const PatinaTabulatedSpectrum t{3, lambda, value};
        EXPECT_EQ(check_tabulated(t), nullptr);
        const TabulatedSpectrum copy(t);
        const PatinaWavelengths wl = wavelengths({380.0f, 450.0f, 600.0f, 800.0f});
        const SpectralArray a = copy.eval(wl);
        for (int i = 0; i < wl.count; ++i)
            EXPECT_EQ(a[i], patina_tabulated_eval(&t, wl.lambda_nm[i]));
        EXPECT_FLOAT_EQ(a[1], 0.3f);
        EXPECT_FLOAT_EQ(a[2], 0.35f);
        // Broken tables are named
        const float unsorted[] = {500.0f, 400.0f, 700.0f};
        EXPECT_NE(check_tabulated(PatinaTabulatedSpectrum{3, unsorted, value}), nullptr);
        EXPECT_NE(check_tabulated(PatinaTabulatedSpectrum{0, lambda, value}), nullptr);
        // The exact range of an RGB spectrum: brute force over 1 nm agrees
        const PatinaRgbSpectrum s{-2e-4f, 0.22f, -58.0f, 0.9f, 0}; // a bump near 550 nm
        float lo = 0, hi = 0;
        rgb_spectrum_range(s, &lo, &hi);
        float blo = 1e9f, bhi = -1e9f;
        for (float l = PATINA_LAMBDA_MIN_NM; l <= PATINA_LAMBDA_MAX_NM; l += 0.25f) {
            const float v = patina_rgb_spectrum_eval(&s, l);
            blo = std::min(blo, v);
            bhi = std::max(bhi, v);
        }
        EXPECT_NEAR(lo, blo, 1e-5f);
        EXPECT_NEAR(hi, bhi, 1e-5f);
        EXPECT_GT(hi, lo + 0.1f);
        // eval_rgb is patina_rgb_spectrum_eval at each wavelength
        const SpectralArray r = eval_rgb(s, wl);
        for (int i = 0; i < wl.count; ++i)
            EXPECT_EQ(r[i], patina_rgb_spectrum_eval(&s, wl.lambda_nm[i]));
    }

} // namespace
} // namespace patina::test
