// What does a call through the plugin ABI cost? Lambert eval + sample through the dlopen'd
// basic plugin against the same Lambert written inline in the host, in the same run.
// Prints the ratio ABI / inline (1.0 = free; the indirect call and the uplifted-spectrum
// evaluation are the expected overhead).
#include "host/host.h"
#include "host/plugin_registry.h"
#include "host/shader_instance.h"
#include "core/spectrum.h"

#include <patina/shading/frame.h>
#include <patina/shading/sampling.h>
#include <patina/shading/spectral.h>

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <map>

namespace {

constexpr float kInvPi = 0.318309886f;

struct Fixture {
    patina::PluginRegistry registry{patina::default_host().c_host()};
    std::shared_ptr<patina::ShaderInstance> lambert;
    PatinaRgbSpectrum reflectance{};

    Fixture()
    {
        registry.load_directory(PATINA_TEST_PLUGIN_DIR);
        toml::table params{{"reflectance", toml::array{0.8, 0.3, 0.2}}};
        lambert = patina::create_shader_instance(registry, "lambert", params, "bench");
        const float rgb[3] = {0.8f, 0.3f, 0.2f};
        reflectance = patina::default_host().uplift(rgb, false);
    }
};

Fixture& fixture()
{
    static Fixture f;
    return f;
}

PatinaWavelengths wavelengths() { return patina::sample_wavelengths_visible(0.37f, 4); }

void BM_LambertThroughAbi(benchmark::State& state)
{
    Fixture& f = fixture();
    const PatinaBsdfFuncs* bsdf = f.lambert->bsdf();
    const void* inst = f.lambert->get();
    const PatinaWavelengths wl = wavelengths();
    PatinaShadingContext ctx{};
    float u = 0.1f;
    for (auto _ : state) {
        PatinaBsdfSample s;
        u = u + 0.6180339f - std::floor(u + 0.6180339f);
        bsdf->sample(inst, &ctx, {0.3f, 0.1f, 0.95f}, u, {u, 1.0f - u}, &wl, &s);
        float f_val[PATINA_MAX_WAVELENGTHS];
        bsdf->eval(inst, &ctx, {0.3f, 0.1f, 0.95f}, s.wi, &wl, f_val);
        benchmark::DoNotOptimize(f_val);
        benchmark::DoNotOptimize(s);
    }
}

// The same work with no ABI in between: the plugin's own header-only helpers (cosine
// hemisphere sampling, R(λ)/π) called inline, so the ratio isolates the cost of the
// boundary (indirect calls, no inlining across it, the plugin's argument checks).
void BM_LambertInline(benchmark::State& state)
{
    namespace sh = patina::shading;
    const PatinaRgbSpectrum r = fixture().reflectance;
    const PatinaWavelengths wl = wavelengths();
    const PatinaVec3 wo{0.3f, 0.1f, 0.95f};
    float u = 0.1f;
    for (auto _ : state) {
        PatinaBsdfSample s;
        u = u + 0.6180339f - std::floor(u + 0.6180339f);
        const sh::Vec3 wi = sh::sample_cosine_hemisphere(sh::Vec2{u, 1.0f - u});
        s.wi = wi;
        s.pdf = sh::cosine_hemisphere_pdf(sh::abs_cos_theta(wi));
        const bool same = sh::same_hemisphere(wo, wi);
        sh::store(sh::eval_rgb(r, wl) * (same ? kInvPi : 0.0f), wl, s.f);
        float f_val[PATINA_MAX_WAVELENGTHS];
        sh::store(sh::eval_rgb(r, wl) * (same ? kInvPi : 0.0f), wl, f_val);
        benchmark::DoNotOptimize(f_val);
        benchmark::DoNotOptimize(s);
    }
}

BENCHMARK(BM_LambertThroughAbi);
BENCHMARK(BM_LambertInline);

// Collects the per-iteration times so main can print the ratio.
class RatioReporter : public benchmark::ConsoleReporter {
public:
    std::map<std::string, double> ns;
    void ReportRuns(const std::vector<Run>& runs) override
    {
        for (const Run& r : runs)
            ns[r.benchmark_name()] = r.GetAdjustedRealTime();
        ConsoleReporter::ReportRuns(runs);
    }
};

}  // namespace

int main(int argc, char** argv)
{
    benchmark::Initialize(&argc, argv);
    RatioReporter reporter;
    benchmark::RunSpecifiedBenchmarks(&reporter);
    const double abi = reporter.ns["BM_LambertThroughAbi"], inl = reporter.ns["BM_LambertInline"];
    if (abi > 0 && inl > 0)
        std::printf("ratio abi/inline (lambert sample+eval, 4 wavelengths): %.2f\n", abi / inl);
    benchmark::Shutdown();
    return 0;
}
