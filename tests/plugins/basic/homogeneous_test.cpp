// homogeneous: Beer-Lambert transmittance, free-flight sampling (distribution, pass
// probability, unbiasedness of the one-sample spectral MIS weights), the Henyey-Greenstein
// phase function (normalisation, exact inverse cdf, chi-square, direction convention,
// reciprocity), edge cases without NaN/Inf, and bad values refused at create.
#include "basic_plugin.h"
#include <patina/testing/chi2.h>

#include <patina/shading/phase.h>

#include <functional>
#include <memory>

namespace patina::test {
namespace {

    using shading::henyey_greenstein;
    using shading::kPi;
    using Spectrum = Medium::Spectrum;

    /// A spectrally varying medium whose coefficients the test evaluates on its own.
    struct Coefficients {
        std::vector<float> a_lambda, a_value, s_lambda, s_value;
        float density = 1.0f;

        double sigma_a(float lambda) const { return density * eval(a_lambda, a_value, lambda); }
        double sigma_s(float lambda) const { return density * eval(s_lambda, s_value, lambda); }
        double sigma_t(float lambda) const { return sigma_a(lambda) + sigma_s(lambda); }

        void apply(ParamSet& params) const
        {
            params.set_spectrum("sigma_a", a_lambda, a_value);
            params.set_spectrum("sigma_s", s_lambda, s_value);
            params.set_float("density", density);
        }

        static double eval(const std::vector<float>& l, const std::vector<float>& v, float lambda)
        {
            const PatinaTabulatedSpectrum s{static_cast<int>(v.size()), l.data(), v.data()};
            return patina_tabulated_eval(&s, lambda);
        }
    };

    /// σa rising from 0.2 to 3 1/m, σs falling from 2 to 0.5 1/m over 360-830 nm, density 1.5.
    Coefficients varying()
    {
        return {{360.0f, 830.0f}, {0.2f, 3.0f}, {360.0f, 830.0f}, {2.0f, 0.5f}, 1.5f};
    }

    /// Both coefficients fall to 0 at 560 nm and stay 0 above: σt = 0 at long wavelengths.
    Coefficients clear_above_560()
    {
        return {{360.0f, 560.0f, 830.0f},
                {1.0f, 0.0f, 0.0f},
                {360.0f, 560.0f, 830.0f},
                {1.5f, 0.0f, 0.0f},
                1.0f};
    }

    /// The wavelengths `lambda` rotated so that lambda[r] is the hero (index 0).
    PatinaWavelengths rotated(const std::vector<float>& lambda, int r)
    {
        const int n = static_cast<int>(lambda.size());
        std::vector<float> l(n);
        for (int k = 0; k < n; ++k)
            l[k] = lambda[(r + k) % n];
        return wavelengths(l);
    }

    /// Means over u (jittered strata) and over the hero (each of the n wavelengths in turn,
    /// as hero-wavelength sampling makes each equally likely) of weight_i · [pass] and of
    /// weight_i · f(t) · [scatter], per wavelength of `lambda` (not per slot).
    struct Means {
        std::vector<double> pass, scatter;
        bool finite = true;
        double max_weight = 0.0;
    };
    Means spectral_means(Medium& medium, const std::vector<float>& lambda, float t_max, int strata,
                         const std::function<double(double)>& f)
    {
        const int n = static_cast<int>(lambda.size());
        Means m{std::vector<double>(n, 0.0), std::vector<double>(n, 0.0)};
        Pcg32 rng(11);
        for (int r = 0; r < n; ++r) {
            medium.set_wavelengths(rotated(lambda, r));
            for (int k = 0; k < strata; ++k) {
                const float u = std::min((k + rng.next_float()) / strata, 0x1.fffffep-1f);
                const Medium::Distance d = medium.sample_distance(t_max, u);
                for (int j = 0; j < n; ++j) {
                    const float w = d.weight[j];
                    m.finite = m.finite && std::isfinite(w) && w >= 0.0f;
                    m.max_weight = std::max(m.max_weight, static_cast<double>(w));
                    if (d.scattered)
                        m.scatter[(r + j) % n] += w * f(d.t);
                    else
                        m.pass[(r + j) % n] += w;
                }
            }
        }
        for (int i = 0; i < n; ++i) {
            m.pass[i] /= static_cast<double>(n) * strata;
            m.scatter[i] /= static_cast<double>(n) * strata;
        }
        return m;
    }

    /// ∫_0^T e^{−σt t} σs (1 + 2t) dt in closed form (T may be infinite).
    double scatter_integral(double sigma_t, double sigma_s, double T)
    {
        if (sigma_s == 0.0)
            return 0.0;
        if (sigma_t == 0.0)
            return sigma_s * (T + T * T);
        const double e = std::isinf(T) ? 0.0 : std::exp(-sigma_t * T);
        const double tail = std::isinf(T) ? 0.0 : e * sigma_t * T;
        // ∫ e^{−at} dt = (1 − e^{−aT})/a; ∫ t e^{−at} dt = (1 − e^{−aT}(1 + aT))/a²
        return sigma_s * ((1.0 - e) / sigma_t + 2.0 * (1.0 - e - tail) / (sigma_t * sigma_t));
    }

    ParamSet& with_g(ParamSet& params, float g)
    {
        params.set_float("g", g);
        return params;
    }

    // -----------------------------------------------------------------------------------
    // Descriptor and transmittance
    // -----------------------------------------------------------------------------------

    TEST(Homogeneous, IsAMediumWithAllFourFunctions)
    {
        const PatinaShaderDesc& s = shader("homogeneous");
        EXPECT_EQ(s.kind, PATINA_SHADER_MEDIUM);
        ASSERT_TRUE(s.medium);
        EXPECT_TRUE(s.medium->sample_distance && s.medium->transmittance && s.medium->phase_eval &&
                    s.medium->phase_sample);
        EXPECT_EQ(s.bsdf, nullptr);
        EXPECT_EQ(s.emitter, nullptr);
        EXPECT_EQ(s.texture, nullptr);
    }

    TEST(Homogeneous, TransmittanceIsBeerLambert)
    {
        const Coefficients c = varying();
        ParamSet params(shader("homogeneous"));
        c.apply(params);
        const Medium medium("homogeneous", params);
        ASSERT_TRUE(medium) << test_host().errors.front();
        for (float t : {0.0f, 0.05f, 0.7f, 3.0f}) {
            const Spectrum tr = medium.transmittance(t);
            const Spectrum tr_other_u = medium.transmittance(t, 0.9f);
            for (int i = 0; i < medium.wl().count; ++i) {
                // Tr = exp(−σt t), σt = density (σa + σs): pbrt-v4 §11.2 Eq. 11.6
                const double expected = std::exp(-c.sigma_t(medium.wl().lambda_nm[i]) * t);
                EXPECT_NEAR(tr[i], expected, 1e-6 * expected + 1e-12)
                    << "t " << t << ", lambda " << medium.wl().lambda_nm[i];
                EXPECT_EQ(tr[i], tr_other_u[i]) << "u must not matter";
            }
        }
        // Infinite distance: nothing gets through; a negative or NaN distance is no distance
        for (int i = 0; i < medium.wl().count; ++i) {
            EXPECT_EQ(medium.transmittance(INFINITY)[i], 0.0f);
            EXPECT_EQ(medium.transmittance(-1.0f)[i], 1.0f);
            EXPECT_EQ(medium.transmittance(NAN)[i], 1.0f);
        }
    }

    TEST(Homogeneous, OwnsCopiesOfItsTables)
    {
        // The host's arrays live only during create: scribble over them afterwards
        const PatinaShaderDesc& desc = shader("homogeneous");
        const ParamSet defaults(desc);
        std::vector<PatinaParamValue> values(defaults.data(), defaults.data() + desc.param_count);
        std::vector<float> lambda = {400.0f, 700.0f}, sa = {1.0f, 2.0f}, ss = {0.5f, 0.25f};
        values[0].spectrum = {2, lambda.data(), sa.data()};
        values[1].spectrum = {2, lambda.data(), ss.data()};
        test_host().errors.clear();
        void* instance = desc.create(&test_host(), values.data());
        ASSERT_TRUE(instance);
        std::fill(lambda.begin(), lambda.end(), 0.0f);
        std::fill(sa.begin(), sa.end(), 1e6f);
        std::fill(ss.begin(), ss.end(), 1e6f);
        const PatinaWavelengths wl = wavelengths({400.0f, 550.0f, 700.0f});
        float tr[PATINA_MAX_WAVELENGTHS] = {};
        desc.medium->transmittance(instance, nullptr, {0, 0, 0}, {0, 0, 1}, 1.0f, 0.5f, &wl, tr);
        desc.destroy(instance);
        // σt = σa + σs from the original tables: 1 + 0.5 at 400 nm, 1.5 + 0.375 at 550 nm
        // (halfway), 2 + 0.25 at 700 nm
        EXPECT_NEAR(tr[0], std::exp(-1.5), 1e-6);
        EXPECT_NEAR(tr[1], std::exp(-1.875), 1e-6);
        EXPECT_NEAR(tr[2], std::exp(-2.25), 1e-6);
    }

    // -----------------------------------------------------------------------------------
    // Free-flight sampling
    // -----------------------------------------------------------------------------------

    TEST(Homogeneous, GreyDistancesFollowTheExponentialDensity)
    {
        // σa = 0.5, σs = 1.5: σt = 2 1/m at every wavelength
        ParamSet params(shader("homogeneous"));
        params.set_constant("sigma_a", 0.5f).set_constant("sigma_s", 1.5f);
        const Medium medium("homogeneous", params);
        ASSERT_TRUE(medium);
        constexpr double kSigmaT = 2.0;
        constexpr float kTMax = 1.2f;
        constexpr int kBins = 20, kSamples = 200000;
        std::vector<double> observed(kBins + 1, 0.0); // the last cell counts passes
        Pcg32 rng(5);
        for (int k = 0; k < kSamples; ++k) {
            const Medium::Distance d = medium.sample_distance(kTMax, rng.next_float());
            if (d.scattered) {
                ASSERT_GE(d.t, 0.0f);
                ASSERT_LT(d.t, kTMax);
                observed[std::min(static_cast<int>(d.t / kTMax * kBins), kBins - 1)] += 1.0;
                // Grey: Tr σs / (σt Tr) = σs / σt = 0.75 at every wavelength
                for (int i = 0; i < medium.wl().count; ++i)
                    ASSERT_NEAR(d.weight[i], 0.75f, 1e-6f);
            } else {
                ASSERT_EQ(d.t, kTMax);
                observed[kBins] += 1.0;
                for (int i = 0; i < medium.wl().count; ++i)
                    ASSERT_NEAR(d.weight[i], 1.0f, 1e-6f); // Tr / Tr
            }
        }
        // Expected counts: N ∫ σt e^{−σt t} dt per bin, N e^{−σt T} for passing
        double x2 = 0.0;
        for (int b = 0; b <= kBins; ++b) {
            const double t0 = kTMax * b / kBins, t1 = kTMax * (b + 1) / kBins;
            const double expected =
                b < kBins ? kSamples * (std::exp(-kSigmaT * t0) - std::exp(-kSigmaT * t1))
                          : kSamples * std::exp(-kSigmaT * kTMax);
            x2 += chi2::sqr_diff(observed[b], expected) / expected;
        }
        const double p = chi2::p_value(x2, kBins);
        EXPECT_GT(p, 0.01) << "X2 = " << x2 << " with " << kBins << " dof";
        // Probability of passing = exp(−σt t_max) = 0.0907, within 4 binomial sigmas
        const double pass = observed[kBins] / kSamples, expected_pass = std::exp(-kSigmaT * kTMax);
        EXPECT_NEAR(pass, expected_pass,
                    4.0 * std::sqrt(expected_pass * (1.0 - expected_pass) / kSamples));
    }

    TEST(Homogeneous, SampledDistanceAndWeightsMatchTheirFormulas)
    {
        const Coefficients c = varying();
        ParamSet params(shader("homogeneous"));
        c.apply(params);
        const Medium medium("homogeneous", params);
        ASSERT_TRUE(medium);
        const PatinaWavelengths& wl = medium.wl();
        const int n = wl.count;
        for (float u : {0.0f, 0.25f, 0.5f, 0.9f, 0.999f}) {
            const Medium::Distance d = medium.sample_distance(INFINITY, u);
            ASSERT_TRUE(d.scattered) << "an infinite medium always scatters";
            // u picks the mixture component j = ⌊u n⌋ and u' = u n − j the distance
            // t = −ln(1 − u') / σt(λj): pbrt-v4 §11.2.2
            const double un = static_cast<double>(u) * n;
            const int j = std::min(n - 1, static_cast<int>(un));
            const double t = -std::log1p(-(un - j)) / c.sigma_t(wl.lambda_nm[j]);
            EXPECT_NEAR(d.t, t, 1e-6 * t + 1e-12) << "u " << u;
            double p_mean = 0.0;
            for (int j = 0; j < n; ++j)
                p_mean += c.sigma_t(wl.lambda_nm[j]) * std::exp(-c.sigma_t(wl.lambda_nm[j]) * d.t);
            p_mean /= n;
            for (int i = 0; i < n; ++i) {
                const double tr = std::exp(-c.sigma_t(wl.lambda_nm[i]) * d.t);
                const double expected = tr * c.sigma_s(wl.lambda_nm[i]) / p_mean;
                EXPECT_NEAR(d.weight[i], expected, 1e-5 * expected) << "u " << u << ", i " << i;
            }
        }
        // Pass: Tr_i(t_max) / avg_j Tr_j(t_max)
        const float t_max = 0.1f;
        const Medium::Distance d = medium.sample_distance(t_max, 0.99f);
        ASSERT_FALSE(d.scattered);
        EXPECT_EQ(d.t, t_max);
        double tr_mean = 0.0;
        for (int j = 0; j < n; ++j)
            tr_mean += std::exp(-c.sigma_t(wl.lambda_nm[j]) * t_max);
        tr_mean /= n;
        for (int i = 0; i < n; ++i)
            EXPECT_NEAR(d.weight[i], std::exp(-c.sigma_t(wl.lambda_nm[i]) * t_max) / tr_mean, 1e-5);
    }

    struct MisCase {
        const char* label;
        Coefficients coefficients;
        std::vector<float> lambda;
        float t_max;
    };

    TEST(Homogeneous, SpectralMisWeightsAreUnbiased)
    {
        // E over u and over the hero of weight_i [pass] = Tr_i(t_max), and of
        // weight_i f(t) [scatter] = ∫_0^T Tr_i(t) σs_i f(t) dt, f(t) = 1 + 2t, for every
        // wavelength i: the one-sample MIS over wavelengths (balance heuristic) is unbiased
        // (Veach 1997 §9.2.4; Wilkie et al. 2014 §4)
        const std::vector<MisCase> cases = {
            {"varying, 4 wavelengths", varying(), {400.0f, 520.0f, 640.0f, 760.0f}, 0.8f},
            {"varying, 8 wavelengths",
             varying(),
             {380.0f, 440.0f, 500.0f, 560.0f, 620.0f, 680.0f, 740.0f, 800.0f},
             0.3f},
            {"varying, infinite", varying(), {400.0f, 520.0f, 640.0f, 760.0f}, INFINITY},
            {"sigma_t = 0 above 560 nm", clear_above_560(), {400.0f, 480.0f, 600.0f, 700.0f}, 1.1f},
            {"sigma_t = 0 above 560 nm, infinite",
             clear_above_560(),
             {400.0f, 480.0f, 600.0f, 700.0f},
             INFINITY},
        };
        const auto f = [](double t) { return 1.0 + 2.0 * t; };
        for (const MisCase& mc : cases) {
            SCOPED_TRACE(mc.label);
            ParamSet params(shader("homogeneous"));
            mc.coefficients.apply(params);
            Medium medium("homogeneous", params);
            ASSERT_TRUE(medium);
            const Means m = spectral_means(medium, mc.lambda, mc.t_max, 50000, f);
            EXPECT_TRUE(m.finite);
            EXPECT_LE(m.max_weight, mc.lambda.size() * (1.0 + 1e-5)) << "weights are at most n";
            for (size_t i = 0; i < mc.lambda.size(); ++i) {
                const float lambda = mc.lambda[i];
                const double sigma_t = mc.coefficients.sigma_t(lambda);
                const double pass = std::isinf(mc.t_max) ? (sigma_t > 0.0 ? 0.0 : 1.0)
                                                         : std::exp(-sigma_t * mc.t_max);
                const double scatter =
                    scatter_integral(sigma_t, mc.coefficients.sigma_s(lambda), mc.t_max);
                EXPECT_NEAR(m.pass[i], pass, 0.01 * pass + 1e-9) << "lambda " << lambda;
                EXPECT_NEAR(m.scatter[i], scatter, 0.01 * scatter + 1e-9) << "lambda " << lambda;
            }
        }
    }

    TEST(Homogeneous, SpectralMisWeightsAreUnbiasedWithRandomNumbers)
    {
        // The same property with plain random u (no strata), N = 4 x 500000, to 1%
        const std::vector<float> lambda = {400.0f, 520.0f, 640.0f, 760.0f};
        ParamSet params(shader("homogeneous"));
        varying().apply(params);
        Medium medium("homogeneous", params);
        const int n = static_cast<int>(lambda.size());
        constexpr int kSamples = 500000;
        constexpr float kTMax = 0.8f;
        std::vector<double> pass(n, 0.0);
        Pcg32 rng(23);
        for (int r = 0; r < n; ++r) {
            medium.set_wavelengths(rotated(lambda, r));
            for (int k = 0; k < kSamples; ++k) {
                const Medium::Distance d = medium.sample_distance(kTMax, rng.next_float());
                if (!d.scattered)
                    for (int j = 0; j < n; ++j)
                        pass[(r + j) % n] += d.weight[j];
            }
        }
        for (int i = 0; i < n; ++i) {
            const double expected = std::exp(-varying().sigma_t(lambda[i]) * kTMax);
            EXPECT_NEAR(pass[i] / (static_cast<double>(n) * kSamples), expected, 0.01 * expected)
                << "lambda " << lambda[i];
        }
    }

    TEST(Homogeneous, DegenerateMediaAndRaysGiveFiniteWeights)
    {
        const PatinaShaderDesc& desc = shader("homogeneous");
        // Nothing in the medium: always pass with weight exactly 1
        for (const char* what : {"zero coefficients", "zero density"}) {
            ParamSet params(desc);
            if (std::string(what) == "zero density")
                params.set_float("density", 0.0f);
            else
                params.set_constant("sigma_a", 0.0f).set_constant("sigma_s", 0.0f);
            const Medium medium("homogeneous", params);
            ASSERT_TRUE(medium) << what;
            for (float t_max : {0.0f, 1.0f, INFINITY}) {
                for (float u : {0.0f, 0.5f, 0x1.fffffep-1f}) {
                    const Medium::Distance d = medium.sample_distance(t_max, u);
                    EXPECT_FALSE(d.scattered) << what;
                    EXPECT_EQ(d.t, t_max);
                    for (int i = 0; i < medium.wl().count; ++i)
                        EXPECT_EQ(d.weight[i], 1.0f) << what << ", t_max " << t_max;
                }
            }
        }
        // u in the first mixture component (700 nm, no extinction): the ray passes and the
        // averaged weights stay finite
        {
            ParamSet params(desc);
            clear_above_560().apply(params);
            Medium medium("homogeneous", params);
            medium.set_wavelengths(wavelengths({700.0f, 400.0f, 480.0f, 600.0f}));
            for (float t_max : {0.5f, INFINITY}) {
                const Medium::Distance d = medium.sample_distance(t_max, 0.1f);
                EXPECT_FALSE(d.scattered);
                for (int i = 0; i < 4; ++i)
                    EXPECT_TRUE(std::isfinite(d.weight[i]) && d.weight[i] >= 0.0f);
            }
            // Through an infinite medium only the clear wavelengths arrive: 4 Tr / (Tr sum)
            const Medium::Distance d = medium.sample_distance(INFINITY, 0.1f);
            EXPECT_FLOAT_EQ(d.weight[0], 2.0f);
            EXPECT_EQ(d.weight[1], 0.0f);
            EXPECT_EQ(d.weight[2], 0.0f);
            EXPECT_FLOAT_EQ(d.weight[3], 2.0f);
        }
        // Extreme coefficients, distances and random numbers
        struct Extreme {
            float sigma, density;
        };
        for (const Extreme e : {Extreme{1e6f, 1e6f}, Extreme{1e-30f, 1e-6f},
                                Extreme{1e-30f, 1e-20f}, Extreme{1.0f, 1.0f}}) {
            ParamSet params(desc);
            params.set_spectrum("sigma_a", {360.0f, 830.0f}, {e.sigma, 0.5f * e.sigma});
            params.set_constant("sigma_s", e.sigma).set_float("density", e.density);
            const Medium medium("homogeneous", params);
            ASSERT_TRUE(medium);
            for (float t_max : {-1.0f, 0.0f, 1e-13f, 1.0f, 1e30f, INFINITY, NAN}) {
                for (float u : {0.0f, 1e-7f, 0.5f, 0x1.fffffep-1f, 1.0f, NAN}) {
                    const Medium::Distance d = medium.sample_distance(t_max, u);
                    if (d.scattered) {
                        EXPECT_TRUE(d.t >= 0.0f && d.t < t_max) << d.t;
                    }
                    for (int i = 0; i < medium.wl().count; ++i) {
                        EXPECT_TRUE(std::isfinite(d.weight[i]) && d.weight[i] >= 0.0f &&
                                    d.weight[i] <= medium.wl().count * (1.0f + 1e-5f))
                            << "sigma " << e.sigma << " x " << e.density << ", t_max " << t_max
                            << ", u " << u << ": " << d.weight[i];
                    }
                }
            }
            for (float t : {0.0f, 1e-13f, 1.0f, 1e30f, INFINITY}) {
                const Spectrum tr = medium.transmittance(t);
                for (int i = 0; i < medium.wl().count; ++i)
                    EXPECT_TRUE(tr[i] >= 0.0f && tr[i] <= 1.0f) << tr[i];
            }
        }
    }

    // -----------------------------------------------------------------------------------
    // Henyey-Greenstein phase function
    // -----------------------------------------------------------------------------------

    const float kAsymmetries[] = {-0.8f, 0.0f, 0.3f, 0.9f};

    TEST(Homogeneous, PhaseFunctionIntegratesToOne)
    {
        for (float g : kAsymmetries) {
            ParamSet params(shader("homogeneous"));
            const Medium medium("homogeneous", with_g(params, g));
            ASSERT_TRUE(medium);
            // Midpoint rule over the sphere, pole along +y (wo and −wo, where the lobe
            // peaks, lie in the x-z plane, away from the pole's degenerate cells)
            const Vec3 wo = direction(0.6f, 0.0f);
            const shading::Frame frame = shading::Frame::from_z(Vec3(0.0f, 1.0f, 0.0f));
            constexpr int kTheta = 512, kPhi = 1024;
            const double dtheta = M_PI / kTheta, dphi = 2.0 * M_PI / kPhi;
            double sum = 0.0;
            for (int i = 0; i < kTheta; ++i) {
                const double theta = (i + 0.5) * dtheta;
                for (int j = 0; j < kPhi; ++j) {
                    const double phi = (j + 0.5) * dphi;
                    const Vec3 wi =
                        frame.from_local(Vec3(static_cast<float>(std::sin(theta) * std::cos(phi)),
                                              static_cast<float>(std::sin(theta) * std::sin(phi)),
                                              static_cast<float>(std::cos(theta))));
                    sum += medium.phase0(wo, wi) * std::sin(theta);
                }
            }
            EXPECT_NEAR(sum * dtheta * dphi, 1.0, 2e-3) << "g " << g;
        }
        // The header's function alone, up to |g| = 0.99: 2π ∫_{-1}^{1} p(c) dc = 1
        for (float g : {-0.99f, -0.5f, 0.0f, 1e-4f, 0.5f, 0.95f, 0.99f}) {
            const double integral =
                2.0 * M_PI *
                chi2::adaptive_simpson(
                    [&](double c) { return static_cast<double>(henyey_greenstein(float(c), g)); },
                    -1.0, 1.0, 1e-9, 40);
            EXPECT_NEAR(integral, 1.0, 1e-5) << "g " << g;
        }
    }

    TEST(Homogeneous, PhaseSamplingInvertsTheCdfExactly)
    {
        for (float g : {-0.99f, -0.8f, -1e-4f, 0.0f, 1e-7f, 0.3f, 0.9f, 0.99f}) {
            float previous = -2.0f;
            for (int k = 0; k <= 1000; ++k) {
                const float u = k / 1000.0f;
                const float c = shading::sample_henyey_greenstein_cos_theta(g, u);
                ASSERT_GE(c, previous) << "g " << g << ": the inverse cdf must not decrease";
                previous = c;
                // F(c) = u, up to the float rounding of c (slope of F: 2π p(c))
                const double slack = 2.0 * M_PI * henyey_greenstein(c, g) * 1.2e-7 + 1e-6;
                EXPECT_NEAR(shading::henyey_greenstein_cdf(c, g), u, slack)
                    << "g " << g << ", u " << u;
            }
            EXPECT_EQ(shading::sample_henyey_greenstein_cos_theta(g, 0.0f), -1.0f) << g;
            EXPECT_EQ(shading::sample_henyey_greenstein_cos_theta(g, 1.0f), 1.0f) << g;
        }
    }

    TEST(Homogeneous, PhaseSamplingPassesChiSquare)
    {
        const Vec3 wos[] = {direction(0.7f, 1.1f), direction(2.8f, -0.4f)};
        const int tests = static_cast<int>(std::size(kAsymmetries) * std::size(wos));
        for (float g : kAsymmetries) {
            ParamSet params(shader("homogeneous"));
            const Medium medium("homogeneous", with_g(params, g));
            ASSERT_TRUE(medium);
            for (const Vec3& wo : wos) {
                chi2::Options opt;
                opt.test_count = tests;
                Pcg32 rng(opt.seed);
                const chi2::Result r = chi2::run(
                    opt,
                    [&](Vec3* w) {
                        Spectrum p;
                        return medium.phase_sample(wo, rng.next_vec2(), w, &p) > 0.0f;
                    },
                    [&](Vec3 w) { return medium.phase0(wo, w); });
                EXPECT_TRUE(r.passed) << "g " << g << ": " << r.message;
                EXPECT_NEAR(r.pdf_integral, 1.0, 1e-3) << "g " << g;
                EXPECT_EQ(r.sampled_fraction, 1.0);
            }
        }
    }

    TEST(Homogeneous, PhaseSampleAgreesWithPhaseEval)
    {
        Pcg32 rng(9);
        for (float g : kAsymmetries) {
            ParamSet params(shader("homogeneous"));
            const Medium medium("homogeneous", with_g(params, g));
            for (int k = 0; k < 2000; ++k) {
                const Vec3 wo = direction(kPi * rng.next_float(), 2.0f * kPi * rng.next_float());
                Vec3 wi;
                Spectrum p;
                const float pdf = medium.phase_sample(wo, rng.next_vec2(), &wi, &p);
                ASSERT_GT(pdf, 0.0f);
                ASSERT_NEAR(shading::length(wi), 1.0f, 1e-5f);
                float eval_pdf = 0.0f;
                const Spectrum q = medium.phase(wo, wi, &eval_pdf);
                // HG sampled exactly: pdf == p, and phase_eval returns the same numbers
                EXPECT_EQ(pdf, eval_pdf);
                for (int i = 0; i < medium.wl().count; ++i) {
                    EXPECT_EQ(p[i], pdf);
                    EXPECT_EQ(q[i], pdf);
                }
            }
        }
    }

    TEST(Homogeneous, ForwardScatteringFavoursWiOppositeWo)
    {
        // wo and wi both point away from the scattering point (wo to the previous vertex, wi
        // to the next), cos θ = dot(wo, wi): g > 0 peaks at wi = −wo (light keeps its
        // direction), g < 0 at wi = wo (pbrt-v4 §11.3.1)
        const Vec3 wo = direction(0.9f, 2.0f);
        for (float g : {0.7f, -0.7f}) {
            ParamSet params(shader("homogeneous"));
            const Medium medium("homogeneous", with_g(params, g));
            const double along_minus_wo = medium.phase0(wo, -wo);
            const double along_wo = medium.phase0(wo, wo);
            // p(cos θ = −1) = (1 − g²)/(4π (1 − g)³) = (1 + g)/(4π (1 − g)²), and p(+1) =
            // (1 − g)/(4π (1 + g)²): the HG extremes
            EXPECT_NEAR(along_minus_wo, (1.0 + g) / (4.0 * M_PI * (1.0 - g) * (1.0 - g)), 1e-4);
            EXPECT_NEAR(along_wo, (1.0 - g) / (4.0 * M_PI * (1.0 + g) * (1.0 + g)), 1e-6);
            if (g > 0.0f)
                EXPECT_GT(along_minus_wo, 10.0 * along_wo);
            else
                EXPECT_GT(along_wo, 10.0 * along_minus_wo);
            // The mean cosine of the scattering angle is g: E[dot(wo, wi)] = −g
            Pcg32 rng(13);
            double mean = 0.0;
            constexpr int kSamples = 200000;
            for (int k = 0; k < kSamples; ++k) {
                Vec3 wi;
                Spectrum p;
                medium.phase_sample(wo, rng.next_vec2(), &wi, &p);
                mean += shading::dot(wo, wi);
            }
            EXPECT_NEAR(mean / kSamples, -g, 0.01) << "g " << g;
        }
    }

    TEST(Homogeneous, PhaseFunctionIsReciprocal)
    {
        Pcg32 rng(17);
        for (float g : {-0.8f, 0.3f, 0.9f}) {
            ParamSet params(shader("homogeneous"));
            const Medium medium("homogeneous", with_g(params, g));
            for (int k = 0; k < 1000; ++k) {
                const Vec3 wo = direction(kPi * rng.next_float(), 2.0f * kPi * rng.next_float());
                const Vec3 wi = direction(kPi * rng.next_float(), 2.0f * kPi * rng.next_float());
                EXPECT_EQ(medium.phase(wo, wi), medium.phase(wi, wo));
            }
        }
    }

    TEST(Homogeneous, DegenerateDirectionsGiveZeroNotNaN)
    {
        ParamSet params(shader("homogeneous"));
        const Medium medium("homogeneous", with_g(params, 0.5f));
        float pdf = 1.0f;
        EXPECT_EQ(medium.phase(Vec3(), Vec3(0, 0, 1), &pdf)[0], 0.0f);
        EXPECT_EQ(pdf, 0.0f);
        EXPECT_EQ(medium.phase(Vec3(0, 0, 1), Vec3(NAN, 0, 0), &pdf)[0], 0.0f);
        EXPECT_EQ(pdf, 0.0f);
        Vec3 wi;
        Spectrum p;
        EXPECT_EQ(medium.phase_sample(Vec3(), Vec2(0.3f, 0.4f), &wi, &p), 0.0f);
        EXPECT_EQ(p[0], 0.0f);
        // A direction that is not quite unit is normalised
        EXPECT_NEAR(medium.phase0(Vec3(0, 0, 2), Vec3(0, 0, -3)), henyey_greenstein(-1.0f, 0.5f),
                    1e-6f);
    }

    // -----------------------------------------------------------------------------------
    // Bad values
    // -----------------------------------------------------------------------------------

    TEST(Homogeneous, RejectsWhatItCannotHonour)
    {
        const PatinaShaderDesc& desc = shader("homogeneous");
        auto expect_rejected = [&](ParamSet& params, const char* name, const char* what) {
            Instance instance(desc, params);
            EXPECT_FALSE(instance) << what;
            ASSERT_FALSE(test_host().errors.empty()) << what << ": no error message";
            EXPECT_NE(test_host().errors.front().find(name), std::string::npos)
                << test_host().errors.front();
        };
        struct Case {
            const char* name;
            const char* what;
            std::function<void(ParamSet&)> set;
        };
        const std::vector<Case> cases = {
            {"sigma_a", "negative", [](ParamSet& p) { p.set_constant("sigma_a", -0.1f); }},
            {"sigma_a", "NaN", [](ParamSet& p) { p.set_constant("sigma_a", NAN); }},
            {"sigma_a", "above 1e6", [](ParamSet& p) { p.set_constant("sigma_a", 2e6f); }},
            {"sigma_s", "negative entry",
             [](ParamSet& p) {
                 p.set_spectrum("sigma_s", {400.0f, 700.0f}, {1.0f, -1.0f});
             }},
            {"sigma_s", "infinite", [](ParamSet& p) { p.set_constant("sigma_s", INFINITY); }},
            {"sigma_s", "wavelengths not increasing",
             [](ParamSet& p) {
                 p.set_spectrum("sigma_s", {700.0f, 400.0f}, {1.0f, 1.0f});
             }},
            {"sigma_s", "empty table", [](ParamSet& p) { p.set_spectrum("sigma_s", {}, {}); }},
            {"g", "0.995", [](ParamSet& p) { p.set_float("g", 0.995f); }},
            {"g", "-1", [](ParamSet& p) { p.set_float("g", -1.0f); }},
            {"g", "NaN", [](ParamSet& p) { p.set_float("g", NAN); }},
            {"density", "negative", [](ParamSet& p) { p.set_float("density", -1.0f); }},
            {"density", "above 1e6", [](ParamSet& p) { p.set_float("density", 2e6f); }},
            {"density", "NaN", [](ParamSet& p) { p.set_float("density", NAN); }},
        };
        for (const Case& c : cases) {
            ParamSet params(desc);
            c.set(params);
            expect_rejected(params, c.name, c.what);
        }
        // The limits themselves are accepted
        ParamSet limits(desc);
        limits.set_float("g", -0.99f).set_float("density", 1e6f).set_constant("sigma_a", 1e6f);
        EXPECT_TRUE(Instance(desc, limits));
        ParamSet other(desc);
        other.set_float("g", 0.99f).set_float("density", 0.0f).set_constant("sigma_s", 0.0f);
        EXPECT_TRUE(Instance(desc, other));
    }

} // namespace
} // namespace patina::test
