// bench_patina_script: the urban copper strip of Dorsey & Hanrahan 1996 §5.1 (the script as
// printed, samples/copper_strips/urban.patina) on a 2048 x 2048 strip, on 2 threads.
//
// Prints the seconds of each phase (parse, grow the six texture() maps, apply the seven
// operators, write the stack: 6 tiled mip-mapped EXRs, stack.toml and the preview PNG), and
// the script's seconds (parse + grow + operators) against the target of 5 s as a
// ratio (target / measured; >= 1 meets it). As a bound measured in the same run it also
// prints the seconds to stream the same bytes the operators touch through memory (one
// read + write of every layer's floats per operator), and the ratio to that.
//
//   bench_patina_script [--resolution N] [--threads T] [--no-output] [--half] [SOURCE_DIR]
//   (--half writes half-float maps, as patina-texgen patina --half does)
#include "core/color_management.h"
#include "texgen/growth/growth_model.h"
#include "texgen/patina/interpreter.h"
#include "texgen/patina/material_library.h"
#include "texgen/patina/script_parser.h"
#include "texgen/patina/stack_writer.h"

#include <tbb/global_control.h>
#include <tbb/parallel_for.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

namespace {

using Clock = std::chrono::steady_clock;
namespace fs = std::filesystem;
using namespace patina;
using namespace patina::texgen;

double seconds_since(Clock::time_point start)
{
    return std::chrono::duration<double>(Clock::now() - start).count();
}

}  // namespace

int main(int argc, char** argv)
{
    int resolution = 2048, threads = 2;
    bool output = true, half = false;
    fs::path source = fs::path(__FILE__).parent_path().parent_path();
    for (int i = 1; i < argc; ++i) {
        if (!std::strcmp(argv[i], "--resolution") && i + 1 < argc)
            resolution = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc)
            threads = std::atoi(argv[++i]);
        else if (!std::strcmp(argv[i], "--no-output"))
            output = false;
        else if (!std::strcmp(argv[i], "--half"))
            half = true;
        else
            source = argv[i];
    }
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, threads);

    ColorManager colors(source / "ocio" / "config.ocio");
    MaterialLibrary library;
    library.load(source / "shaders/patina/copper.toml", colors);
    const fs::path script_path = source / "samples/copper_strips/urban.patina";
    std::ifstream in(script_path);
    std::stringstream text;
    text << in.rdbuf();

    const PatinaDomain strip = make_strip_domain(resolution, resolution, 0.1);
    auto start = Clock::now();
    const Script script = parse_script(text.str(), "urban.patina", library.names());
    const double parse_s = seconds_since(start);

    // Grow alone (the interpreter grows the same maps before running the operators).
    InterpreterOptions options;
    options.times_years = {30.0};
    start = Clock::now();
    const std::vector<PatinaStep> steps = run_patina_script(script, library, strip, options);
    const double run_s = seconds_since(start);

    // The same script with every texture() replaced by a constant: the operators alone.
    std::string constant = text.str();
    for (size_t at = constant.find("texture("); at != std::string::npos;
         at = constant.find("texture(")) {
        const size_t end = constant.find(')', at);
        constant.replace(at, end - at + 1, "0.5");
    }
    const Script operators_only = parse_script(constant, "urban-constant.patina", library.names());
    start = Clock::now();
    run_patina_script(operators_only, library, strip, options);
    const double operators_s = seconds_since(start);

    double write_s = 0;
    if (output) {
        const fs::path dir = fs::temp_directory_path() / "bench_patina_script";
        fs::remove_all(dir);
        PatinaOutputOptions out;
        out.script = "urban.patina";
        if (half)
            out.maps.format = OIIO::TypeDesc::HALF;
        start = Clock::now();
        write_patina_step(dir, steps.back(), strip, out, colors);
        write_s = seconds_since(start);
        fs::remove_all(dir);
    }

    // Bound: each of the 7 operators reads and writes every layer's floats once.
    const size_t n = strip.size();
    std::vector<std::vector<float>> layers(6, std::vector<float>(n, 1.0f));
    start = Clock::now();
    for (int op = 0; op < 7; ++op)
        for (auto& layer : layers)
            tbb::parallel_for(tbb::blocked_range<size_t>(0, n, 1 << 16),
                              [&](const tbb::blocked_range<size_t>& r) {
                                  for (size_t i = r.begin(); i != r.end(); ++i)
                                      layer[i] = layer[i] * 0.999f + 0.001f;
                              });
    const double bound_s = seconds_since(start);

    const double script_s = parse_s + run_s;
    std::printf("urban.patina (D&H 1996 §5.1) on a %dx%d strip, %d threads\n", resolution,
                resolution, threads);
    std::printf("  parse              %8.4f s\n", parse_s);
    std::printf("  grow + operators   %8.3f s   (operators alone: %.3f s)\n", run_s, operators_s);
    if (output)
        std::printf("  write stack        %8.3f s   (6 EXR textures, stack.toml, preview.png)\n",
                    write_s);
    std::printf("  memory-stream bound of the operators: %.3f s (operators / bound = %.2f)\n",
                bound_s, operators_s / bound_s);
    std::printf("script %.3f s; target 5 s; ratio target / script = %.2f (>= 1 meets it)\n",
                script_s, 5.0 / script_s);
    if (output)
        std::printf("with output %.3f s; ratio target / (script + output) = %.2f\n",
                    script_s + write_s, 5.0 / (script_s + write_s));
    return 0;
}
