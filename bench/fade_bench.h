// What the fading benchmarks (bench_fade_map, bench_years_map) share: their options, a
// clock, and the exposure map they time.
#pragma once

#include "texgen/fade/fade_map.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>

/// --size N --threads T --runs R
struct FadeBenchOptions {
    int size = 2048, threads = 2, runs = 3;
};
inline FadeBenchOptions parse_fade_bench_options(int argc, char** argv, int default_size)
{
    FadeBenchOptions o;
    o.size = default_size;
    for (int i = 1; i + 1 < argc; i += 2) {
        if (!std::strcmp(argv[i], "--size"))
            o.size = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--threads"))
            o.threads = std::atoi(argv[i + 1]);
        else if (!std::strcmp(argv[i], "--runs"))
            o.runs = std::atoi(argv[i + 1]);
    }
    return o;
}

inline double seconds_since(std::chrono::steady_clock::time_point t)
{
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

/// An exposure map: a window's light on a floor, a smooth falloff with the shadows of two
/// boxes, up to `peak` J/m^2 (figure 1 of Kimmel et al. 2013 has 2.789e7).
inline patina::texgen::fade::ExposureMap synthetic_exposure_map(int n, double peak)
{
    patina::texgen::fade::ExposureMap map;
    map.width = map.height = n;
    map.channel = "exposure";
    map.units = "J/m^2";
    map.values.resize(static_cast<size_t>(n) * n);
    map.coverage.assign(map.values.size(), 1.0f);
    for (int y = 0; y < n; ++y)
        for (int x = 0; x < n; ++x) {
            const double u = (x + 0.5) / n, v = (y + 0.5) / n;
            double e = peak * std::exp(-2.0 * (u * u + 0.5 * v * v));
            if ((u > 0.2 && u < 0.45 && v > 0.3 && v < 0.6) || (u > 0.6 && u < 0.8 && v > 0.1))
                e *= 0.05;
            map.values[static_cast<size_t>(y) * n + x] = static_cast<float>(e);
        }
    return map;
}
