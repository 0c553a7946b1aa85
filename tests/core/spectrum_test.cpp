// CIE tables, colorimetric integration and wavelength sampling (core/spectrum.h).
#include "core/spectrum.h"

#include <patina/shading/spectral.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

namespace patina {
namespace {

    std::array<double, 2> chromaticity(const Xyz& xyz)
    {
        const double s = xyz[0] + xyz[1] + xyz[2];
        return {xyz[0] / s, xyz[1] / s};
    }

    TEST(SpectrumTest, TableSpotValues)
    {
        // CIE 1931 2° observer: ȳ(555 nm) = 1 (its peak), x̄(600) = 1.0622, z̄(450) = 1.77211.
        EXPECT_FLOAT_EQ(cie_y(555.0f), 1.0f);
        EXPECT_FLOAT_EQ(cie_x(600.0f), 1.0622f);
        EXPECT_FLOAT_EQ(cie_z(450.0f), 1.77211f);
        // D65 is 100 at 560 nm by definition; 117.812 at 460 nm (CIE 15:2004 table of D65).
        EXPECT_FLOAT_EQ(d65(560.0f), 100.0f);
        EXPECT_FLOAT_EQ(d65(460.0f), 117.812f);
        // Linear interpolation between 5 nm samples, zero outside 360-830 nm.
        EXPECT_FLOAT_EQ(cie_y(557.5f), 0.5f * (1.0f + 0.995f));
        EXPECT_EQ(cie_x(359.0f), 0.0f);
        EXPECT_EQ(d65(831.0f), 0.0f);
    }

    TEST(SpectrumTest, CieYIntegralMatchesTable)
    {
        // kCieYIntegral is ∫ ȳ dλ of the embedded table; pbrt-v4's 1 nm value is 106.856895.
        double sum = 0.0;
        for (int i = 0; i <= 4700; ++i) {
            const float l = 360.0f + 0.1f * static_cast<float>(i);
            sum += ((i == 0 || i == 4700) ? 0.5 : 1.0) * cie_y(l) * 0.1;
        }
        EXPECT_NEAR(sum, kCieYIntegral, 1e-3);
        EXPECT_NEAR(kCieYIntegral, 106.856895, 0.01);
    }

    TEST(SpectrumTest, D65WhitePoint)
    {
        // D65 x CIE 1931 2° white point: xy = (0.31271, 0.32902) from the 5 nm tables
        // (CIE 15:2004 gives 0.31272, 0.32903 from the 1 nm tables); checked to 1e-4.
        const Xyz w = spectrum_to_xyz([](double) { return 1.0; }, d65);
        EXPECT_NEAR(w[1], 1.0, 1e-12); // normalised so the illuminant has Y = 1
        const auto xy = chromaticity(w);
        EXPECT_NEAR(xy[0], 0.31271, 1e-4);
        EXPECT_NEAR(xy[1], 0.32901, 1e-4);
    }

    TEST(SpectrumTest, IlluminantA)
    {
        // CIE 15:2004 table of illuminant A: S_A(560) = 100, S_A(400) = 14.708, S_A(700) = 198.261;
        // white point xy = (0.44757, 0.40745) (CIE 15:2004).
        EXPECT_NEAR(illuminant_a(560.0f), 100.0, 1e-4);
        EXPECT_NEAR(illuminant_a(400.0f), 14.708, 1e-3);
        EXPECT_NEAR(illuminant_a(700.0f), 198.261, 1e-3);
        const auto xy = chromaticity(spectrum_to_xyz([](double) { return 1.0; }, illuminant_a));
        EXPECT_NEAR(xy[0], 0.44757, 2e-4);
        EXPECT_NEAR(xy[1], 0.40745, 2e-4);
    }

    TEST(SpectrumTest, EmissionToXyzOfConstantIsOne)
    {
        // Closed form: a constant radiance 1 has Y = ∫ȳ / kCieYIntegral = 1.
        const Xyz xyz = emission_to_xyz([](double) { return 1.0; });
        EXPECT_NEAR(xyz[1], 1.0, 1e-6);
        // Equal-energy white E is at xy = (1/3, 1/3) (the three functions have equal areas) to
        // table precision.
        EXPECT_NEAR(chromaticity(xyz)[0], 1.0 / 3.0, 2e-4);
        EXPECT_NEAR(chromaticity(xyz)[1], 1.0 / 3.0, 2e-4);
    }

    // Optional cross-check: the embedded numbers equal the CGATS files of Debian's colord-data.
    std::vector<std::vector<double>> read_cgats(const std::filesystem::path& path)
    {
        std::ifstream in(path);
        std::vector<std::vector<double>> sets;
        std::string line;
        bool data = false;
        while (std::getline(in, line)) {
            if (line.rfind("BEGIN_DATA", 0) == 0 && line.find("FORMAT") == std::string::npos) {
                data = true;
            } else if (line.rfind("END_DATA", 0) == 0 && line.find("FORMAT") == std::string::npos) {
                data = false;
            } else if (data) {
                std::istringstream ss(line);
                std::vector<double> v;
                for (double x; ss >> x;)
                    v.push_back(x);
                sets.push_back(v);
            }
        }
        return sets;
    }

    TEST(SpectrumTest, MatchesColordData)
    {
        const std::filesystem::path cmf = "/usr/share/colord/cmf/CIE1931-2deg-XYZ.cmf";
        const std::filesystem::path sp = "/usr/share/colord/illuminant/CIE-D65.sp";
        if (!std::filesystem::exists(cmf) || !std::filesystem::exists(sp))
            GTEST_SKIP() << "colord-data not installed";
        const auto sets = read_cgats(cmf);
        ASSERT_EQ(sets.size(), 3u);
        for (int i = 0; i < kCieSamples; ++i) {
            const float l = 360.0f + 5.0f * static_cast<float>(i);
            EXPECT_FLOAT_EQ(cie_x(l), static_cast<float>(sets[0][i])) << l;
            EXPECT_FLOAT_EQ(cie_y(l), static_cast<float>(sets[1][i])) << l;
            EXPECT_FLOAT_EQ(cie_z(l), static_cast<float>(sets[2][i])) << l;
        }
        const auto d = read_cgats(sp); // 300-830 nm every 5 nm, divided by 100
        ASSERT_EQ(d.size(), 1u);
        ASSERT_EQ(d[0].size(), 107u);
        for (int i = 0; i < kCieSamples; ++i) {
            const float l = 360.0f + 5.0f * static_cast<float>(i);
            EXPECT_NEAR(d65(l), 100.0 * d[0][i + 12], 1e-4) << l;
        }
        // Illuminant A, 300-830 nm every 1 nm, divided by 100.
        const std::filesystem::path a_file = "/usr/share/colord/illuminant/CIE-A.sp";
        if (!std::filesystem::exists(a_file))
            return;
        const auto a = read_cgats(a_file);
        ASSERT_EQ(a.size(), 1u);
        ASSERT_EQ(a[0].size(), 531u);
        for (int l = 360; l <= 830; l += 10)
            EXPECT_NEAR(illuminant_a(float(l)), 100.0 * a[0][l - 300],
                        1e-4 * illuminant_a(float(l)))
                << l;
    }

    TEST(SpectrumTest, MatchesCvrlOneNanometreTable)
    {
        // The CVRL 1 nm CIE 1931 table agrees with ours at every 5 nm, and the integrals of
        // x̄, ȳ, z̄ over 380-780 nm agree to 1e-4 relative (linear interpolation between our
        // samples misses only the curvature, which averages out).
        const std::filesystem::path csv = std::filesystem::path(PATINA_SOURCE_DIR) /
                                          "../shared/data/cie1931_2deg_xyz_380-780_1nm.csv";
        std::ifstream in(csv);
        if (!in)
            GTEST_SKIP() << "no " << csv;
        std::string line;
        std::getline(in, line); // header
        int rows = 0;
        double ref[3] = {}, ours[3] = {};
        while (std::getline(in, line)) {
            float l, x, y, z;
            if (std::sscanf(line.c_str(), "%f,%f,%f,%f", &l, &x, &y, &z) != 4)
                continue;
            ++rows;
            const double err =
                std::max({std::abs(cie_x(l) - x), std::abs(cie_y(l) - y), std::abs(cie_z(l) - z)});
            if (static_cast<int>(l) % 5 == 0) {
                EXPECT_LT(err, 1e-6) << l;
            }
            ref[0] += x, ref[1] += y, ref[2] += z;
            ours[0] += cie_x(l), ours[1] += cie_y(l), ours[2] += cie_z(l);
        }
        EXPECT_EQ(rows, 401);
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(ours[c] / ref[c], 1.0, 1e-4) << c;
    }

    TEST(SpectrumTest, VisiblePdfIntegratesToOne)
    {
        double sum = 0.0;
        for (int i = 0; i < 47000; ++i)
            sum += visible_wavelength_pdf(360.0f + 0.01f * (i + 0.5f)) * 0.01;
        EXPECT_NEAR(sum, 1.0, 1e-5);
        EXPECT_EQ(visible_wavelength_pdf(359.0f), 0.0f);
        EXPECT_EQ(visible_wavelength_pdf(831.0f), 0.0f);
        // Shape: p ∝ 1/cosh²(0.0072 (λ − 538)), so p(538)/p(600) = cosh²(0.0072 · 62).
        const double c = std::cosh(0.0072 * 62.0);
        EXPECT_NEAR(visible_wavelength_pdf(538.0f) / visible_wavelength_pdf(600.0f), c * c, 1e-5);
    }

    TEST(SpectrumTest, VisibleSamplingInvertsTheCdf)
    {
        // Ends map to the ends; the median splits the pdf's mass in two.
        EXPECT_NEAR(sample_visible_wavelength(0.0f), 360.0f, 1e-3);
        EXPECT_NEAR(sample_visible_wavelength(0x1.fffffep-1f), 830.0f, 1e-2);
        const float median = sample_visible_wavelength(0.5f);
        double mass = 0.0;
        for (int i = 0; i < 10000; ++i) {
            const float l = 360.0f + (median - 360.0f) * (i + 0.5f) / 10000.0f;
            mass += visible_wavelength_pdf(l) * (median - 360.0f) / 10000.0;
        }
        EXPECT_NEAR(mass, 0.5, 1e-4);
    }

    // Chi-square test of the samples against the pdf (Mitsuba's test of sampling routines).
    double chi_square(const std::vector<float>& samples, float (*pdf)(float))
    {
        constexpr int kBins = 47;
        std::vector<double> observed(kBins, 0.0), expected(kBins, 0.0);
        for (float l : samples) {
            const int b = std::clamp(static_cast<int>((l - 360.0f) / 10.0f), 0, kBins - 1);
            observed[b] += 1.0;
        }
        for (int b = 0; b < kBins; ++b) {
            double p = 0.0;
            for (int s = 0; s < 100; ++s)
                p += pdf(360.0f + 10.0f * b + 0.1f * (s + 0.5f)) * 0.1;
            expected[b] = p * static_cast<double>(samples.size());
        }
        double chi2 = 0.0;
        for (int b = 0; b < kBins; ++b)
            chi2 += (observed[b] - expected[b]) * (observed[b] - expected[b]) / expected[b];
        return chi2;
    }

    TEST(SpectrumTest, WavelengthSamplesFollowTheirPdf)
    {
        // Stratified u with rotated companions: every lambda_nm[i] is distributed by the pdf.
        // Chi-square with 46 degrees of freedom: the 99.9% quantile is 81.4.
        std::vector<float> vis, uni;
        const int n = 20000;
        for (int k = 0; k < n; ++k) {
            const float u = (k * 0.6180339887f) - std::floor(k * 0.6180339887f);
            const PatinaWavelengths a = sample_wavelengths_visible(u, 4);
            const PatinaWavelengths b = sample_wavelengths_uniform(u, 4);
            ASSERT_EQ(a.count, 4);
            for (int i = 0; i < 4; ++i) {
                ASSERT_GE(a.lambda_nm[i], 360.0f);
                ASSERT_LE(a.lambda_nm[i], 830.0f);
                vis.push_back(a.lambda_nm[i]);
                uni.push_back(b.lambda_nm[i]);
            }
        }
        EXPECT_LT(chi_square(vis, visible_wavelength_pdf), 81.4);
        EXPECT_LT(chi_square(uni, uniform_wavelength_pdf), 81.4);
        // A wrong pdf must fail the same test (the test has power).
        EXPECT_GT(chi_square(uni, visible_wavelength_pdf), 1000.0);
    }

    TEST(SpectrumTest, HeroRotation)
    {
        // lambda_i = sample(frac(u + i/count)): with uniform sampling, evenly spaced by 470/count.
        const PatinaWavelengths wl = sample_wavelengths_uniform(0.1f, 4);
        for (int i = 0; i < 4; ++i)
            EXPECT_NEAR(wl.lambda_nm[i], 360.0f + 470.0f * (0.1f + 0.25f * i), 1e-3);
        const PatinaWavelengths w2 = sample_wavelengths_visible(0.8f, 2);
        EXPECT_FLOAT_EQ(w2.lambda_nm[1], sample_visible_wavelength(0.8f + 0.5f - 1.0f));
    }

    TEST(SpectrumTest, SampledSpectrumArithmetic)
    {
        SampledSpectrum a(4, 2.0f),
            b = SampledSpectrum::from_array(4, std::array<float, 4>{1, 2, 0, 4}.data());
        const SampledSpectrum q = a / b; // division by zero gives 0, never Inf
        EXPECT_EQ(q[0], 2.0f);
        EXPECT_EQ(q[2], 0.0f);
        EXPECT_FLOAT_EQ((a * b).average(), (2 + 4 + 0 + 8) / 4.0f);
        EXPECT_EQ((a + b).max_value(), 6.0f);
        EXPECT_EQ((a - b).min_value(), -2.0f);
        EXPECT_TRUE((a * 0.0f).is_black());
        EXPECT_FALSE(a.is_black());
        EXPECT_FLOAT_EQ(exp(SampledSpectrum(2, -1.0f))[1], std::exp(-1.0f));
    }

    TEST(SpectrumTest, XyzFromSamplesIsUnbiased)
    {
        // Monte Carlo estimate of the XYZ of D65 / 100 (radiance) converges to emission_to_xyz.
        const Xyz ref = emission_to_xyz([](double l) { return d65(float(l)) * 0.01; });
        Xyz sum = {0.0, 0.0, 0.0};
        const int n = 40000;
        for (int k = 0; k < n; ++k) {
            const PatinaWavelengths wl = sample_wavelengths_visible((k + 0.5f) / n, 4);
            const SampledSpectrum L =
                SampledSpectrum::from_function(wl, [](float l) { return d65(l) * 0.01f; });
            const Xyz e = xyz_from_samples(L, wl);
            for (int c = 0; c < 3; ++c)
                sum[c] += e[c] / n;
        }
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(sum[c], ref[c], 2e-3 * ref[1]) << c;
        // Uniform wavelengths with their own pdf give the same answer.
        Xyz usum = {0.0, 0.0, 0.0};
        for (int k = 0; k < n; ++k) {
            const PatinaWavelengths wl = sample_wavelengths_uniform((k + 0.5f) / n, 4);
            const SampledSpectrum L =
                SampledSpectrum::from_function(wl, [](float l) { return d65(l) * 0.01f; });
            const Xyz e =
                xyz_from_samples(L, wl, SampledSpectrum(4, uniform_wavelength_pdf(500.0f)));
            for (int c = 0; c < 3; ++c)
                usum[c] += e[c] / n;
        }
        for (int c = 0; c < 3; ++c)
            EXPECT_NEAR(usum[c], ref[c], 2e-3 * ref[1]) << c;
    }

} // namespace
} // namespace patina

// The pdf returned with the sampled wavelengths is the density visible_wavelength_pdf gives.
TEST(SpectrumTest, SampledWavelengthPdfMatchesTheDensity)
{
    for (float u : {0.0f, 0.13f, 0.5f, 0.77f, 0.999f})
        for (int n : {1, 4, 8}) {
            patina::SampledSpectrum pdf;
            const PatinaWavelengths wl = patina::sample_wavelengths_visible(u, n, pdf);
            const PatinaWavelengths ref = patina::sample_wavelengths_visible(u, n);
            ASSERT_EQ(pdf.count, n);
            for (int i = 0; i < n; ++i) {
                EXPECT_NEAR(wl.lambda_nm[i], ref.lambda_nm[i], 1e-3f);
                const float expected = patina::visible_wavelength_pdf(wl.lambda_nm[i]);
                EXPECT_NEAR(pdf[i], expected, 1e-4f * expected) << wl.lambda_nm[i];
            }
        }
}

// One table position per wavelength gives what the four single look-ups give, and the film's
// XYZ from it equals the per-wavelength path.
TEST(SpectrumTest, CieAtWavelengthsMatchesTheSingleLookups)
{
    for (float u : {0.0f, 0.13f, 0.5f, 0.77f, 0.999f})
        for (int n : {1, 3, 4, 8}) {
            patina::SampledSpectrum pdf;
            const PatinaWavelengths wl = patina::sample_wavelengths_visible(u, n, pdf);
            const patina::CieAtWavelengths cie = patina::cie_at_wavelengths(wl);
            ASSERT_EQ(cie.x.count, n);
            ASSERT_EQ(cie.d65.count, n);
            patina::SampledSpectrum L(n, 0.0f);
            for (int i = 0; i < n; ++i) {
                const float l = wl.lambda_nm[i];
                EXPECT_EQ(cie.x[i], patina::cie_x(l));
                EXPECT_EQ(cie.y[i], patina::cie_y(l));
                EXPECT_EQ(cie.z[i], patina::cie_z(l));
                EXPECT_EQ(cie.d65[i], patina::d65(l));
                L[i] = 0.5f + 0.1f * static_cast<float>(i);
            }
            const patina::Xyz a = patina::xyz_from_samples(L, cie, pdf);
            const patina::Xyz b = patina::xyz_from_samples(L, wl, pdf);
            for (int c = 0; c < 3; ++c)
                EXPECT_NEAR(a[c], b[c], 1e-6 * std::abs(b[c]) + 1e-12) << c;
        }
    // Outside 360-830 nm every table is 0; a terminated wavelength (pdf 0) adds nothing.
    PatinaWavelengths wl{};
    wl.count = 2;
    wl.lambda_nm[0] = 300.0f;
    wl.lambda_nm[1] = 555.0f;
    const patina::CieAtWavelengths cie = patina::cie_at_wavelengths(wl);
    EXPECT_EQ(cie.y[0], 0.0f);
    EXPECT_EQ(cie.d65[0], 0.0f);
    patina::SampledSpectrum pdf(2, 0.0f);
    EXPECT_EQ(patina::xyz_from_samples(patina::SampledSpectrum(2, 1.0f), cie, pdf)[1], 0.0);
}

// Arithmetic runs over every lane; what lies past `count` never shows in a result.
TEST(SpectrumTest, SampledSpectrumIgnoresLanesPastCount)
{
    patina::SampledSpectrum a(3, 2.0f);
    EXPECT_EQ(a[3], 0.0f);
    EXPECT_EQ(a[7], 0.0f);
    a *= std::numeric_limits<float>::infinity();  // 0 * inf in the unused lanes
    EXPECT_EQ(a.count, 3);
    EXPECT_FALSE(a.is_black());
    EXPECT_EQ(a.max_value(), std::numeric_limits<float>::infinity());
    patina::SampledSpectrum z(3, 0.0f);
    z /= patina::SampledSpectrum(3, 0.0f);
    EXPECT_TRUE(z.is_black());
    EXPECT_TRUE((patina::SampledSpectrum(4, 1.0f) / 0.0f).is_black());
}

// The plugin helpers' exact path for greys (shading/spectral.h): eval_rgb of a spectrum with
// c0 = c1 = 0 (of either sign) is patina_rgb_spectrum_eval at each wavelength, bit for bit.
TEST(SpectrumTest, EvalRgbOfAGreyIsExact)
{
    const PatinaWavelengths wl = patina::sample_wavelengths_visible(0.37f, 4);
    for (const PatinaRgbSpectrum& grey :
         {PatinaRgbSpectrum{0.0f, 0.0f, 1.3f, 0.8f, 0}, PatinaRgbSpectrum{-0.0f, 0.0f, 0.0f, 1.0f, 0},
          PatinaRgbSpectrum{0.0f, -0.0f, -4.0f, 0.5f, 0}}) {
        const patina::shading::SpectralArray g = patina::shading::eval_rgb(grey, wl);
        for (int i = 0; i < wl.count; ++i)
            EXPECT_EQ(g[i], patina_rgb_spectrum_eval(&grey, wl.lambda_nm[i]));
        for (int i = wl.count; i < PATINA_MAX_WAVELENGTHS; ++i)
            EXPECT_EQ(g[i], 0.0f);
    }
}
