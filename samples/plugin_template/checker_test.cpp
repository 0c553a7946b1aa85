// The checks every BSDF of Patina passes, on checker_lambert, with the installed testing
// headers and no test framework: the sampler against its pdf (chi-square), the white
// furnace (albedo 1 for a white checker, by quadrature and by importance sampling) and
// reciprocity. Exits non-zero, saying which check failed. Run by ctest in the build.
#include <patina/testing/bsdf_checks.h>
#include <patina/testing/chi2.h>

#include <cmath>
#include <cstdio>

extern "C" const PatinaPluginInfo* patina_plugin_entry(const PatinaHost*);

namespace {

int failures = 0;

void check(bool ok, const char* what, double value)
{
    std::printf("%-48s %s (%g)\n", what, ok ? "ok" : "FAILED", value);
    failures += ok ? 0 : 1;
}

PatinaParamValue colour(float grey)
{
    PatinaParamValue v{};
    v.type = PATINA_PARAM_COLOR;
    v.rgb[0] = v.rgb[1] = v.rgb[2] = grey;
    // A flat reflectance: the sigmoid at 0 is 1/2, scaled to `grey`.
    v.color = {0.0f, 0.0f, 0.0f, 2.0f * grey, 0};
    return v;
}

}  // namespace

int main()
{
    const PatinaShaderDesc& desc = patina_plugin_entry(nullptr)->shaders[0];
    PatinaParamValue values[3] = {colour(1.0f), colour(1.0f), {}};
    values[2].type = PATINA_PARAM_FLOAT;
    values[2].f = 8.0f;
    void* instance = desc.create(nullptr, values);
    if (!instance) {
        std::printf("create refused the values\n");
        return 1;
    }
    PatinaWavelengths wl{};
    wl.count = 4;
    for (int i = 0; i < 4; ++i)
        wl.lambda_nm[i] = 400.0f + 100.0f * i;
    const patina::test::BsdfCalls bsdf(desc.bsdf, instance, wl);

    for (float theta : {0.1f, 0.8f, 1.4f}) {
        const PatinaVec3 wo = {std::sin(theta), 0.0f, std::cos(theta)};
        // White furnace: a white Lambertian reflects everything (albedo exactly 1).
        const double quadrature = patina::test::albedo_by_quadrature(bsdf, wo, 256)[0];
        const double sampled = patina::test::albedo_by_sampling(bsdf, wo, 64)[0];
        check(std::abs(quadrature - 1.0) < 5e-3, "white furnace by quadrature", quadrature);
        check(std::abs(sampled - 1.0) < 1e-5, "white furnace by importance sampling", sampled);

        // The sampler against its pdf.
        unsigned state = 12345u;
        auto next = [&] { return ((state = state * 1664525u + 1013904223u) >> 8) * 0x1p-24f; };
        const patina::test::chi2::Result r = patina::test::chi2::run(
            {}, [&](patina::shading::Vec3* w) {
                PatinaBsdfSample s;
                const float u_lobe = next();
                const PatinaVec2 u = {next(), next()};
                if (!bsdf.sample(wo, u_lobe, u, &s))
                    return false;
                *w = s.wi;
                return true;
            },
            [&](patina::shading::Vec3 w) {
                return desc.bsdf->pdf(instance, &bsdf.ctx, wo, w, &wl);
            });
        check(r.passed, "chi-square: sampling matches pdf (p-value)", r.p_value);
        for (float phi : {0.5f, 2.0f, 4.0f}) {
            const PatinaVec3 wi = {0.6f * std::cos(phi), 0.6f * std::sin(phi), 0.8f};
            const double e = patina::test::reciprocity_error(bsdf, wo, wi);
            check(e == 0.0, "reciprocity f(wo, wi) = f(wi, wo)", e);
        }
    }
    desc.destroy(instance);
    return failures == 0 ? 0 : 1;
}
