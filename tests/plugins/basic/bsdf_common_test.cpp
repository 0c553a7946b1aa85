// Properties every BSDF of the basic plugin must have (abi.h §3), checked on a table of
// configurations: sample() returns the f and pdf that eval() and pdf() give at the sampled
// direction; nothing returns NaN or Inf, even for degenerate directions; eval is reentrant.
#include "basic_plugin.h"

#include <thread>

namespace patina::test {
namespace {

    struct Config {
        const char* label;
        const char* shader;
        std::vector<std::pair<const char*, float>> floats;
        PatinaTransportMode mode = PATINA_TRANSPORT_RADIANCE;
    };

    const std::vector<Config>& configs()
    {
        static const std::vector<Config> c = {
            {"lambert", "lambert", {}},
            {"conductor_smooth", "conductor", {{"roughness", 0.0f}}},
            {"conductor_r005", "conductor", {{"roughness", 0.05f}}},
            {"conductor_r03", "conductor", {{"roughness", 0.3f}}},
            {"conductor_r1", "conductor", {{"roughness", 1.0f}}},
            {"conductor_aniso", "conductor", {{"roughness", 0.4f}, {"anisotropy", 1.0f}}},
            {"conductor_r0001", "conductor", {{"roughness", 0.001f}}},
            {"dielectric_smooth", "dielectric", {{"roughness", 0.0f}}},
            {"dielectric_smooth_importance",
             "dielectric",
             {{"roughness", 0.0f}},
             PATINA_TRANSPORT_IMPORTANCE},
            {"dielectric_eta1", "dielectric", {{"eta", 1.0f}, {"roughness", 0.5f}}},
            {"dielectric_r005", "dielectric", {{"roughness", 0.05f}}},
            {"dielectric_r03", "dielectric", {{"roughness", 0.3f}}},
            {"dielectric_r03_importance",
             "dielectric",
             {{"roughness", 0.3f}},
             PATINA_TRANSPORT_IMPORTANCE},
            {"dielectric_eta4_r1", "dielectric", {{"eta", 4.0f}, {"roughness", 1.0f}}},
            {"dielectric_eta1001_r02", "dielectric", {{"eta", 1.001f}, {"roughness", 0.2f}}},
            {"dielectric_r0001", "dielectric", {{"roughness", 0.001f}}},
        };
        return c;
    }

    class BsdfProperties : public ::testing::TestWithParam<int> {
    protected:
        const Config& config() const { return configs()[GetParam()]; }
        Bsdf make() const
        {
            ParamSet params(shader(config().shader));
            for (const auto& [name, value] : config().floats)
                params.set_float(name, value);
            return Bsdf(config().shader, params, config().mode);
        }
    };

    /// A direction uniform on the sphere.
    Vec3 random_direction(Pcg32& rng)
    {
        const float z = 1.0f - 2.0f * rng.next_float();
        const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
        const float phi = 2.0f * shading::kPi * rng.next_float();
        return {r * std::cos(phi), r * std::sin(phi), z};
    }

    bool all_finite_nonnegative(const float* v, int n)
    {
        for (int i = 0; i < n; ++i)
            if (!std::isfinite(v[i]) || v[i] < 0.0f)
                return false;
        return true;
    }

    TEST_P(BsdfProperties, SampleReturnsEvalAndPdfAtTheSampledDirection)
    {
        const Bsdf bsdf = make();
        ASSERT_TRUE(bsdf);
        const int n = bsdf.wl().count;
        Pcg32 rng(99);
        int checked = 0;
        for (int k = 0; k < 20000; ++k) {
            const Vec3 wo = random_direction(rng);
            PatinaBsdfSample s;
            const float u_lobe = rng.next_float();
            if (!bsdf.sample(wo, u_lobe, rng.next_vec2(), &s))
                continue;
            ASSERT_NEAR(shading::length(s.wi), 1.0f, 1e-4f);
            const auto f = bsdf.f(wo, s.wi);
            const float pdf = bsdf.pdf(wo, s.wi);
            if (s.lobe & PATINA_LOBE_SPECULAR) {
                // Delta lobes are never returned by eval and pdf
                for (int i = 0; i < n; ++i)
                    EXPECT_EQ(f[i], 0.0f);
                EXPECT_EQ(pdf, 0.0f);
                EXPECT_GT(s.pdf, 0.0f);
                EXPECT_LE(s.pdf, 1.0f);
                continue;
            }
            ++checked;
            ASSERT_GT(s.pdf, 0.0f);
            ASSERT_NEAR(s.pdf, pdf, 1e-5f * pdf) << "wo " << wo.x << " " << wo.y << " " << wo.z;
            for (int i = 0; i < n; ++i)
                ASSERT_NEAR(s.f[i], f[i], 1e-5f * f[i]) << "wavelength " << i;
            // Lobe flags say which side wi went to
            const bool transmitted = wo.z * s.wi.z < 0.0f;
            EXPECT_EQ((s.lobe & PATINA_LOBE_TRANSMISSION) != 0, transmitted);
            EXPECT_EQ((s.lobe & PATINA_LOBE_REFLECTION) != 0, !transmitted);
            if (!transmitted) {
                EXPECT_EQ(s.eta, 1.0f);
            }
        }
        RecordProperty("checked_samples", checked);
    }

    TEST_P(BsdfProperties, NeverReturnsNanOrInf)
    {
        const Bsdf bsdf = make();
        ASSERT_TRUE(bsdf);
        const int n = bsdf.wl().count;
        // Degenerate and grazing directions, then random ones
        std::vector<Vec3> dirs = {{0, 0, 1},
                                  {0, 0, -1},
                                  {1, 0, 0},
                                  {0, 1, 0},
                                  {-1, 0, 0},
                                  {0.6f, 0.8f, 0.0f},
                                  {0, 1e-8f, 1.0f},
                                  {1.0f, 0, 1e-7f},
                                  {1.0f, 0, -1e-7f},
                                  {0.70710678f, 0, 0.70710678f},
                                  {-0.70710678f, 0, 0.70710678f},
                                  {0.70710678f, 0, -0.70710678f}};
        Pcg32 rng(5);
        for (int k = 0; k < 200; ++k)
            dirs.push_back(random_direction(rng));
        for (const Vec3& wo : dirs) {
            for (const Vec3& wi : dirs) {
                const auto f = bsdf.f(wo, wi);
                ASSERT_TRUE(all_finite_nonnegative(f.data(), n))
                    << wo.x << " " << wo.y << " " << wo.z;
                const float p = bsdf.pdf(wo, wi);
                ASSERT_TRUE(std::isfinite(p) && p >= 0.0f);
            }
            const auto a = bsdf.albedo(wo);
            ASSERT_TRUE(all_finite_nonnegative(a.data(), n));
            for (const Vec2 u : {Vec2(0, 0), Vec2(0.5f, 0.5f), Vec2(0.99999994f, 0.99999994f),
                                 Vec2(0, 0.99999994f), rng.next_vec2()}) {
                for (float u_lobe : {0.0f, 0.5f, 0.99999994f}) {
                    PatinaBsdfSample s;
                    if (!bsdf.sample(wo, u_lobe, u, &s))
                        continue;
                    ASSERT_TRUE(shading::is_finite(Vec3(s.wi)));
                    ASSERT_TRUE(all_finite_nonnegative(s.f, n));
                    ASSERT_TRUE(std::isfinite(s.pdf) && s.pdf > 0.0f);
                    ASSERT_TRUE(std::isfinite(s.eta) && s.eta > 0.0f);
                }
            }
        }
    }

    TEST_P(BsdfProperties, EvalIsReentrantAcrossThreads)
    {
        const Bsdf bsdf = make();
        ASSERT_TRUE(bsdf);
        Pcg32 rng(11);
        std::vector<std::pair<Vec3, Vec3>> pairs;
        for (int k = 0; k < 2000; ++k)
            pairs.emplace_back(random_direction(rng), random_direction(rng));
        std::vector<float> serial;
        for (const auto& [wo, wi] : pairs)
            serial.push_back(bsdf.f0(wo, wi) + bsdf.pdf(wo, wi));
        std::vector<float> a(pairs.size()), b(pairs.size());
        auto work = [&](std::vector<float>* out) {
            for (size_t k = 0; k < pairs.size(); ++k)
                (*out)[k] = bsdf.f0(pairs[k].first, pairs[k].second) +
                            bsdf.pdf(pairs[k].first, pairs[k].second);
        };
        std::thread t1(work, &a), t2(work, &b);
        t1.join();
        t2.join();
        EXPECT_EQ(a, serial);
        EXPECT_EQ(b, serial);
    }

    INSTANTIATE_TEST_SUITE_P(Basic, BsdfProperties,
                             ::testing::Range(0, static_cast<int>(configs().size())),
                             [](const ::testing::TestParamInfo<int>& info) {
                                 return configs()[info.param].label;
                             });

} // namespace
} // namespace patina::test
