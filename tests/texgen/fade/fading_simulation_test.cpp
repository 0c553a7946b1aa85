// The layered fading model of Kimmel et al. 2013 (§3, §4.2): no fading reproduces the KM
// layer, only absorbers fade (§3.1.1), the behaviours of figure 14, breakdown products
// (Eq. 15), the λ cut-off of β (§3.1.2), illumination from both sides.
#include "texgen/fade/fading_simulation.h"
#include "texgen/fade/km_inversion.h"

#include "fade_test_util.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace patina::texgen::fade;
using patina::texgen::fade::test::flat_colorant;
using patina::texgen::fade::test::material_of;

namespace {

WavelengthGrid one_wavelength() { return WavelengthGrid{{500.0}}; }

Illumination top_light(const WavelengthGrid& g, double e) { return {std::vector<double>(g.size(), e), {}}; }

// Depth (m) where colorant j's fraction first drops below half its initial value... i.e. the
// fading front, interpolated between sublayer centres; 0 if even the top is above half.
double front_depth(const FadeSimulation& sim, size_t j, double f0, double thickness)
{
    const int n = sim.sublayers();
    const double dz = thickness / n;
    double prev = sim.fraction(0, j) / f0;
    if (prev >= 0.5)
        return 0.0;
    for (int i = 1; i < n; ++i) {
        const double cur = sim.fraction(i, j) / f0;
        if (cur >= 0.5) {
            const double t = (0.5 - prev) / (cur - prev);
            return (i - 1 + 0.5 + t) * dz;
        }
        prev = cur;
    }
    return thickness;
}

}  // namespace

TEST(FadingSimulation, UnexposedReflectanceIsTheKmLayerForAnyN)
{
    // A homogeneous layer split into N sublayers composites exactly back to the closed
    // form of Eq. (37) (Kubelka's layer over the ground): equal for every N, not only as
    // N grows, since each sublayer uses the exact Eqs. (22), (23).
    const FadeMaterial m = material_of({flat_colorant("c", 4e4, 6e4, 1e-9)}, {0.5}, 60e-6, 0.7);
    for (int n : {1, 3, 10, 100, 1000}) {
        FadeSimulation sim(m, one_wavelength(), n);
        const double closed = km_layer_reflectance(2e4, 3e4, 60e-6, 0.7);
        EXPECT_NEAR(sim.reflectance()[0], closed, 1e-12) << n;
    }
}

TEST(FadingSimulation, FadedReflectanceConvergesAsSublayersGrow)
{
    // A faded (depth-varying) state: the error of the reflectance after the same dose
    // falls as N grows; measured against N = 800.
    const FadeMaterial m =
        material_of({flat_colorant("c", 8e5, 0.0, 2e-8), flat_colorant("w", 0.0, 1e5, 0.0)},
                    {0.1, 0.5}, 100e-6, 0.8);
    auto reflect = [&](int n) {
        FadeSimulation sim(m, one_wavelength(), n);
        sim.run(top_light(one_wavelength(), 1e-3), 4e4, 40);
        return sim.reflectance()[0];
    };
    const double ref = reflect(800);
    const double e25 = std::abs(reflect(25) - ref);
    const double e50 = std::abs(reflect(50) - ref);
    const double e100 = std::abs(reflect(100) - ref);
    const double e200 = std::abs(reflect(200) - ref);
    EXPECT_GT(e25, 1e-6);  // the state is depth-varying enough to matter
    EXPECT_LT(e50, 0.7 * e25);
    EXPECT_LT(e100, 0.7 * e50);
    EXPECT_LT(e200, 0.7 * e100);
    EXPECT_LT(e100, 2e-3);
}

TEST(FadingSimulation, NonAbsorbingColorantDoesNotFade)
{
    // §3.1.1: fading needs absorption (Grotthus-Draper); a scatterer with β > 0 stays.
    const FadeMaterial m =
        material_of({flat_colorant("dye", 5e5, 0.0, 1e-8), flat_colorant("white", 0.0, 5e4, 1e-6)},
                    {0.05, 0.6}, 50e-6, 0.5);
    FadeSimulation sim(m, WavelengthGrid::uniform(400, 700, 10), 20);
    sim.run(top_light(sim.grid(), 1.0), 1e3, 10);
    for (int i = 0; i < 20; ++i) {
        EXPECT_EQ(sim.fraction(i, 1), 0.6);
        EXPECT_LT(sim.fraction(i, 0), 0.05);
    }
}

TEST(FadingSimulation, Figure14NonScatteringFrontMovesAtConstantSpeed)
{
    // Figure 14, top row: with no scattering the bleached top is clear, all light reaches
    // the front and is absorbed there, so the front moves at v = β E_0 / f_0 (each J/m^2
    // absorbed consumes β m^3/m^2 of colorant, f_0 m^3 per m^3 of layer): constant speed.
    const double a = 2e6, f0 = 0.5, beta = 1e-9, e0 = 1.0, Z = 200e-6;
    const FadeMaterial m = material_of({flat_colorant("c", a, 0.0, beta)}, {f0}, Z, 0.0);
    FadeSimulation sim(m, one_wavelength(), 400);
    const Illumination light = top_light(one_wavelength(), e0);
    const double v = beta * e0 / f0;  // m/s (β at 500 nm = the reference)
    const double t_cross = 20e-6 / v; // time to cross 20 µm
    std::vector<double> fronts;
    // Steps small against the front's passage through a sublayer (the time step holds the
    // fluence fixed, Eq. 35: its error is first order in dt).
    for (int k = 0; k < 6; ++k) {
        sim.run(light, t_cross, 800);
        fronts.push_back(front_depth(sim, 0, f0, Z));
    }
    // After the first interval (the front forming), equal advances of 20 µm.
    for (size_t k = 2; k < fronts.size(); ++k) {
        const double advance = fronts[k] - fronts[k - 1];
        EXPECT_NEAR(advance, 20e-6, 0.4e-6) << "interval " << k;
    }
}

TEST(FadingSimulation, Figure14ScatteringFrontSlows)
{
    // Figure 14, middle row: in a highly scattering medium light diffuses, the fluence at
    // the front decays as the faded layer thickens, and fading slows with time.
    const double a = 2e6, f0 = 0.5, beta = 1e-9, Z = 200e-6;
    const FadeMaterial m = material_of(
        {flat_colorant("c", a, 0.0, beta), flat_colorant("white", 0.0, 4e5, 0.0)}, {f0, 0.5},
        Z, 0.0);
    FadeSimulation sim(m, one_wavelength(), 400);
    const Illumination light = top_light(one_wavelength(), 1.0);
    const double t = 20e-6 / (beta / f0);
    std::vector<double> fronts;
    for (int k = 0; k < 6; ++k) {
        sim.run(light, t, 50);
        fronts.push_back(front_depth(sim, 0, f0, Z));
    }
    for (size_t k = 2; k < fronts.size(); ++k)
        EXPECT_LT(fronts[k] - fronts[k - 1], fronts[k - 1] - fronts[k - 2]) << k;
    // Slower than the non-scattering front (20 µm per interval) and slowing: the last
    // advance well below the second.
    EXPECT_LT(fronts.back(), 6 * 20e-6);
    EXPECT_LT(fronts[5] - fronts[4], 0.8 * (fronts[2] - fronts[1]));
}

TEST(FadingSimulation, Figure14MixtureFugitiveColorantGoesFirst)
{
    // Figure 14, bottom row: two colorants absorbing alike, one 10x less lightfast.
    const FadeMaterial m = material_of(
        {flat_colorant("fugitive", 1e6, 0.0, 1e-8), flat_colorant("fast", 1e6, 0.0, 1e-9),
         flat_colorant("white", 0.0, 2e5, 0.0)},
        {0.2, 0.2, 0.5}, 100e-6, 0.8);
    FadeSimulation sim(m, one_wavelength(), 100);
    sim.run(top_light(one_wavelength(), 1.0), 3000.0, 60);
    double fug = 0.0, fast = 0.0;
    for (int i = 0; i < 100; ++i) {
        fug += sim.fraction(i, 0) / 0.2;
        fast += sim.fraction(i, 1) / 0.2;
        EXPECT_LE(sim.fraction(i, 0), sim.fraction(i, 1) + 1e-15) << i;
    }
    // The fugitive lost far more of its colorant over the depth (here 15.6% vs 8.8%).
    EXPECT_GT(100.0 - fug, 1.5 * (100.0 - fast));
    EXPECT_GT(front_depth(sim, 0, 0.2, 100e-6), front_depth(sim, 1, 0.2, 100e-6));
    // First order in f: at the top, where the fluence is the same for both, the fugitive's
    // log-loss is 10x the other's only approximately (the fluence changes over time); both
    // must have faded there.
    EXPECT_LT(sim.fraction(0, 1), 0.2);
}

TEST(FadingSimulation, BreakdownProductConservesVolumeWhenGammaEqualsBeta)
{
    // Eq. (15) with γ = β (lignin -> o-quinone, Tables II and III): the product gains what
    // the parent loses, so parent + product stays at the initial fraction in every sublayer.
    Colorant lignin = flat_colorant("lignin", 4e5, 0.0, 1.67e-9);
    lignin.breakdown = Breakdown{"quinone", {1.67e-9, 500.0, 1e9}};
    const Colorant quinone = flat_colorant("quinone", 2e5, 0.0, 0.0);
    const FadeMaterial m = material_of({lignin, quinone, flat_colorant("fibre", 0.0, 2e4, 0.0)},
                                       {0.235, 0.0, 0.765}, 70e-6, 0.0);
    const WavelengthGrid g = WavelengthGrid::uniform(330, 450, 5);
    FadeSimulation sim(m, g, 30);
    sim.run(top_light(g, 0.05), 3e5, 7);
    for (int i = 0; i < 30; ++i)
        EXPECT_NEAR(sim.fraction(i, 0) + sim.fraction(i, 1), 0.235, 1e-12) << i;
    EXPECT_GT(sim.fraction(0, 1), 0.01);
    EXPECT_GT(sim.fraction(0, 1), sim.fraction(29, 1));
}

TEST(FadingSimulation, NoFadingBeyondTheCutOffWavelength)
{
    // §3.1.2: photons beyond λmax cannot excite the colorant.
    Colorant c = flat_colorant("uv", 1e5, 0.0, 1e-8);
    c.fading = {1e-8, 400.0, 400.0};
    const FadeMaterial m = material_of({c}, {0.5}, 50e-6, 0.0);
    const WavelengthGrid g = WavelengthGrid::uniform(380, 700, 10);
    FadeSimulation sim(m, g, 10);
    Illumination light = top_light(g, 1.0);
    for (size_t w = 0; w < g.size(); ++w)
        light.top[w] = g.nm[w] > 400.0 ? 1.0 : 0.0;
    sim.run(light, 1e6, 5);
    EXPECT_EQ(sim.fraction(0, 0), 0.5);
    light.top.assign(g.size(), 1.0);
    sim.step(light, 10.0);
    EXPECT_LT(sim.fraction(0, 0), 0.5);
    // β ∝ λ: rate(380)/rate(400) = 380/400 (§3.1.2).
    EXPECT_DOUBLE_EQ(c.fading.at(380.0) / c.fading.at(400.0), 380.0 / 400.0);
    EXPECT_EQ(c.fading.at(401.0), 0.0);
}

TEST(FadingSimulation, BothSidesFadeSymmetrically)
{
    const FadeMaterial m = material_of(
        {flat_colorant("c", 5e5, 3e4, 1e-8), flat_colorant("w", 0.0, 3e4, 0.0)}, {0.1, 0.5},
        70e-6, 0.0);
    FadeSimulation sim(m, one_wavelength(), 40);
    Illumination light = top_light(one_wavelength(), 1.0);
    light.bottom = light.top;
    sim.run(light, 500.0, 10);
    for (int i = 0; i < 20; ++i)
        EXPECT_NEAR(sim.fraction(i, 0), sim.fraction(39 - i, 0), 1e-13) << i;
    EXPECT_LT(sim.fraction(0, 0), sim.fraction(20, 0));
}

TEST(FadingSimulation, FirstOrderKineticsAtTheSurfaceOfAThinLayer)
{
    // A layer thin enough that the fluence is E_0 throughout (optical depth 1e-6):
    // f(t) = f_0 exp(-β a E_0 t) exactly, whatever f_0 (first order, not second: the
    // DESIGN note on Eq. 35). Same relative loss for f_0 = 0.5 and 0.05.
    for (double f0 : {0.5, 0.05}) {
        const FadeMaterial m = material_of({flat_colorant("c", 1e3, 0.0, 1e-6)}, {f0}, 1e-9, 0.0);
        FadeSimulation sim(m, one_wavelength(), 1);
        sim.run(top_light(one_wavelength(), 2.0), 300.0, 3);
        // Trapezoid weight of a one-wavelength grid: 1 nm.
        EXPECT_NEAR(sim.fraction(0, 0) / f0, std::exp(-1e-6 * 1e3 * 2.0 * 300.0), 1e-6);
    }
}

TEST(FadingSimulation, StepEqualsTheScalarSolvePerWavelength)
{
    // step() runs the block Thomas sweeps over blocks of wavelengths; one step must equal
    // Eq. (35) with the fluence of the scalar solve_two_flux at each wavelength.
    const FadeMaterial m = material_of(
        {flat_colorant("c", 4e5, 2e4, 3e-9), flat_colorant("w", 0.0, 5e4, 0.0)}, {0.2, 0.5},
        80e-6, 0.6);
    const WavelengthGrid g = WavelengthGrid::uniform(400, 700, 7);  // 43: not whole blocks
    FadeSimulation sim(m, g, 25);
    Illumination light = top_light(g, 0.0);
    for (size_t w = 0; w < g.size(); ++w)
        light.top[w] = 0.5 + 0.01 * static_cast<double>(w);
    std::vector<double> rate(25, 0.0);
    const std::vector<double> weights = g.trapezoid_weights();
    for (size_t w = 0; w < g.size(); ++w) {
        const std::vector<double> f = sim.fluence_rate(light, w);
        for (int i = 0; i < 25; ++i)
            rate[i] += weights[w] * 3e-9 * g.nm[w] / 500.0 * 4e5 * f[i];
    }
    sim.step(light, 40.0);
    for (int i = 0; i < 25; ++i)
        EXPECT_NEAR(sim.fraction(i, 0), 0.2 * std::exp(-rate[i] * 40.0), 1e-14) << i;
}

TEST(FadingSimulation, RejectsBadInput)
{
    const FadeMaterial m = material_of({flat_colorant("c", 1e3, 0.0, 1e-6)}, {0.5}, 1e-6, 0.0);
    EXPECT_THROW(FadeSimulation(m, WavelengthGrid{}, 10), std::runtime_error);
    EXPECT_THROW(FadeSimulation(m, one_wavelength(), 0), std::runtime_error);
    FadeSimulation sim(m, one_wavelength(), 2);
    EXPECT_THROW(sim.step(Illumination{{1.0, 2.0}, {}}, 1.0), std::runtime_error);
}
