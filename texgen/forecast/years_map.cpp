#include "texgen/forecast/years_map.h"

#include "formats/texture_stack/texture_stack.h"
#include "texgen/stack/map_output.h"

#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <stdexcept>

namespace patina::texgen::forecast {

YearsMaps make_years_maps(const fade::ExposureMap& map, double dose_per_year_factor,
                          double threshold_dose_j_m2, const DeltaECurve& curve,
                          double after_years)
{
    YearsMaps out;
    out.width = map.width;
    out.height = map.height;
    const size_t count = static_cast<size_t>(map.width) * map.height;
    out.years.resize(count);
    out.delta_e.resize(count);
    std::atomic<size_t> bad{count};  // the first bad texel (lowest index wins)
    // Per row: the least years and the most ΔE00 over covered texels
    std::vector<double> row_min(static_cast<size_t>(map.height), kNeverYears),
        row_max(static_cast<size_t>(map.height), 0.0);
    tbb::parallel_for(tbb::blocked_range<int>(0, map.height, 16), [&](const tbb::blocked_range<int>& rows) {
        for (int y = rows.begin(); y < rows.end(); ++y) {
            const size_t row = static_cast<size_t>(y) * map.width;
            for (int x = 0; x < map.width; ++x) {
                const size_t i = row + x;
                const float v = map.values[i];
                if (!(v >= 0.0f) || !std::isfinite(v)) {
                    size_t seen = bad.load();
                    while (i < seen && !bad.compare_exchange_weak(seen, i)) {
                    }
                    out.years[i] = out.delta_e[i] = 0.0f;
                    continue;
                }
                const double per_year = dose_per_year_factor * v;
                const double years = per_year > 0.0 ? threshold_dose_j_m2 / per_year : kNeverYears;
                out.years[i] = static_cast<float>(std::min(years, kNeverYears));
                out.delta_e[i] = static_cast<float>(curve(per_year * after_years));
                if (map.coverage[i] > 0.0f) {
                    row_min[y] = std::min(row_min[y], static_cast<double>(out.years[i]));
                    row_max[y] = std::max(row_max[y], static_cast<double>(out.delta_e[i]));
                }
            }
        }
    });
    if (bad.load() < count) {
        const size_t i = bad.load();
        throw std::runtime_error(fmt::format("exposure map '{}': texel ({}, {}) is {} (a dose must "
                                             "be a finite number >= 0)",
                                             map.file.string(), i % map.width, i / map.width,
                                             map.values[i]));
    }
    // Summary: the first texel to fade and the median, over covered texels (the median of
    // at most 2^20 of them, evenly strided: exact for maps up to 1024², within a texel's
    // spread beyond)
    const size_t stride = std::max<size_t>(1, count >> 20);
    std::vector<float> covered;
    covered.reserve(count / stride + 1);
    for (size_t i = 0; i < count; i += stride)
        if (map.coverage[i] > 0.0f)
            covered.push_back(out.years[i]);
    const double min_years = *std::min_element(row_min.begin(), row_min.end());
    out.max_delta_e = *std::max_element(row_max.begin(), row_max.end());
    if (!covered.empty()) {
        const auto mid = covered.begin() + static_cast<std::ptrdiff_t>(covered.size() / 2);
        std::nth_element(covered.begin(), mid, covered.end());
        out.median_years = *mid;
        out.min_years = min_years;
    }
    return out;
}

void write_years_maps(const std::filesystem::path& dir, const YearsMaps& maps,
                      const std::vector<float>& coverage, const Metadata& parameters,
                      double threshold_de2000, double after_years)
{
    TexelGrid tile;
    tile.width = maps.width;
    tile.height = maps.height;
    const size_t n = static_cast<size_t>(maps.width) * maps.height;
    std::vector<float> pixels(3 * n);
    tbb::parallel_for(size_t(0), n, [&](size_t i) {
        pixels[3 * i] = maps.years[i];
        pixels[3 * i + 1] = maps.delta_e[i];
        pixels[3 * i + 2] = coverage[i];
    });
    MapDescription d;
    d.name = kForecastMap;
    d.channels = {"years_to_threshold", "delta_e_after"};
    d.units = "years, 1";
    d.description = fmt::format("years on display until dE2000 {} (capped at {:g}); dE2000 after "
                                "{} years on display",
                                threshold_de2000, kNeverYears, after_years);
    d.baker = "forecast";
    d.parameters = parameters;
    TextureOptions to;
    to.format = OIIO::TypeDesc::FLOAT;
    to.wrap = "clamp";
    // Uncompressed, as the fade stack's dose.exr: zip took most of a 4096² run
    to.compression = "none";
    to.metadata = parameters;
    const std::filesystem::path file = dir / (std::string(kForecastMap) + ".exr");
    make_texture_atomic(file, pixels.data(), maps.width, maps.height, 3,
                        {"years_to_threshold", "delta_e_after", formats::kCoverageChannel}, to);
    record_in_manifest(dir, d, {file}, {tile});
}

FalseColours false_colours(const YearsMaps& maps, const std::vector<float>& coverage,
                           double threshold_de2000)
{
    const size_t n = static_cast<size_t>(maps.width) * maps.height;
    auto paint = [&](auto scaled) {
        OIIO::ImageBuf value(OIIO::ImageSpec(maps.width, maps.height, 1, OIIO::TypeDesc::FLOAT));
        float* v = static_cast<float*>(value.localpixels());
        for (size_t i = 0; i < n; ++i)
            v[i] = std::clamp(static_cast<float>(scaled(i)), 0.0f, 1.0f);
        const OIIO::ImageBuf colour = OIIO::ImageBufAlgo::color_map(value, 0, "inferno");
        std::vector<float> rgb(3 * n);
        colour.get_pixels(OIIO::ROI(0, maps.width, 0, maps.height, 0, 1, 0, 3),
                          OIIO::TypeDesc::FLOAT, rgb.data());
        for (size_t i = 0; i < n; ++i)
            if (!(coverage[i] > 0.0f))
                rgb[3 * i] = rgb[3 * i + 1] = rgb[3 * i + 2] = 0.5f;
        return rgb;
    };
    // Years on a log scale over the map's own range (covered texels), at least a decade
    double lo = kNeverYears, hi = 0.0, top = 3.0 * threshold_de2000;
    for (size_t i = 0; i < n; ++i)
        if (coverage[i] > 0.0f) {
            lo = std::min(lo, static_cast<double>(maps.years[i]));
            hi = std::max(hi, static_cast<double>(maps.years[i]));
            top = std::max(top, static_cast<double>(maps.delta_e[i]));
        }
    FalseColours out;
    out.log10_years_bright = std::min(std::log10(std::max(lo, 1e-9)),
                                      std::log10(std::max(hi, 1e-9)) - 1.0);
    out.log10_years_dark = std::log10(std::max(hi, 1e-9));
    out.delta_e_bright = top;
    out.years = paint([&](size_t i) {
        const double y = std::log10(std::max(static_cast<double>(maps.years[i]), 1e-9));
        return (out.log10_years_dark - y) / (out.log10_years_dark - out.log10_years_bright);
    });
    out.delta_e = paint([&](size_t i) { return maps.delta_e[i] / top; });
    return out;
}

void write_years_previews(const std::filesystem::path& dir, const YearsMaps& maps,
                          const std::vector<float>& coverage, double threshold_de2000)
{
    const FalseColours c = false_colours(maps, coverage, threshold_de2000);
    write_image_atomic(dir / "fade_forecast_years.png", c.years.data(), maps.width, maps.height,
                       3, {}, OIIO::TypeDesc::UINT8);
    write_image_atomic(dir / "fade_forecast_delta_e.png", c.delta_e.data(), maps.width,
                       maps.height, 3, {}, OIIO::TypeDesc::UINT8);
}

}  // namespace patina::texgen::forecast
