// What does a call through the plugin ABI cost? Lambert eval + sample through the dlopen'd
// basic plugin against the same Lambert written inline in the host, in the same run.
// Prints the ratio ABI / inline (1.0 = free; the indirect call and the uplifted-spectrum
// evaluation are the expected overhead).
#include "core/host.h"
#include "core/plugin_registry.h"
#include "core/shader_instance.h"
#include "core/spectrum.h"

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

// The same work with no ABI in between: cosine sampling and R(λ)/π inline.
void BM_LambertInline(benchmark::State& state)
{
    const PatinaRgbSpectrum r = fixture().reflectance;
    const PatinaWavelengths wl = wavelengths();
    float u = 0.1f;
    for (auto _ : state) {
        PatinaBsdfSample s;
        u = u + 0.6180339f - std::floor(u + 0.6180339f);
        const float rad = std::sqrt(u), phi = 6.2831853f * (1.0f - u);
        s.wi = {rad * std::cos(phi), rad * std::sin(phi), std::sqrt(std::max(0.0f, 1.0f - u))};
        s.pdf = s.wi.z * kInvPi;
        float f_val[PATINA_MAX_WAVELENGTHS];
        for (int i = 0; i < wl.count; ++i) {
            s.f[i] = patina_rgb_spectrum_eval(&r, wl.lambda_nm[i]) * kInvPi;
            f_val[i] = patina_rgb_spectrum_eval(&r, wl.lambda_nm[i]) * kInvPi;
        }
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
