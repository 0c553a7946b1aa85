// The Table IV case of Kimmel et al. 2013: newsprint yellowing with 371 wavelengths
// (330-700 nm at 1 nm), 100 sublayers and 100 time steps on one core. The paper: 34.15 s
// on one core of a 2.8 GHz Xeon (2013). Target (issue 7): under 10 ms.
//
//   bench_fade_solver [--repeats R] [--sublayers N] [--steps T] [--dump FILE]
// Prints the best time of R runs, the ratio target / time (>= 1 meets the target) and
// paper / time. --dump writes the final reflectance and fractions (%a, exact) to FILE, to
// compare two builds.
#include "texgen/fade/fading_simulation.h"
#include "texgen/fade/illuminant.h"

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>

using namespace patina::texgen::fade;

int main(int argc, char** argv)
{
    int repeats = 5, sublayers = 100, steps = 100;
    std::string dump;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--repeats"))
            repeats = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--sublayers"))
            sublayers = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--steps"))
            steps = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--dump"))
            dump = argv[i + 1];
    }
    try {
        const FadeLibrary lib = FadeLibrary::load_files({});
        const FadeMaterial& newsprint = lib.material("newsprint");
        const WavelengthGrid grid = WavelengthGrid::uniform(330.0, 700.0, 1.0);
        // Seven days (figure 9's longest exposure) at 100 W/m^2 of D65.
        const Illumination light = illuminant_by_name("D65").illumination(grid, 100.0);
        const double duration = 7.0 * 86400.0;
        double best = 1e30, checksum = 0.0;
        std::vector<double> refl, fractions;
        for (int r = 0; r < repeats; ++r) {
            const auto t0 = std::chrono::steady_clock::now();
            FadeSimulation sim(newsprint, grid, sublayers);
            sim.run(light, duration, steps);
            refl = sim.reflectance();
            const auto t1 = std::chrono::steady_clock::now();
            best = std::min(best, std::chrono::duration<double>(t1 - t0).count());
            checksum = refl[70];  // 400 nm
            fractions = sim.fractions();
        }
        if (!dump.empty()) {
            std::FILE* f = std::fopen(dump.c_str(), "w");
            if (!f)
                throw std::runtime_error("cannot write " + dump);
            for (double v : refl)
                std::fprintf(f, "R %a\n", v);
            for (double v : fractions)
                std::fprintf(f, "f %a\n", v);
            std::fclose(f);
        }
        const double target = 10e-3, paper = 34.15;
        std::printf("fade_solver: %zu wavelengths, %d sublayers, %d steps, best of %d\n",
                    grid.size(), sublayers, steps, repeats);
        std::printf("  time %.3f ms; target 10 ms: ratio %.2f (>= 1 meets it); paper 34.15 s: "
                    "%.0fx faster\n",
                    best * 1e3, target / best, paper / best);
        std::printf("  reflectance at 400 nm after 7 days: %.4f\n", checksum);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "bench_fade_solver: %s\n", e.what());
        return 1;
    }
    return 0;
}
