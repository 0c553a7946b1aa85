// The Table IV case of Kimmel et al. 2013: newsprint yellowing with 371 wavelengths
// (330-700 nm at 1 nm), 100 sublayers and 100 time steps on one core. The paper: 34.15 s
// on one core of a 2.8 GHz Xeon (2013). Target (issue 7): under 10 ms.
//
//   bench_fade_solver [--repeats R] [--sublayers N] [--steps T] [--precision P]
//                     [--portable] [--dump FILE]
// Runs the double (reference) and the float kernels (--precision float64 or float32: one
// of them), with AVX2 + FMA where the CPU has them (--portable: the SSE2 build). Prints the
// best time of R runs (and the thread's CPU time), the ratio target / time (>= 1 meets the
// target), paper / time, and how far the float results are from the double ones. --dump
// writes the final reflectance and fractions (%a, exact; double if run) to FILE, to
// compare two builds.
#include "texgen/fade/fading_simulation.h"
#include "texgen/fade/illuminant.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <ctime>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

using namespace patina::texgen::fade;

namespace {

// CPU time of this thread: on a shared machine it counts only the cycles we got.
double thread_cpu_seconds()
{
    timespec ts{};
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

struct Result {
    double best = 1e30, best_cpu = 1e30;
    std::vector<double> reflectance, fractions;
};

Result run_case(const FadeMaterial& material, const WavelengthGrid& grid,
                const Illumination& light, int sublayers, int steps, int repeats,
                FadeSimulation::Precision precision, FadeSimulation::Kernel kernel)
{
    Result out;
    for (int r = 0; r < repeats; ++r) {
        const double c0 = thread_cpu_seconds();
        const auto t0 = std::chrono::steady_clock::now();
        FadeSimulation sim(material, grid, sublayers);
        sim.set_precision(precision);
        sim.set_kernel(kernel);
        sim.run(light, 7.0 * 86400.0, steps);  // seven days (figure 9's longest exposure)
        out.reflectance = sim.reflectance();
        const auto t1 = std::chrono::steady_clock::now();
        out.best = std::min(out.best, std::chrono::duration<double>(t1 - t0).count());
        out.best_cpu = std::min(out.best_cpu, thread_cpu_seconds() - c0);
        out.fractions = sim.fractions();
    }
    return out;
}

void print_case(const char* name, const Result& r)
{
    const double target = 10e-3, paper = 34.15;
    std::printf("  %s: time %.3f ms (thread CPU %.3f ms); target 10 ms: ratio %.2f (>= 1 "
                "meets it); paper 34.15 s: %.0fx faster\n",
                name, r.best * 1e3, r.best_cpu * 1e3, target / r.best, paper / r.best);
}

}  // namespace

int main(int argc, char** argv)
{
    int repeats = 5, sublayers = 100, steps = 100;
    std::string dump, precision = "both";
    bool portable = false;
    for (int i = 1; i < argc; ++i) {
        const bool has_value = i + 1 < argc;
        if (!std::strcmp(argv[i], "--portable"))
            portable = true;
        else if (has_value && !std::strcmp(argv[i], "--repeats"))
            repeats = std::atoi(argv[++i]);
        else if (has_value && !std::strcmp(argv[i], "--sublayers"))
            sublayers = std::atoi(argv[++i]);
        else if (has_value && !std::strcmp(argv[i], "--steps"))
            steps = std::atoi(argv[++i]);
        else if (has_value && !std::strcmp(argv[i], "--dump"))
            dump = argv[++i];
        else if (has_value && !std::strcmp(argv[i], "--precision"))
            precision = argv[++i];
    }
    try {
        const FadeLibrary lib = FadeLibrary::load_files({});
        const FadeMaterial& newsprint = lib.material("newsprint");
        const WavelengthGrid grid = WavelengthGrid::uniform(330.0, 700.0, 1.0);
        // 100 W/m^2 of D65.
        const Illumination light = illuminant_by_name("D65").illumination(grid, 100.0);
        using P = FadeSimulation::Precision;
        using K = FadeSimulation::Kernel;
        const K kernel = portable || !FadeSimulation::kernel_available(K::avx2) ? K::portable
                                                                                 : K::avx2;
        std::printf("fade_solver: %zu wavelengths, %d sublayers, %d steps, best of %d, %s "
                    "kernels\n",
                    grid.size(), sublayers, steps, repeats,
                    kernel == K::avx2 ? "AVX2 + FMA" : "SSE2");
        Result r64, r32;
        if (precision != "float32") {
            r64 = run_case(newsprint, grid, light, sublayers, steps, repeats, P::float64,
                           kernel);
            print_case("double (reference)", r64);
        }
        if (precision != "float64") {
            r32 = run_case(newsprint, grid, light, sublayers, steps, repeats, P::float32,
                           kernel);
            print_case("float            ", r32);
        }
        const Result& shown = r64.reflectance.empty() ? r32 : r64;
        std::printf("  reflectance at 400 nm after 7 days: %.4f\n", shown.reflectance[70]);
        if (!r64.reflectance.empty() && !r32.reflectance.empty()) {
            double dr = 0.0, df = 0.0;
            for (size_t w = 0; w < r64.reflectance.size(); ++w)
                dr = std::max(dr, std::abs(r32.reflectance[w] - r64.reflectance[w]));
            for (size_t k = 0; k < r64.fractions.size(); ++k)
                df = std::max(df, std::abs(r32.fractions[k] - r64.fractions[k]));
            std::printf("  float - double: reflectance %.2e, fractions %.2e (max abs)\n", dr,
                        df);
        }
        if (!dump.empty()) {
            std::FILE* f = std::fopen(dump.c_str(), "w");
            if (!f)
                throw std::runtime_error("cannot write " + dump);
            for (double v : shown.reflectance)
                std::fprintf(f, "R %a\n", v);
            for (double v : shown.fractions)
                std::fprintf(f, "f %a\n", v);
            std::fclose(f);
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_fade_solver: %s\n", e.what());
        return 1;
    }
    return 0;
}
