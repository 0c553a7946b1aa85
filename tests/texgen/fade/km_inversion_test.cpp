// Appendix A of Kimmel et al. 2013: K and S from reflectance over black and over white,
// and the R_inf route of the patina paper.
#include "texgen/fade/km_inversion.h"

#include "test_util.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace patina::texgen::fade;

TEST(KmInversion, Eq37MatchesItsPrintedForm)
{
    // Eq. (37) as printed, with a, b of Eqs. (38), (39).
    const double mu_a = 1.5e4, mu_s = 4e4, Z = 70e-6, rho_g = 0.35;
    // Eq. (38) as printed divides by mu_a, but Eqs. (22) and (48) (mu_a = (a - 1) mu_s) need
    // a = (mu_a + mu_s) / mu_s: the consistent reading, used here.
    const double as = (mu_a + mu_s) / mu_s, b = std::sqrt(as * as - 1.0);
    const double coth = 1.0 / std::tanh(b * mu_s * Z);
    const double printed = (1.0 - rho_g * (as - b * coth)) / (as + b * coth - rho_g);
    EXPECT_NEAR(km_layer_reflectance(mu_a, mu_s, Z, rho_g), printed, 1e-14);
    // Limits: no absorption, no scattering.
    EXPECT_NEAR(km_layer_reflectance(0.0, mu_s, Z, 0.0), mu_s * Z / (1.0 + mu_s * Z), 1e-14);
    EXPECT_NEAR(km_layer_reflectance(mu_a, 0.0, Z, rho_g), rho_g * std::exp(-2.0 * mu_a * Z),
                1e-14);
}

TEST(KmInversion, RecoversKAndSFromBlackAndWhiteGrounds)
{
    struct Case {
        double mu_a, mu_s, Z, rho_b, rho_w;
    };
    for (const Case& c : {Case{1.5e4, 4e4, 70e-6, 0.0, 1.0}, Case{2e3, 1.6e4, 70e-6, 0.04, 1.0},
                          Case{3e5, 2e5, 10e-6, 0.05, 0.95}, Case{50.0, 9e4, 100e-6, 0.02, 1.0},
                          Case{6e4, 1e3, 30e-6, 0.03, 0.98}}) {
        // Synthesise the two measurements (Eqs. 44, 45), then invert (Eqs. 46-48).
        const double rho_0 = km_layer_reflectance(c.mu_a, c.mu_s, c.Z, c.rho_b);
        const double rho_1 = km_layer_reflectance(c.mu_a, c.mu_s, c.Z, c.rho_w);
        const KmCoefficients k = invert_black_white(rho_0, c.rho_b, rho_1, c.Z, c.rho_w);
        EXPECT_NEAR(k.absorption_per_m / c.mu_a, 1.0, 1e-8) << c.mu_a << " " << c.mu_s;
        EXPECT_NEAR(k.scattering_per_m / c.mu_s, 1.0, 1e-8) << c.mu_a << " " << c.mu_s;
    }
    // A non-absorbing layer (a = 1); over a perfect white it would reflect 1, so the white
    // ground here reflects 0.9.
    const double r0 = km_layer_reflectance(0.0, 3e4, 50e-6, 0.0);
    const double r1 = km_layer_reflectance(0.0, 3e4, 50e-6, 0.9);
    const KmCoefficients k = invert_black_white(r0, 0.0, r1, 50e-6, 0.9);
    EXPECT_NEAR(k.absorption_per_m, 0.0, 1e-3);
    EXPECT_NEAR(k.scattering_per_m / 3e4, 1.0, 1e-6);
}

TEST(KmInversion, ImpossibleMeasurementsAreReported)
{
    EXPECT_NE(patina::test::message_of([] { invert_black_white(0.5, 0.0, 0.4, 70e-6); })
                  .find("no solution"),
              std::string::npos);
    EXPECT_NE(patina::test::message_of([] { invert_black_white(0.2, 0.0, 0.5, 0.0); })
                  .find("thickness"),
              std::string::npos);
    EXPECT_THROW(invert_black_white(1.2, 0.0, 0.5, 1e-5), std::runtime_error);
}

TEST(KmInversion, RInfinityRoute)
{
    // R_inf = 1 + K/S - sqrt((K/S)^2 + 2 K/S) (D&H 1996 §4.1) and back.
    EXPECT_NEAR(km_r_infinity(0.5), 1.5 - std::sqrt(0.25 + 1.0), 1e-15);
    for (double q : {0.0, 1e-4, 0.3, 2.0, 50.0})
        EXPECT_NEAR(km_k_over_s(km_r_infinity(q)), q, 1e-9 * (1.0 + q));
    const KmCoefficients k = from_r_infinity(km_r_infinity(0.8), 1.65e4);
    EXPECT_NEAR(k.absorption_per_m, 0.8 * 1.65e4, 1e-6);
    EXPECT_EQ(k.scattering_per_m, 1.65e4);
    // An optically thick layer reflects R_inf (Eq. 37 with Z -> infinity).
    EXPECT_NEAR(km_layer_reflectance(0.8 * 1.65e4, 1.65e4, 1.0, 0.3), km_r_infinity(0.8), 1e-12);
    EXPECT_THROW(from_r_infinity(0.0, 1.0), std::runtime_error);
    EXPECT_THROW(from_r_infinity(0.5, -1.0), std::runtime_error);
}
