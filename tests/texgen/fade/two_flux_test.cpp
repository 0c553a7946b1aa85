// The two-flux system of Kimmel et al. 2013 §4.1: the O(N) adding-method solve against a
// dense solve of the same matrix (Eqs. 28-34), Kubelka's sublayer formulas (Eqs. 22, 23)
// and the folding of sublayers into a layer's R_top, T, R_bottom.
#include "texgen/fade/layer_optics.h"
#include "texgen/fade/two_flux.h"

#include "dense_two_flux.h"

#include <patina/shading/kubelka_munk.h>
#include "core/sampling.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

using namespace patina::texgen::fade;
using patina::texgen::fade::test::dense_solve;

namespace {

struct Stack {
    std::vector<double> rho, tau;
};

// N sublayers of random absorption and scattering (1/m) over a 100 µm layer.
Stack random_stack(size_t n, uint64_t seed, double max_mu)
{
    patina::Pcg32 rng(seed);
    Stack s;
    const double dz = 100e-6 / static_cast<double>(n);
    for (size_t i = 0; i < n; ++i) {
        const double mu_a = max_mu * rng.uniform_float();
        const double mu_s = max_mu * rng.uniform_float();
        const SublayerOptics o = sublayer_optics(mu_a, mu_s, dz);
        s.rho.push_back(o.rho);
        s.tau.push_back(o.tau);
    }
    return s;
}

}  // namespace

TEST(TwoFlux, AddingMethodEqualsDenseSolve)
{
    for (size_t n : {1u, 2u, 7u, 60u}) {
        for (const TwoFluxBoundary bc : {TwoFluxBoundary{1.0, 0.0, 0.8},
                                         TwoFluxBoundary{2.5, 0.0, 0.0},
                                         TwoFluxBoundary{1.0, 0.7, 0.0},
                                         TwoFluxBoundary{0.0, 1.0, 0.3}}) {
            const Stack s = random_stack(n, 17 + n, 3e5);
            std::vector<double> down(n + 1), up(n + 1), down_ref, up_ref;
            solve_two_flux(s.rho, s.tau, bc, down, up);
            dense_solve(s.rho, s.tau, bc, down_ref, up_ref);
            for (size_t i = 0; i <= n; ++i) {
                EXPECT_NEAR(down[i], down_ref[i], 1e-10) << "n " << n << " i " << i;
                EXPECT_NEAR(up[i], up_ref[i], 1e-10) << "n " << n << " i " << i;
            }
        }
    }
}

TEST(TwoFlux, SublayerOpticsMatchesKubelkaAndItsLimits)
{
    // Eqs. (22), (23) evaluated as printed with a = (S + K)/S, b = sqrt(a^2 - 1).
    const double K = 2.0e4, S = 3.0e4, dz = 50e-6;
    const double a = (S + K) / S, b = std::sqrt(a * a - 1.0), x = b * S * dz;
    const SublayerOptics o = sublayer_optics(K, S, dz);
    EXPECT_NEAR(o.rho, 1.0 / (a + b / std::tanh(x)), 1e-14);
    EXPECT_NEAR(o.tau, b / (a * std::sinh(x) + b * std::cosh(x)), 1e-14);
    // Non-scattering: Beer-Lambert; non-absorbing: rho = S d / (1 + S d) (Kubelka 1948).
    EXPECT_NEAR(sublayer_optics(K, 0.0, dz).tau, std::exp(-K * dz), 1e-15);
    EXPECT_EQ(sublayer_optics(K, 0.0, dz).rho, 0.0);
    EXPECT_NEAR(sublayer_optics(0.0, S, dz).rho, S * dz / (1.0 + S * dz), 1e-15);
    EXPECT_NEAR(sublayer_optics(0.0, S, dz).tau, 1.0 / (1.0 + S * dz), 1e-15);
    // No jump where the series branch (x < 1e-2) hands over to the exponential one.
    const double kb = 1e-2 / dz;  // K with S = 0 puts x exactly at the switch
    const SublayerOptics lo = sublayer_optics(kb * (1 - 1e-9), 1.0, dz);
    const SublayerOptics hi = sublayer_optics(kb * (1 + 1e-9), 1.0, dz);
    EXPECT_NEAR(lo.tau, hi.tau, 1e-10);
    EXPECT_NEAR(lo.rho, hi.rho, 1e-10);
    // Very thick: R_inf and no overflow.
    const SublayerOptics thick = sublayer_optics(K, S, 1.0);
    EXPECT_NEAR(thick.rho, patina::shading::km_r_infinity(K / S), 1e-6);
    EXPECT_LT(thick.tau, 1e-300);
}

TEST(TwoFlux, BranchFreeExponentialIsAccurate)
{
    for (double y = -750.0; y <= 0.0; y += 0.0137) {
        const double ref = std::exp(std::max(y, -708.0));
        EXPECT_NEAR(exp_nonpositive(y) / ref, 1.0, 1e-15) << y;
    }
    EXPECT_EQ(exp_nonpositive(0.0), 1.0);
    for (double v = 1e-300; v < 1e300; v *= 1.7)
        EXPECT_NEAR(sqrt_nonnegative(v) / std::sqrt(v), 1.0, 1e-15) << v;
    EXPECT_EQ(sqrt_nonnegative(0.0), 0.0);
    EXPECT_EQ(exp_nonpositive(1.0), 1.0);  // clamped: only y <= 0 is meant
}

TEST(TwoFlux, SinglePrecisionHelpersAreAccurate)
{
    // The float kernel's exp (degree-7 Taylor) and 1/sqrt (three Newton steps), against
    // the library in double: within a few float roundings (2^-24 = 6e-8).
    for (double y = -87.0; y <= 0.0; y += 0.0071) {
        const float yf = static_cast<float>(y);
        EXPECT_NEAR(exp_nonpositive(yf) / std::exp(static_cast<double>(yf)), 1.0, 3e-7) << y;
    }
    for (double v = 1e-20; v < 1e30; v *= 1.37) {
        const float f = static_cast<float>(v);
        EXPECT_NEAR(rsqrt_positive(f) * std::sqrt(static_cast<double>(f)), 1.0, 3e-7) << v;
    }
    // The float sublayer terms against the double ones over the kernels' range of x.
    for (double K : {0.0, 1e2, 1e4, 1e5, 1e6, 1e7})
        for (double S : {0.0, 1e3, 2e4, 1e5}) {
            const double dz = 0.7e-6;
            const SublayerTerms<double> d = sublayer_terms(K, S, dz);
            const SublayerTerms<float> f = sublayer_terms(static_cast<float>(K),
                                                          static_cast<float>(S), 0.7e-6f);
            EXPECT_NEAR(f.a / f.d, d.a / d.d, 1e-6) << K << " " << S;
            EXPECT_NEAR(f.t / f.d, d.t / d.d, 1e-6) << K << " " << S;
        }
}

TEST(TwoFlux, TopReflectanceEqualsKmCompositingOfTheSublayers)
{
    // The system's E^u_0 / E_0 against patina/shading/kubelka_munk.h composited sublayer by
    // sublayer from the bottom up in float (hence 1e-6) and against the double top-down fold
    // of layer_optics.h (1e-12).
    const Stack s = random_stack(40, 5, 2e5);
    const double ground = 0.6;
    std::vector<double> down(41), up(41);
    solve_two_flux(s.rho, s.tau, {1.0, 0.0, ground}, down, up);
    using patina::shading::KmLayers;
    KmLayers<float> below{static_cast<float>(ground), static_cast<float>(ground), 0.0f};
    for (size_t i = s.rho.size(); i-- > 0;) {
        const float r = static_cast<float>(s.rho[i]), t = static_cast<float>(s.tau[i]);
        below = patina::shading::km_composite<float>({r, r, t}, below);
    }
    EXPECT_NEAR(up[0], below.r_top, 1e-6);
    const LayerOpticsValue v = fold_sublayers(s.rho, s.tau);
    EXPECT_NEAR(up[0], reflectance_over(v, ground), 1e-12);
}

TEST(TwoFlux, TransmittanceIsReciprocalAndBottomReflectanceMatches)
{
    const Stack s = random_stack(30, 9, 3e5);
    const LayerOpticsValue v = fold_sublayers(s.rho, s.tau);
    std::vector<double> down(31), up(31);
    // Lit from the top over a black ground: E^d_N = T.
    solve_two_flux(s.rho, s.tau, {1.0, 0.0, 0.0}, down, up);
    EXPECT_NEAR(down[30], v.t, 1e-12);
    EXPECT_NEAR(up[0], v.r_top, 1e-12);
    // Lit from below with nothing above: E^u_0 = T (reciprocity), E^d_N = R_bottom.
    solve_two_flux(s.rho, s.tau, {0.0, 1.0, 0.0}, down, up);
    EXPECT_NEAR(up[0], v.t, 1e-12);
    EXPECT_NEAR(down[30], v.r_bottom, 1e-12);
    // A depth-varying layer reflects differently from its two sides.
    EXPECT_GT(std::abs(v.r_top - v.r_bottom), 1e-4);
}

TEST(TwoFlux, FluenceRateAveragesTheBoundaries)
{
    const std::vector<double> down{1.0, 0.5, 0.25}, up{0.3, 0.2, 0.1};
    std::vector<double> f(2);
    sublayer_fluence_rate(down, up, f);
    EXPECT_DOUBLE_EQ(f[0], 0.5 * (1.3 + 0.7));
    EXPECT_DOUBLE_EQ(f[1], 0.5 * (0.7 + 0.35));
}
