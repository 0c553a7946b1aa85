// RGB -> spectrum uplift (core/rgb_spectrum.h): exact greys, round trips over the Rec.709
// gamut in ACEScg and in linear Rec.709, bounds, illuminants, determinism across threads.
#include "core/rgb_spectrum.h"

#include "core/spectrum.h"

#include <OpenColorIO/OpenColorIO.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <thread>
#include <vector>

namespace OCIO = OCIO_NAMESPACE;

namespace patina {
namespace {

    // A CPU processor for one OCIO builtin transform (OCIO 2.1 names them "UTILITY - ...").
    OCIO::ConstCPUProcessorRcPtr builtin(const char* style, bool inverse)
    {
        auto transform = OCIO::BuiltinTransform::Create();
        transform->setStyle(style);
        transform->setDirection(inverse ? OCIO::TRANSFORM_DIR_INVERSE
                                        : OCIO::TRANSFORM_DIR_FORWARD);
        return OCIO::Config::CreateRaw()->getProcessor(transform)->getDefaultCPUProcessor();
    }

    // The matrix of a linear processor, from the images of the unit vectors.
    Matrix3 matrix_of(const OCIO::ConstCPUProcessorRcPtr& p)
    {
        Matrix3 m{};
        for (int j = 0; j < 3; ++j) {
            float v[3] = {0.0f, 0.0f, 0.0f};
            v[j] = 1.0f;
            p->applyRGB(v);
            for (int i = 0; i < 3; ++i)
                m[3 * i + j] = v[i];
        }
        return m;
    }

    Matrix3 mul(const Matrix3& a, const Matrix3& b)
    {
        Matrix3 r{};
        for (int i = 0; i < 3; ++i)
            for (int j = 0; j < 3; ++j)
                for (int k = 0; k < 3; ++k)
                    r[3 * i + j] += a[3 * i + k] * b[3 * k + j];
        return r;
    }

    struct Spaces {
        Matrix3 acescg_to_xyz = matrix_of(builtin("UTILITY - ACES-AP1_to_CIE-XYZ-D65_BFD", false));
        OCIO::ConstCPUProcessorRcPtr rec709_to_acescg =
            builtin("UTILITY - ACES-AP1_to_LINEAR-REC709_BFD", true);
        Matrix3 rec709_to_xyz = mul(acescg_to_xyz, matrix_of(rec709_to_acescg));
    };

    const Spaces& spaces()
    {
        static const Spaces s;
        return s;
    }

    // Every colour of the Rec.709 cube on an (n+1)^3 grid, optionally expressed in ACEScg.
    std::vector<std::array<float, 3>> rec709_grid(int n, bool in_acescg)
    {
        std::vector<std::array<float, 3>> out;
        for (int r = 0; r <= n; ++r)
            for (int g = 0; g <= n; ++g)
                for (int b = 0; b <= n; ++b) {
                    float c[3] = {float(r) / n, float(g) / n, float(b) / n};
                    if (in_acescg)
                        spaces().rec709_to_acescg->applyRGB(c);
                    out.push_back({c[0], c[1], c[2]});
                }
        return out;
    }

    float max_abs_diff(const std::array<float, 3>& a, const std::array<float, 3>& b)
    {
        return std::max({std::abs(a[0] - b[0]), std::abs(a[1] - b[1]), std::abs(a[2] - b[2])});
    }

    TEST(RgbSpectrumTest, Rec709PrimariesLandInsideAcescg)
    {
        // Sanity of the test set-up: OCIO's matrix takes ACEScg white to D65 (Y = 1) and the
        // Rec.709 primaries to non-negative ACEScg (notes/dependencies.md: ACEScg (1,0,0) is
        // lin Rec.709 (1.70505, -0.13026, -0.02400)).
        const Matrix3& m = spaces().acescg_to_xyz;
        EXPECT_NEAR(m[3] + m[4] + m[5], 1.0f, 1e-5);
        float red[3] = {1.0f, 0.0f, 0.0f};
        spaces().rec709_to_acescg->applyRGB(red);
        for (float c : red)
            EXPECT_GE(c, 0.0f);
        EXPECT_NEAR(red[0], 0.61310, 1e-4); // inverse of the 1.70505 row above
    }

    TEST(RgbSpectrumTest, GreyIsExactlyConstant)
    {
        const RgbToSpectrum up(spaces().acescg_to_xyz);
        for (float g : {0.0f, 0.18f, 1.0f / 3.0f, 0.5f, 0.999f, 1.0f}) {
            const PatinaRgbSpectrum s = up.uplift({g, g, g}, false);
            EXPECT_EQ(s.c0, 0.0f);
            EXPECT_EQ(s.c1, 0.0f);
            EXPECT_EQ(s.c2, 0.0f);
            EXPECT_EQ(s.scale, 2.0f * g);
            EXPECT_EQ(s.illuminant, 0);
            for (float l = 360.0f; l <= 830.0f; l += 7.0f) {
                EXPECT_EQ(patina_rgb_spectrum_eval(&s, l), g) << l; // bit-exact
                EXPECT_EQ(RgbToSpectrum::eval(s, l), g) << l;
            }
            // The matrix's white is matched to the tables', so the grey comes back as itself.
            EXPECT_LT(max_abs_diff(up.rgb_of(s), {g, g, g}), 1e-6f);
        }
    }

    void check_round_trip(const Matrix3& rgb_to_xyz, bool in_acescg, const char* what)
    {
        const RgbToSpectrum up(rgb_to_xyz);
        float worst = 0.0f, worst_continuous = 0.0f;
        std::array<float, 3> worst_rgb{};
        double seconds = 0.0;
        const auto grid = rec709_grid(12, in_acescg);
        up.uplift({0.5f, 0.4f, 0.3f}, false); // build the lazy warm-start table outside the timing
        for (const auto& rgb : grid) {
            const auto t0 = std::chrono::steady_clock::now();
            const PatinaRgbSpectrum s = up.uplift(rgb, false);
            seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            ASSERT_EQ(s.illuminant, 0);
            const float err = max_abs_diff(up.rgb_of(s), rgb);
            if (err > worst)
                worst = err, worst_rgb = rgb;
            // A reflectance stays in [0, 1] everywhere (sampled every 1 nm).
            for (float l = 360.0f; l <= 830.0f; l += 1.0f) {
                const float v = patina_rgb_spectrum_eval(&s, l);
                ASSERT_GE(v, 0.0f) << l;
                ASSERT_LE(v, 1.0f) << l;
            }
            // Integrated independently (1 nm trapezoid of core/spectrum.h) the colour still
            // matches: the fit's quadrature does not hide a colour error. 1e-3 allows for the
            // ~3e-4 between OCIO's D65 white and the CIE table's.
            const Xyz xyz =
                spectrum_to_xyz([&](double l) { return patina_rgb_spectrum_eval(&s, float(l)); });
            Matrix3 inv;
            {
                const Matrix3& m = rgb_to_xyz;
                const double det = m[0] * (m[4] * m[8] - m[5] * m[7]) -
                                   m[1] * (m[3] * m[8] - m[5] * m[6]) +
                                   m[2] * (m[3] * m[7] - m[4] * m[6]);
                inv = {float((m[4] * m[8] - m[5] * m[7]) / det),
                       float((m[2] * m[7] - m[1] * m[8]) / det),
                       float((m[1] * m[5] - m[2] * m[4]) / det),
                       float((m[5] * m[6] - m[3] * m[8]) / det),
                       float((m[0] * m[8] - m[2] * m[6]) / det),
                       float((m[2] * m[3] - m[0] * m[5]) / det),
                       float((m[3] * m[7] - m[4] * m[6]) / det),
                       float((m[1] * m[6] - m[0] * m[7]) / det),
                       float((m[0] * m[4] - m[1] * m[3]) / det)};
            }
            std::array<float, 3> continuous{};
            for (int i = 0; i < 3; ++i)
                continuous[i] =
                    float(inv[3 * i] * xyz[0] + inv[3 * i + 1] * xyz[1] + inv[3 * i + 2] * xyz[2]);
            worst_continuous = std::max(worst_continuous, max_abs_diff(continuous, rgb));
        }
        // The brief's bound: max |rgb_of(uplift(rgb)) - rgb| < 1e-3 over the gamut.
        EXPECT_LT(worst, 1e-3f) << what << " at " << worst_rgb[0] << " " << worst_rgb[1] << " "
                                << worst_rgb[2];
        EXPECT_LT(worst_continuous, 1e-3f) << what;
        std::printf("[ %s ] %zu colours: max round-trip error %.2e, vs 1 nm integration %.2e, "
                    "%.2f us per uplift\n",
                    what, grid.size(), worst, worst_continuous, 1e6 * seconds / grid.size());
        ::testing::Test::RecordProperty(std::string(what) + "_max_round_trip_error",
                                        std::to_string(worst));
    }

    TEST(RgbSpectrumTest, RoundTripRec709GamutInAcescg)
    {
        check_round_trip(spaces().acescg_to_xyz, true, "ACEScg");
    }

    TEST(RgbSpectrumTest, RoundTripLinearRec709)
    {
        check_round_trip(spaces().rec709_to_xyz, false, "linear Rec.709");
    }

    TEST(RgbSpectrumTest, ReflectanceInputsAreClamped)
    {
        const RgbToSpectrum up(spaces().acescg_to_xyz);
        const PatinaRgbSpectrum a = up.uplift({1.5f, -0.2f, 0.5f}, false);
        const PatinaRgbSpectrum b = up.uplift({1.0f, 0.0f, 0.5f}, false);
        EXPECT_EQ(std::memcmp(&a, &b, sizeof a), 0);
        const PatinaRgbSpectrum n = up.uplift({NAN, 0.2f, 0.2f}, false);
        for (float l = 360.0f; l <= 830.0f; l += 10.0f)
            EXPECT_TRUE(std::isfinite(RgbToSpectrum::eval(n, l)));
    }

    TEST(RgbSpectrumTest, OutOfGamutStaysBoundedAndFinite)
    {
        // ACEScg primaries lie (nearly) on or beyond the spectral locus: no reflectance reaches
        // them, but the best effort is finite, in [0, 1] and of the right hue.
        const RgbToSpectrum up(spaces().acescg_to_xyz);
        for (const std::array<float, 3> rgb :
             {std::array<float, 3>{1, 0, 0}, {0, 1, 0}, {0, 0, 1}}) {
            const PatinaRgbSpectrum s = up.uplift(rgb, false);
            const auto back = up.rgb_of(s);
            for (float l = 360.0f; l <= 830.0f; l += 5.0f) {
                const float v = RgbToSpectrum::eval(s, l);
                ASSERT_TRUE(v >= 0.0f && v <= 1.0f);
            }
            // Coefficients stay moderate, so float evaluation in nm (whose terms cancel) is not
            // noise: in-gamut fits have |terms| of a few thousand, unbounded fits reach 1e11.
            EXPECT_LT(std::abs(s.c0) * 830.0f * 830.0f + std::abs(s.c1) * 830.0f + std::abs(s.c2),
                      1e5f);
            const int hue = int(std::max_element(rgb.begin(), rgb.end()) - rgb.begin());
            EXPECT_EQ(int(std::max_element(back.begin(), back.end()) - back.begin()), hue);
        }
    }

    TEST(RgbSpectrumTest, IlluminantsCarryD65AndRoundTrip)
    {
        const RgbToSpectrum up(spaces().acescg_to_xyz);
        // White (1, 1, 1) is D65 normalised to luminance 1 (abi.h, PatinaRgbSpectrum): the
        // shape of D65 (ratio to 560 nm, CIE 15 table) ...
        const PatinaRgbSpectrum white = up.uplift({1.0f, 1.0f, 1.0f}, true);
        EXPECT_EQ(white.illuminant, 1);
        const float at_560 = RgbToSpectrum::eval(white, 560.0f);
        for (float l : {380.0f, 460.0f, 560.0f, 700.0f})
            EXPECT_NEAR(RgbToSpectrum::eval(white, l) / at_560, d65(l) / 100.0f, 1e-6f);
        // ... scaled so that Y = 1: D65 at 560 nm is then 100 / 98.892 = 1.01121, from
        // ∫ D65 ȳ / ∫ ȳ = 98.892 for the 5 nm CIE tables (sums of the colord-data files).
        EXPECT_NEAR(at_560, 1.0f / 0.98892f, 3e-4f);
        const Xyz w =
            emission_to_xyz([&](double l) { return RgbToSpectrum::eval(white, float(l)); });
        EXPECT_NEAR(w[1], 1.0, 1e-5);
        // And it maps back to the working-space white.
        const auto white_rgb = up.rgb_of(white);
        for (float c : white_rgb)
            EXPECT_NEAR(c, 1.0f, 1e-3f);
        // Unbounded colours: scale = 2 max, colour preserved.
        for (const std::array<float, 3> rgb :
             {std::array<float, 3>{4.0f, 2.0f, 1.0f}, {0.1f, 0.3f, 0.2f}, {20.0f, 20.0f, 25.0f}}) {
            const PatinaRgbSpectrum s = up.uplift(rgb, true);
            EXPECT_EQ(s.scale, 2.0f * std::max({rgb[0], rgb[1], rgb[2]}));
            const auto back = up.rgb_of(s);
            EXPECT_LT(max_abs_diff(back, rgb), 1e-3f * s.scale);
        }
        const PatinaRgbSpectrum black = up.uplift({0.0f, 0.0f, 0.0f}, true);
        EXPECT_EQ(RgbToSpectrum::eval(black, 500.0f), 0.0f);
    }

    TEST(RgbSpectrumTest, DeterministicAcrossThreadsAndCopies)
    {
        const auto grid = rec709_grid(5, true);
        const RgbToSpectrum reference(spaces().acescg_to_xyz);
        std::vector<PatinaRgbSpectrum> expected;
        for (const auto& rgb : grid)
            expected.push_back(reference.uplift(rgb, false));

        // A fresh instance whose lazy table is built by whichever thread gets there first.
        const RgbToSpectrum shared(spaces().acescg_to_xyz);
        std::vector<std::vector<PatinaRgbSpectrum>> results(
            4, std::vector<PatinaRgbSpectrum>(grid.size()));
        std::vector<std::thread> threads;
        for (int t = 0; t < 4; ++t)
            threads.emplace_back([&, t] {
                for (size_t i = 0; i < grid.size(); ++i) {
                    const size_t k = (i + t * 37) % grid.size(); // different orders
                    results[t][k] = shared.uplift(grid[k], false);
                }
            });
        for (auto& th : threads)
            th.join();
        const RgbToSpectrum copy = shared;
        for (size_t k = 0; k < grid.size(); ++k) {
            for (int t = 0; t < 4; ++t)
                EXPECT_EQ(std::memcmp(&results[t][k], &expected[k], sizeof expected[k]), 0);
            const PatinaRgbSpectrum c = copy.uplift(grid[k], false);
            EXPECT_EQ(std::memcmp(&c, &expected[k], sizeof c), 0);
        }
    }

    TEST(RgbSpectrumTest, SingularMatrixThrows)
    {
        EXPECT_THROW(RgbToSpectrum(Matrix3{1, 1, 1, 1, 1, 1, 0, 0, 1}), std::invalid_argument);
    }

} // namespace
} // namespace patina
