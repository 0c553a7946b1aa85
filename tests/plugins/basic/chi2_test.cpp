// Chi-square tests: every sampling routine of the basic plugin and of the shading headers
// against its pdf (see patina/testing/chi2.h). All cases share one Šidák-corrected
// significance level of 1% over the whole table, so a correct sampler fails this suite with
// probability 1% (and, the seeds being fixed, deterministically passes or fails).
#include "basic_plugin.h"
#include <patina/testing/chi2.h>

#include <patina/shading/microfacet.h>
#include <patina/shading/sampling.h>

#include <cstdio>
#include <functional>

namespace patina::test {
namespace {

    using namespace patina::shading;

    struct Chi2Case {
        std::string label;
        std::function<chi2::Result(const chi2::Options&)> run;
    };

    constexpr float kDeg = kPi / 180.0f;

    /// A BSDF case: sample wi given wo at (theta, phi) degrees, compare with pdf(wo, ·).
    Chi2Case bsdf_case(std::string label, const char* shader_name,
                       std::vector<std::pair<const char*, float>> floats, float theta_deg,
                       float phi_deg = 30.0f)
    {
        return {std::move(label), [=](const chi2::Options& opt) {
                    ParamSet params(shader(shader_name));
                    for (const auto& [name, value] : floats)
                        params.set_float(name, value);
                    const Bsdf bsdf(shader_name, params);
                    if (!bsdf) {
                        chi2::Result r;
                        r.message = "create failed";
                        return r;
                    }
                    const Vec3 wo = direction(theta_deg * kDeg, phi_deg * kDeg);
                    Pcg32 rng(opt.seed);
                    return chi2::run(
                        opt,
                        [&](Vec3* w) {
                            PatinaBsdfSample s;
                            const float u_lobe = rng.next_float();
                            const Vec2 u = rng.next_vec2();
                            if (!bsdf.sample(wo, u_lobe, u, &s))
                                return false;
                            if (s.lobe & PATINA_LOBE_SPECULAR)
                                return false;
                            *w = s.wi;
                            return true;
                        },
                        [&](Vec3 w) { return bsdf.pdf(wo, w); });
                }};
    }

    /// A microfacet case: sample wm as seen from w, compare with the distribution's pdf.
    template <typename Distribution>
    Chi2Case visible_normal_case(std::string label, Distribution distribution, float theta_deg,
                                 float phi_deg = 30.0f)
    {
        return {std::move(label), [=](const chi2::Options& opt) {
                    const Vec3 w = direction(theta_deg * kDeg, phi_deg * kDeg);
                    Pcg32 rng(opt.seed);
                    return chi2::run(
                        opt,
                        [&](Vec3* wm) {
                            *wm = distribution.sample_wm(w, rng.next_vec2());
                            return true;
                        },
                        [&](Vec3 wm) { return distribution.pdf(w, wm); });
                }};
    }

    /// A plain warp from sampling.h against its pdf.
    Chi2Case warp_case(std::string label, std::function<Vec3(Vec2)> warp,
                       std::function<float(Vec3)> pdf)
    {
        return {std::move(label), [=](const chi2::Options& opt) {
                    Pcg32 rng(opt.seed);
                    return chi2::run(
                        opt,
                        [&](Vec3* w) {
                            *w = warp(rng.next_vec2());
                            return true;
                        },
                        pdf);
                }};
    }

    const std::vector<Chi2Case>& all_cases()
    {
        static const std::vector<Chi2Case> cases = [] {
            std::vector<Chi2Case> c;
            // lambert: cosine-weighted on the side of wo
            for (float theta : {0.0f, 45.0f, 89.0f, 120.0f})
                c.push_back(
                    bsdf_case("lambert_theta" + std::to_string(int(theta)), "lambert", {}, theta));
            // conductor (default copper), several roughnesses, both sides, anisotropic
            for (float theta : {0.0f, 45.0f, 80.0f})
                c.push_back(bsdf_case("conductor_r03_theta" + std::to_string(int(theta)),
                                      "conductor", {{"roughness", 0.3f}}, theta));
            for (float theta : {30.0f, 75.0f, 130.0f})
                c.push_back(bsdf_case("conductor_r06_theta" + std::to_string(int(theta)),
                                      "conductor", {{"roughness", 0.6f}}, theta));
            c.push_back(
                bsdf_case("conductor_r10_theta60", "conductor", {{"roughness", 1.0f}}, 60.0f));
            c.push_back(bsdf_case("conductor_aniso_theta40", "conductor",
                                  {{"roughness", 0.5f}, {"anisotropy", 0.8f}}, 40.0f, 30.0f));
            c.push_back(bsdf_case("conductor_aniso_theta70", "conductor",
                                  {{"roughness", 0.5f}, {"anisotropy", 0.8f}}, 70.0f, 100.0f));
            // dielectric: reflection + refraction, from outside and from inside
            struct D {
                const char* tag;
                float eta, roughness;
                std::vector<float> thetas;
            };
            for (const D& d : {D{"eta15_r03", 1.5f, 0.3f, {0.0f, 40.0f, 75.0f, 120.0f, 140.0f}},
                               D{"eta15_r07", 1.5f, 0.7f, {30.0f, 160.0f}},
                               D{"eta133_r05", 1.33f, 0.5f, {60.0f, 110.0f}},
                               D{"eta25_r04", 2.5f, 0.4f, {50.0f, 150.0f}},
                               D{"eta105_r02", 1.05f, 0.2f, {45.0f, 135.0f}}}) {
                for (float theta : d.thetas)
                    c.push_back(bsdf_case(
                        std::string("dielectric_") + d.tag + "_theta" + std::to_string(int(theta)),
                        "dielectric", {{"eta", d.eta}, {"roughness", d.roughness}}, theta));
            }
            // microfacet.h: visible normals of GGX and Beckmann, Beckmann D cos θ sampling
            c.push_back(
                visible_normal_case("ggx_vndf_iso_theta30", TrowbridgeReitz(0.3f, 0.3f), 30.0f));
            c.push_back(visible_normal_case("ggx_vndf_aniso_theta70", TrowbridgeReitz(0.1f, 0.5f),
                                            70.0f, 45.0f));
            c.push_back(visible_normal_case("ggx_vndf_below_theta170", TrowbridgeReitz(0.8f, 0.8f),
                                            170.0f));
            c.push_back(
                visible_normal_case("beckmann_vndf_iso_theta0", Beckmann(0.3f, 0.3f), 0.0f));
            c.push_back(
                visible_normal_case("beckmann_vndf_iso_theta60", Beckmann(0.3f, 0.3f), 60.0f));
            c.push_back(visible_normal_case("beckmann_vndf_aniso_theta80", Beckmann(0.15f, 0.6f),
                                            80.0f, 120.0f));
            c.push_back(
                visible_normal_case("beckmann_vndf_rough_theta45", Beckmann(1.0f, 1.0f), 45.0f));
            c.push_back(
                visible_normal_case("beckmann_vndf_below_theta120", Beckmann(0.5f, 0.5f), 120.0f));
            for (const auto& [label, b] :
                 {std::pair{"beckmann_dcos_iso", Beckmann(0.4f, 0.4f)},
                  std::pair{"beckmann_dcos_aniso", Beckmann(0.2f, 0.7f)}}) {
                c.push_back(warp_case(
                    label, [b = b](Vec2 u) { return b.sample_wm_distribution(u); },
                    [b = b](Vec3 wm) { return b.pdf_distribution(wm); }));
            }
            // sampling.h warps
            c.push_back(warp_case("uniform_sphere", sample_uniform_sphere,
                                  [](Vec3) { return uniform_sphere_pdf(); }));
            c.push_back(warp_case("uniform_hemisphere", sample_uniform_hemisphere, [](Vec3 w) {
                return w.z > 0.0f ? uniform_hemisphere_pdf() : 0.0f;
            }));
            c.push_back(warp_case("cosine_hemisphere", sample_cosine_hemisphere,
                                  [](Vec3 w) { return cosine_hemisphere_pdf(w.z); }));
            return c;
        }();
        return cases;
    }

    class Chi2 : public ::testing::TestWithParam<int> {};

    TEST_P(Chi2, SamplingMatchesPdf)
    {
        const Chi2Case& c = all_cases()[GetParam()];
        chi2::Options opt;
        opt.test_count = static_cast<int>(all_cases().size());
        opt.seed = 1234u + static_cast<unsigned>(GetParam());
        const chi2::Result r = c.run(opt);
        std::printf("[ chi2     ] %-36s %s\n", c.label.c_str(), r.message.c_str());
        RecordProperty("p_value", std::to_string(r.p_value));
        EXPECT_TRUE(r.passed) << c.label << ": " << r.message;
        // The pdf integrates to the fraction of samples that produced a direction
        EXPECT_NEAR(r.pdf_integral, r.sampled_fraction, 5e-3) << c.label;
        EXPECT_LE(r.pdf_integral, 1.0 + 2e-3) << c.label;
    }

    INSTANTIATE_TEST_SUITE_P(Basic, Chi2, ::testing::Range(0, static_cast<int>(all_cases().size())),
                             [](const ::testing::TestParamInfo<int>& info) {
                                 return all_cases()[info.param].label;
                             });

} // namespace
} // namespace patina::test
