// bench_years_map: a 4096x4096 map of years to a just-noticeable fade (and of ΔE00 after 10
// years) from an exposure map on 2 cores (issue 32: target <= 2 s), against the fade map
// baker (`patina-texgen fade`'s path) on the same map in the same run. Both are timed after
// the map is in memory and include their tables and the tiled, mip-mapped EXRs they write:
// forecast = the threshold dose, the ΔE00 curve's table, the per-texel years and ΔE00, two
// float maps and stack.toml; fade = its dose table and error table, the per-texel rows, the
// fade stack. Prints both, the ratio forecast / fade, and 2 s / forecast (>= 1 meets it).
//
//   bench_years_map [--size N] [--threads T] [--runs R]
#include "texgen/fade/dose_table.h"
#include "texgen/fade/fade_map.h"
#include "texgen/fade/fade_material.h"
#include "texgen/fade/fade_stack.h"
#include "texgen/fade/illuminant.h"
#include "texgen/forecast/fade_forecast.h"
#include "texgen/forecast/years_map.h"

#include "core/output_transaction.h"

#include "fade_bench.h"

#include <tbb/global_control.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>

namespace fs = std::filesystem;
using namespace patina::texgen;


int main(int argc, char** argv)
{
    const FadeBenchOptions options = parse_fade_bench_options(argc, argv, 4096);
    const int size = options.size, threads = options.threads, runs = options.runs;
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);

    const fade::FadeLibrary library = fade::FadeLibrary::load_files(fade::FadeLibrary::default_files());
    const fade::FadeMaterial& material = library.material("congo_red");
    const fade::Illuminant d65 = fade::illuminant_by_name("D65");
    // The commands' default grid (300-830 nm, 5 nm) for both
    const fade::WavelengthGrid grid = fade::WavelengthGrid::uniform(300.0, 830.0, 5.0);
    // A year of light a window gives a floor: up to 3e7 J/m^2 a year
    const fade::ExposureMap map = synthetic_exposure_map(size, 3e7);
    const forecast::ColourMeter meter(grid, d65);
    const fs::path out = fs::temp_directory_path() / "patina_bench_years_map";
    const double after_years = 10.0;

    double best_forecast = 1e30, best_fade = 1e30;
    for (int run = 0; run < runs; ++run) {
        // patina-texgen forecast --exposure ... --after 10
        fs::remove_all(out);
        {
            patina::OutputTransaction outputs;
            patina::CurrentOutputs current(outputs);
            const auto t0 = std::chrono::steady_clock::now();
            forecast::ForecastOptions fo;
            const double threshold = forecast::threshold_dose(material, d65, grid, meter, fo);
            const fade::DoseRange range = fade::scan_doses(map, 1.0);
            fade::DoseTableOptions t;
            t.max_dose_j_m2 = range.max * after_years;
            t.knee_dose_j_m2 = t.max_dose_j_m2 * 1e-6;
            t.entries = 96;
            const fade::DoseTable table = fade::DoseTable::build(material, d65, grid, t);
            const forecast::DeltaECurve curve(table, meter);
            const double t_tables = seconds_since(t0);
            const auto t1 = std::chrono::steady_clock::now();
            const forecast::YearsMaps maps =
                forecast::make_years_maps(map, 1.0, threshold, curve, after_years);
            const double t_texels = seconds_since(t1);
            const auto t2 = std::chrono::steady_clock::now();
            forecast::write_years_maps(out / "forecast", maps, map.coverage, {}, 1.0, after_years);
            outputs.commit();
            const double t_write = seconds_since(t2);
            const double total = seconds_since(t0);
            best_forecast = std::min(best_forecast, total);
            std::printf("run %d forecast: tables %.3f s, texels %.3f s, write %.3f s, total %.3f s "
                        "(years %.3g to %.3g)\n",
                        run + 1, t_tables, t_texels, t_write, total, maps.min_years, maps.median_years);
        }
        // patina-texgen fade --exposure ... on the same map
        {
            patina::OutputTransaction outputs;
            patina::CurrentOutputs current(outputs);
            const auto t0 = std::chrono::steady_clock::now();
            const fade::DoseRange range = fade::scan_doses(map, 1.0);
            fade::DoseTableOptions o;
            o.max_dose_j_m2 = range.max;
            o.knee_dose_j_m2 = range.max * 1e-6;
            const fade::DoseTable table = fade::DoseTable::build(material, d65, grid, o);
            fade::DoseTableOptions fine_options = o;
            fine_options.entries = 2 * o.entries - 1;
            fine_options.substeps = 1;
            const fade::DoseTable fine = fade::DoseTable::build(material, d65, grid, fine_options);
            const std::vector<float> pixels = fade::make_dose_pixels(map, table, 1.0);
            fade::FadeStackInfo info;
            info.material = material.name;
            info.illuminant = d65.name;
            info.substrate = grid.sample(material.substrate_reflectance);
            info.width = info.height = size;
            info.max_dose = range.max;
            info.max_interpolation_error = fade::interpolation_error(table, fine);
            fade::write_fade_stack(out / "fade", table, info, pixels);
            outputs.commit();
            const double total = seconds_since(t0);
            best_fade = std::min(best_fade, total);
            std::printf("run %d fade map: total %.3f s\n", run + 1, total);
        }
    }
    fs::remove_all(out);
    std::printf("years map %dx%d, %d threads: forecast %.3f s, fade map %.3f s, ratio %.2f; "
                "target 2 s: %.2f (>= 1 meets it)\n",
                size, size, threads, best_forecast, best_fade, best_forecast / best_fade,
                2.0 / best_forecast);
    return 0;
}
