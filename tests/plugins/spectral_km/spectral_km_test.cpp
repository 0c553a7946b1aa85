// spectral_km: the faded layer's reflectance against the solver, the coat's energy balance,
// reciprocity, sampling against pdf (chi-square) and refused inputs.
#include "plugins/spectral_km/spectral_km_fixture.h"

#include <patina/testing/chi2.h>
#include "texgen/fade/fading_simulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <random>

namespace patina::test {
namespace {

namespace fs = std::filesystem;
using namespace texgen::fade;

constexpr float kDeg = 3.14159265f / 180.0f;

Vec3 dir(float theta_deg, float phi_deg)
{
    const float t = theta_deg * kDeg, p = phi_deg * kDeg;
    return {std::sin(t) * std::cos(p), std::sin(t) * std::sin(p), std::cos(t)};
}

// Grid wavelengths of fading_test_grid() (300-830 nm every 10 nm) inside the render range
const std::vector<float> kGridNm = {400.0f, 450.0f, 500.0f, 530.0f, 560.0f, 600.0f, 650.0f, 700.0f};

size_t grid_index(float nm)
{
    return static_cast<size_t>(std::lround((nm - 300.0f) / 10.0f));
}

TEST(SpectralKm, UnfadedMatchesTheSolverAtTimeZero)
{
    KmParams p;
    p.fade = write_uniform_stack("unfaded", 0.0).string();
    KmBsdf bsdf(p);
    ASSERT_TRUE(bsdf) << bsdf.error;
    // The solver's t = 0 reflectance over the substrate, straight from the material
    FadeSimulation solver(fading_test_material(), fading_test_grid(), 40);
    const std::vector<double> r0 = solver.reflectance();
    const auto a = bsdf.albedo(dir(30.0f, 0.0f));
    const auto f = bsdf.f(dir(30.0f, 0.0f), dir(50.0f, 120.0f));
    for (size_t i = 0; i < kGridNm.size(); ++i) {
        const double expected = r0[grid_index(kGridNm[i])];
        EXPECT_NEAR(a[i], expected, 2e-6) << kGridNm[i] << " nm";
        // Lambertian: f = R / π
        EXPECT_NEAR(f[i], expected / M_PI, 1e-6) << kGridNm[i] << " nm";
    }
    // The pigment absorbs at 530 nm: the layer is darker there than at 700 nm
    EXPECT_LT(a[3], 0.6f * a[7]);
}

TEST(SpectralKm, FadedFollowsTheDoseTable)
{
    const double dose = 2.5e6;
    KmParams p;
    p.fade = write_uniform_stack("faded", dose).string();
    KmBsdf bsdf(p);
    ASSERT_TRUE(bsdf) << bsdf.error;
    const FadeStack stack = read_fade_stack(fs::path(p.fade).parent_path());
    DoseTableOptions o;
    o.max_dose_j_m2 = 1e7;
    o.knee_dose_j_m2 = 1e4;
    o.entries = 24;
    o.sublayers = 40;
    const DoseTable table = DoseTable::build(fading_test_material(), illuminant_by_name("D65"),
                                             fading_test_grid(), o);
    const LayerSpectra expected = table.spectra_at(dose);
    FadeSimulation unfaded(fading_test_material(), fading_test_grid(), 40);
    const std::vector<double> r0 = unfaded.reflectance();
    const auto a = bsdf.albedo(dir(0.0f, 0.0f));
    // The plugin interpolates R_top, T, R_bottom between rows and composites them; the
    // table interpolates the composite: they differ at second order in the row step
    for (size_t i = 0; i < kGridNm.size(); ++i) {
        const size_t w = grid_index(kGridNm[i]);
        EXPECT_NEAR(a[i], expected.reflectance[w], 2e-4) << kGridNm[i] << " nm";
    }
    // Fading lightens the absorption band
    EXPECT_GT(a[3], r0[grid_index(530.0f)] + 0.05);
    // Between grid wavelengths: linear between the neighbours
    bsdf.set_wavelengths({535.0f});
    const float mid = bsdf.albedo(dir(0.0f, 0.0f))[0];
    EXPECT_NEAR(mid, 0.5 * (expected.reflectance[23] + expected.reflectance[24]), 2e-3);
}

TEST(SpectralKm, SubstrateOverride)
{
    // Over a black substrate the layer shows its own R_top
    KmParams p;
    p.fade = write_uniform_stack("substrate", 0.0).string();
    p.substrate = {0.0f};
    KmBsdf black(p);
    ASSERT_TRUE(black) << black.error;
    const FadeStack stack = read_fade_stack(fs::path(p.fade).parent_path());
    const auto a = black.albedo(dir(0.0f, 0.0f));
    for (size_t i = 0; i < kGridNm.size(); ++i)
        EXPECT_NEAR(a[i], stack.r_top[0][grid_index(kGridNm[i])], 1e-6);
    // A tabulated override in [0, 1] is accepted; values outside are refused
    p.substrate_nm = {400.0f, 700.0f};
    p.substrate = {0.2f, 0.9f};
    EXPECT_TRUE(KmBsdf(p));
    p.substrate = {0.2f, 1.5f};
    KmBsdf bad(p);
    EXPECT_FALSE(bad);
    EXPECT_NE(bad.error.find("substrate"), std::string::npos) << bad.error;
}

TEST(SpectralKm, CoatIsReciprocalAndConservesEnergy)
{
    KmParams p;
    p.fade = write_uniform_stack("coat", 0.0).string();
    p.coat = 1.0f;
    p.coat_roughness = 0.3f;
    p.substrate = {1.0f};  // the brightest base the layer allows
    KmBsdf bsdf(p);
    ASSERT_TRUE(bsdf) << bsdf.error;
    for (float t0 : {5.0f, 30.0f, 60.0f, 85.0f})
        for (float t1 : {10.0f, 45.0f, 80.0f}) {
            const Vec3 a = dir(t0, 10.0f), b = dir(t1, 200.0f);
            EXPECT_LT(reciprocity_error(bsdf.calls(), a, b, 1.0), 1e-5);
        }
    // Directional albedo by quadrature: <= 1, and equal to albedo() (w E + R (1 - w E))
    bsdf.set_wavelengths({700.0f});
    for (float theta : {0.0f, 40.0f, 75.0f}) {
        const Vec3 wo = dir(theta, 0.0f);
        double sum = 0.0;
        const int n = 200;
        for (int i = 0; i < n; ++i)
            for (int j = 0; j < 2 * n; ++j) {
                const double ct = (i + 0.5) / n;  // uniform in cos θ over the hemisphere
                const double st = std::sqrt(1.0 - ct * ct), ph = (j + 0.5) * M_PI / n;
                const Vec3 wi(static_cast<float>(st * std::cos(ph)),
                              static_cast<float>(st * std::sin(ph)), static_cast<float>(ct));
                sum += bsdf.f(wo, wi)[0] * ct;
            }
        const double albedo = sum * (1.0 / n) * (M_PI / n);
        const float claimed = bsdf.albedo(wo)[0];
        std::printf("[ km       ] theta %4.0f: albedo %.4f (albedo() %.4f)\n", theta, albedo,
                    claimed);
        EXPECT_LE(albedo, 1.0 + 2e-3);
        EXPECT_NEAR(albedo, claimed, 0.01);
    }
}

TEST(SpectralKm, SamplingMatchesPdf)
{
    KmParams p;
    p.fade = write_uniform_stack("chi2", 1e6).string();
    struct Case {
        float coat, roughness, theta;
    };
    const Case cases[] = {{0.0f, 0.1f, 30.0f}, {0.7f, 0.2f, 20.0f}, {1.0f, 0.5f, 70.0f},
                          {0.5f, 0.05f, 45.0f}};
    for (const Case& c : cases) {
        p.coat = c.coat;
        p.coat_roughness = c.roughness;
        KmBsdf bsdf(p);
        ASSERT_TRUE(bsdf) << bsdf.error;
        const Vec3 wo = dir(c.theta, 30.0f);
        chi2::Options opt;
        opt.test_count = static_cast<int>(std::size(cases));
        opt.sample_count = 100000;
        std::mt19937 rng(99);
        auto uniform = [&rng] { return static_cast<float>(rng() >> 8) * 0x1p-24f; };
        const chi2::Result r = chi2::run(
            opt,
            [&](Vec3* w) {
                PatinaBsdfSample s;
                const float u_lobe = uniform();
                const float u0 = uniform();
                const Vec2 u(u0, uniform());
                if (!bsdf.sample(wo, u_lobe, u, &s))
                    return false;
                *w = s.wi;
                // The sample's f and pdf are eval's and pdf's
                EXPECT_NEAR(s.pdf, bsdf.pdf(wo, s.wi), 1e-4f * s.pdf);
                return true;
            },
            [&](Vec3 w) { return bsdf.pdf(wo, w); });
        std::printf("[ chi2     ] coat %.1f r %.2f theta %.0f: %s\n", c.coat, c.roughness,
                    c.theta, r.message.c_str());
        EXPECT_TRUE(r.passed) << r.message;
        EXPECT_NEAR(r.pdf_integral, r.sampled_fraction, 5e-3);
    }
}

TEST(SpectralKm, BothSidesShowTheFront)
{
    KmParams p;
    p.fade = write_uniform_stack("sides", 0.0).string();
    p.coat = 0.5f;
    KmBsdf bsdf(p);
    ASSERT_TRUE(bsdf) << bsdf.error;
    const Vec3 wo = dir(30.0f, 0.0f), wi = dir(60.0f, 180.0f);
    const Vec3 wo_below(wo.x, wo.y, -wo.z), wi_below(wi.x, wi.y, -wi.z);
    EXPECT_FLOAT_EQ(bsdf.f(wo, wi)[2], bsdf.f(wo_below, wi_below)[2]);
    EXPECT_FLOAT_EQ(bsdf.pdf(wo, wi), bsdf.pdf(wo_below, wi_below));
    // Nothing is transmitted
    EXPECT_EQ(bsdf.f(wo, wi_below)[2], 0.0f);
    EXPECT_EQ(bsdf.pdf(wo, wi_below), 0.0f);
}

TEST(SpectralKm, BadInputsAreRefused)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "spectral_km" / "bad";
    fs::remove_all(dir);
    fs::create_directories(dir);
    KmParams p;
    {
        KmBsdf none(p);  // no fade.toml given
        EXPECT_FALSE(none);
        EXPECT_NE(none.error.find("fade"), std::string::npos) << none.error;
    }
    // A fade.toml that does not parse: its line is named
    p.fade = (dir / "broken.toml").string();
    std::ofstream(p.fade) << "[fade\nformat = 1\n";
    {
        KmBsdf broken(p);
        EXPECT_FALSE(broken);
        EXPECT_NE(broken.error.find("broken.toml:1"), std::string::npos) << broken.error;
    }
    // A table whose size does not match its description
    const fs::path good = write_uniform_stack("bad_table", 0.0);
    std::string text;
    {
        std::ifstream in(good);
        text.assign(std::istreambuf_iterator<char>(in), {});
    }
    // One more wavelength (and substrate value) than the table has columns
    for (const auto& [key, value] : {std::pair<std::string, std::string>{"wavelength_nm = [", " 290.0,"},
                                     {"reflectance = [", " 0.5,"}}) {
        const size_t at = text.find(key);
        ASSERT_NE(at, std::string::npos) << text;
        text.insert(at + key.size(), value);
    }
    std::ofstream(good) << text;
    p.fade = good.string();
    {
        KmBsdf mismatched(p);
        EXPECT_FALSE(mismatched);
        EXPECT_NE(mismatched.error.find("fade_table.exr"), std::string::npos) << mismatched.error;
    }
    // A missing table file
    const fs::path missing = write_uniform_stack("missing_table", 0.0);
    fs::remove(missing.parent_path() / kFadeTableFile);
    p.fade = missing.string();
    KmBsdf gone(p);
    EXPECT_FALSE(gone);
    EXPECT_NE(gone.error.find("fade_table.exr"), std::string::npos) << gone.error;
}

}  // namespace
}  // namespace patina::test
