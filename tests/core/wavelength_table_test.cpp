// The tabulated hero-wavelength sampler (core/spectrum.h sample_wavelengths_tabulated): its
// pdf is a density, matches the histogram of its samples, follows the analytic density it
// tabulates, and the companions are the hero rotated by i/count.
#include "core/spectrum.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace patina {
namespace {

    TEST(WavelengthTableTest, PdfIntegratesToOne)
    {
        // Midpoint rule on a 0.001 nm grid: the pdf is piecewise constant, so this is exact
        // but for the few cells that straddle a step.
        double mass = 0.0;
        for (int i = 0; i < 470000; ++i)
            mass += tabulated_wavelength_pdf(360.0f + 0.001f * (static_cast<float>(i) + 0.5f)) *
                    0.001;
        EXPECT_NEAR(mass, 1.0, 1e-5);
        EXPECT_EQ(tabulated_wavelength_pdf(359.9f), 0.0f);
        EXPECT_EQ(tabulated_wavelength_pdf(830.1f), 0.0f);
    }

    // Piecewise constant, it stays within 6 % of the smooth density it tabulates (the
    // widest steps, 3-4 nm in the sparse ends of the range, see the density change most),
    // and in the middle of the range within 0.6 %.
    TEST(WavelengthTableTest, FollowsTheAnalyticDensity)
    {
        for (float l = 360.0f; l <= 830.0f; l += 0.37f) {
            const float analytic = visible_wavelength_pdf(l);
            const float tolerance = (l > 450.0f && l < 650.0f ? 6e-3f : 6e-2f) * analytic;
            EXPECT_NEAR(tabulated_wavelength_pdf(l), analytic, tolerance) << l;
        }
    }

    TEST(WavelengthTableTest, ReturnedPdfIsTheDensityAtTheSample)
    {
        for (float u : {0.0f, 0.13f, 0.5f, 0.77f, 0.999f, 0x1.fffffep-1f})
            for (int n : {1, 3, 4, 5, 8}) {
                SampledSpectrum pdf;
                const PatinaWavelengths wl = sample_wavelengths_tabulated(u, n, pdf);
                ASSERT_EQ(wl.count, n);
                ASSERT_EQ(pdf.count, n);
                for (int i = 0; i < n; ++i) {
                    ASSERT_GE(wl.lambda_nm[i], kLambdaMinNm);
                    ASSERT_LE(wl.lambda_nm[i], kLambdaMaxNm);
                    // Inside a step the density is the step's; at a node either side's.
                    const float l = wl.lambda_nm[i];
                    const float here = tabulated_wavelength_pdf(l);
                    const float below = tabulated_wavelength_pdf(std::nextafter(l, 0.0f));
                    EXPECT_TRUE(pdf[i] == here || pdf[i] == below) << u << " " << n << " " << i;
                    // The companions: the analytic inverse CDF at frac(u + i/n), to within a
                    // tenth of a step (λ is linear in u within a step, the CDF is not).
                    float ui = u + static_cast<float>(i) / static_cast<float>(n);
                    ui = ui >= 1.0f ? ui - 1.0f : ui;
                    EXPECT_NEAR(l, sample_visible_wavelength(ui), 0.5f) << u << " " << i;
                }
                for (int i = n; i < SampledSpectrum::kLanes; ++i) {
                    EXPECT_EQ(pdf[i], 0.0f);
                    EXPECT_EQ(wl.lambda_nm[i], 0.0f);
                }
            }
    }

    // Chi-square of a histogram of the samples against the returned pdf, and against a wrong
    // pdf (the uniform one), which must fail: the test has power.
    TEST(WavelengthTableTest, SamplesMatchTheirHistogram)
    {
        constexpr int kBins = 47, kSamples = 40000;
        std::vector<double> observed(kBins, 0.0);
        for (int k = 0; k < kSamples; ++k) {
            const double g = k * 0.6180339887498949;
            const float u = static_cast<float>(g - std::floor(g));
            SampledSpectrum pdf;
            const PatinaWavelengths wl = sample_wavelengths_tabulated(u, 4, pdf);
            for (int i = 0; i < 4; ++i) {
                const int b = std::clamp(static_cast<int>((wl.lambda_nm[i] - 360.0f) / 10.0f), 0,
                                         kBins - 1);
                observed[static_cast<size_t>(b)] += 1.0;
            }
        }
        auto chi_square = [&](float (*pdf)(float)) {
            double chi2 = 0.0;
            for (int b = 0; b < kBins; ++b) {
                double p = 0.0;
                for (int s = 0; s < 1000; ++s)
                    p += pdf(360.0f + 10.0f * static_cast<float>(b) + 0.01f * (s + 0.5f)) * 0.01;
                const double expected = p * 4.0 * kSamples;
                const double d = observed[static_cast<size_t>(b)] - expected;
                chi2 += d * d / expected;
            }
            return chi2;
        };
        // 46 degrees of freedom: the 99.9 % quantile is 81.4.
        EXPECT_LT(chi_square(tabulated_wavelength_pdf), 81.4);
        EXPECT_GT(chi_square(uniform_wavelength_pdf), 1000.0);
    }

    // The Monte Carlo estimate of the Y of a constant spectrum 1 through the sampler and its
    // pdf converges to 1, as with the analytic sampler.
    TEST(WavelengthTableTest, FilmEstimateOfAConstantIsOne)
    {
        constexpr int kSamples = 4096;
        double y = 0.0;
        for (int k = 0; k < kSamples; ++k) {
            SampledSpectrum pdf;
            const PatinaWavelengths wl =
                sample_wavelengths_tabulated((static_cast<float>(k) + 0.5f) / kSamples, 4, pdf);
            y += xyz_from_samples(SampledSpectrum(4, 1.0f), cie_at_wavelengths(wl), pdf)[1];
        }
        EXPECT_NEAR(y / kSamples, 1.0, 1e-3);
    }

}  // namespace
}  // namespace patina

namespace patina {
namespace {

    // The one-pass set-up gives what the two calls give, bit for bit, for every count.
    TEST(WavelengthTableTest, OnePassSetUpMatchesTheTwoCalls)
    {
        for (float u : {0.0f, 0.01f, 0.13f, 0.5f, 0.77f, 0.999f, 0x1.fffffep-1f})
            for (int n : {1, 3, 4, 8}) {
                SampledSpectrum pdf_a, pdf_b;
                CieAtWavelengths cie_b;
                const PatinaWavelengths a = sample_wavelengths_tabulated(u, n, pdf_a);
                const CieAtWavelengths cie_a = cie_at_wavelengths(a);
                const PatinaWavelengths b = sample_wavelengths_tabulated(u, n, pdf_b, cie_b);
                ASSERT_EQ(b.count, n);
                ASSERT_EQ(pdf_b.count, n);
                ASSERT_EQ(cie_b.x.count, n);
                ASSERT_EQ(cie_b.d65.count, n);
                for (int i = 0; i < SampledSpectrum::kLanes; ++i) {
                    EXPECT_EQ(a.lambda_nm[i], b.lambda_nm[i]) << u << " " << n << " " << i;
                    EXPECT_EQ(pdf_a[i], pdf_b[i]);
                    EXPECT_EQ(cie_a.x[i], cie_b.x[i]);
                    EXPECT_EQ(cie_a.y[i], cie_b.y[i]);
                    EXPECT_EQ(cie_a.z[i], cie_b.z[i]);
                    EXPECT_EQ(cie_a.d65[i], cie_b.d65[i]);
                }
            }
    }

    // The batched set-up (two samples interleaved, an odd one last) gives each sample what
    // the one-sample call gives, bit for bit; the outputs' other lanes end at 0 whatever
    // they held.
    TEST(WavelengthTableTest, BatchedSetUpMatchesOneSampleAtATime)
    {
        for (size_t n : {size_t{1}, size_t{2}, size_t{7}, size_t{64}}) {
            std::vector<float> u(n);
            for (size_t k = 0; k < n; ++k)
                u[k] = std::fmod(0.6180339f * static_cast<float>(k) + 0.01f, 1.0f);
            u[0] = 0x1.fffffep-1f;
            std::vector<PatinaWavelengths> wl(n);
            std::vector<SampledSpectrum> pdf(n, SampledSpectrum(8, 7.0f));
            std::vector<CieAtWavelengths> cie(n);
            std::vector<SpectralSetUp> out(n);
            for (size_t k = 0; k < n; ++k) {
                std::fill(std::begin(wl[k].lambda_nm), std::end(wl[k].lambda_nm), 9.0f);
                cie[k].x = cie[k].y = cie[k].z = cie[k].d65 = SampledSpectrum(8, 5.0f);
                out[k] = {&wl[k], &pdf[k], &cie[k]};
            }
            sample_wavelengths_tabulated4(u, out);
            for (size_t k = 0; k < n; ++k) {
                SampledSpectrum pdf_1;
                CieAtWavelengths cie_1;
                const PatinaWavelengths wl_1 = sample_wavelengths_tabulated(u[k], 4, pdf_1, cie_1);
                ASSERT_EQ(wl[k].count, 4);
                ASSERT_EQ(pdf[k].count, 4);
                ASSERT_EQ(cie[k].z.count, 4);
                for (int i = 0; i < SampledSpectrum::kLanes; ++i) {
                    EXPECT_EQ(wl[k].lambda_nm[i], wl_1.lambda_nm[i]) << n << " " << k << " " << i;
                    EXPECT_EQ(pdf[k][i], pdf_1[i]);
                    EXPECT_EQ(cie[k].x[i], cie_1.x[i]);
                    EXPECT_EQ(cie[k].y[i], cie_1.y[i]);
                    EXPECT_EQ(cie[k].z[i], cie_1.z[i]);
                    EXPECT_EQ(cie[k].d65[i], cie_1.d65[i]);
                }
            }
        }
    }

}  // namespace
}  // namespace patina
