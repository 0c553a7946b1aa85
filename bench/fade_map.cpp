// bench_fade_map: a 2048x2048 fade map from an exposure map on 2 cores (issue 7: target
// < 2 s). Times the whole `patina-texgen fade` path after reading the exposure map: the dose
// table of newsprint under D65 (371 wavelengths, 100 sublayers, 64 entries) and its
// error estimate (a table twice as fine), the per-texel doses and table rows (TBB), and
// the tiled, mip-mapped dose.exr + fade_table.exr + fade.toml. Prints each stage, the
// total and the ratio 2 s / total (>= 1 meets the target).
//
//   bench_fade_map [--size N] [--threads T] [--runs R]
#include "texgen/fade/dose_table.h"
#include "texgen/fade/fade_map.h"
#include "texgen/fade/fade_material.h"
#include "texgen/fade/fade_stack.h"
#include "texgen/fade/illuminant.h"

#include "fade_bench.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>

namespace fs = std::filesystem;
using namespace patina::texgen::fade;


int main(int argc, char** argv)
{
    const FadeBenchOptions options = parse_fade_bench_options(argc, argv, 2048);
    const int size = options.size, threads = options.threads, runs = options.runs;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);

    // The shipped library (<exe>/../share/patina/shaders/fade, or $PATINA_SHADER_PATH)
    const FadeLibrary library = FadeLibrary::load_files(FadeLibrary::default_files());
    const FadeMaterial& material = library.material("newsprint");
    const Illuminant d65 = illuminant_by_name("D65");
    const WavelengthGrid grid = WavelengthGrid::uniform(330.0, 700.0, 1.0);
    const ExposureMap map = synthetic_exposure_map(size, 3e7);
    const fs::path out = fs::temp_directory_path() / "patina_bench_fade_map";

    double best = 1e30;
    for (int run = 0; run < runs; ++run) {
        fs::remove_all(out);
        const auto t0 = std::chrono::steady_clock::now();
        const DoseRange range = scan_doses(map, 1.0);
        DoseTableOptions o;
        o.max_dose_j_m2 = range.max;
        o.knee_dose_j_m2 = range.max * 1e-6;  // as patina-texgen fade
        const DoseTable table = DoseTable::build(material, d65, grid, o);
        DoseTableOptions fine_options = o;
        fine_options.entries = 2 * o.entries - 1;
        fine_options.substeps = 1;
        const DoseTable fine = DoseTable::build(material, d65, grid, fine_options);
        const double error = interpolation_error(table, fine);
        const double t_table = seconds_since(t0);

        const auto t1 = std::chrono::steady_clock::now();
        const std::vector<float> pixels = make_dose_pixels(map, table, 1.0);
        const double t_pixels = seconds_since(t1);

        const auto t2 = std::chrono::steady_clock::now();
        FadeStackInfo info;
        info.material = material.name;
        info.illuminant = d65.name;
        info.substrate = grid.sample(material.substrate_reflectance);
        info.width = info.height = size;
        info.max_dose = range.max;
        info.max_interpolation_error = error;
        write_fade_stack(out, table, info, pixels);
        const double t_write = seconds_since(t2);
        const double total = seconds_since(t0);
        best = std::min(best, total);
        std::printf("run %d: tables %.3f s (error %.2g), doses + rows %.3f s, write %.3f s, "
                    "total %.3f s\n",
                    run + 1, t_table, error, t_pixels, t_write, total);
    }
    fs::remove_all(out);
    std::printf("fade map %dx%d, %d threads, %zu wavelengths: best %.3f s; target 2 s, ratio "
                "%.2f (>= 1 meets it)\n",
                size, size, threads, grid.size(), best, 2.0 / best);
    return 0;
}
