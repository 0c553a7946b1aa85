// Exposure map -> doses -> table coordinates (see fade_map.h).
#include "texgen/fade/fade_map.h"

#include "texgen/stack/map_output.h"

#include "core/image_io.h"
#include "texgen/fade/fade_stack.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace patina::texgen::fade {

namespace fs = std::filesystem;

namespace {

    const std::string* find_metadata(const ImageData& image, const std::string& key)
    {
        for (const auto& [k, v] : image.metadata)
            if (k == key)
                return &v;
        return nullptr;
    }

    // "300:49.98 305:52.31 ..." (the exposure baker's illuminant_spectrum)
    void parse_spectrum(const std::string& text, const fs::path& file, std::vector<double>* nm,
                        std::vector<double>* value)
    {
        std::istringstream in(text);
        std::string pair;
        while (in >> pair) {
            const size_t colon = pair.find(':');
            char* end = nullptr;
            const double l = std::strtod(pair.c_str(), &end);
            const double v = colon == std::string::npos
                                 ? std::numeric_limits<double>::quiet_NaN()
                                 : std::strtod(pair.c_str() + colon + 1, nullptr);
            if (colon == std::string::npos || !std::isfinite(l) || !std::isfinite(v) ||
                (!nm->empty() && l <= nm->back()))
                throw std::runtime_error(fmt::format(
                    "exposure map '{}': patina:illuminant_spectrum entry '{}' is not nm:value "
                    "with increasing nm",
                    file.string(), pair));
            nm->push_back(l);
            value->push_back(v);
        }
    }

}  // namespace

ExposureMap read_exposure_map(const fs::path& file, const std::string& channel)
{
    if (!fs::exists(file))
        throw std::runtime_error("exposure map '" + file.string() + "' does not exist");
    const ImageData image = read_image(file);
    ExposureMap map;
    map.file = file;
    map.width = image.width;
    map.height = image.height;
    map.channel = channel;
    if (map.channel.empty())
        map.channel = image.channel("exposure") >= 0 ? "exposure" : "irradiance";
    const int c = image.channel(map.channel);
    if (c < 0) {
        std::string names;
        for (const std::string& n : image.channel_names)
            names += (names.empty() ? "" : ", ") + n;
        throw std::runtime_error(fmt::format("exposure map '{}' has no channel '{}' (it has {})",
                                             file.string(), map.channel, names));
    }
    if (const std::string* units = find_metadata(image, "patina:units"))
        map.units = *units;
    else
        map.units = map.channel == "irradiance" ? "W/m^2" : "J/m^2";
    if (map.units != "J/m^2" && map.units != "W/m^2")
        throw std::runtime_error(fmt::format("exposure map '{}': units '{}', expected J/m^2 or "
                                             "W/m^2 (an exposure or irradiance map)",
                                             file.string(), map.units));
    if (const std::string* p = find_metadata(image, "patina:period_seconds"))
        map.period_s = std::strtod(p->c_str(), nullptr);
    if (const std::string* name = find_metadata(image, "patina:illuminant"))
        map.illuminant = *name;
    if (const std::string* spectrum = find_metadata(image, "patina:illuminant_spectrum"))
        parse_spectrum(*spectrum, file, &map.illuminant_nm, &map.illuminant_value);

    map.values.resize(static_cast<size_t>(map.width) * map.height);
    for (size_t i = 0; i < map.values.size(); ++i)
        map.values[i] = image.pixels[i * image.channels + c];
    const int a = image.channel(kCoverageChannel);
    map.coverage.assign(map.values.size(), 1.0f);
    if (a >= 0)
        for (size_t i = 0; i < map.coverage.size(); ++i)
            map.coverage[i] = image.pixels[i * image.channels + a];
    return map;
}

double dose_factor(const ExposureMap& map, double scale, double duration_s)
{
    if (!(scale > 0.0) || !std::isfinite(scale))
        throw std::runtime_error(fmt::format("--scale {} must be positive", scale));
    if (!(duration_s >= 0.0) || !std::isfinite(duration_s))
        throw std::runtime_error(fmt::format("--duration {} s must not be negative", duration_s));
    if (map.units == "W/m^2") {
        if (duration_s <= 0.0)
            throw std::runtime_error("exposure map '" + map.file.string() +
                                     "' holds a mean irradiance (W/m^2): --duration is needed "
                                     "to turn it into a dose");
        return scale * duration_s;
    }
    if (duration_s == 0.0)
        return scale;
    if (!(map.period_s > 0.0))
        throw std::runtime_error("exposure map '" + map.file.string() +
                                 "' does not say which period it covers (patina:period_seconds): "
                                 "--duration cannot rescale it; use --scale");
    return scale * duration_s / map.period_s;
}

DoseRange scan_doses(const ExposureMap& map, double factor)
{
    DoseRange r;
    r.min = std::numeric_limits<double>::infinity();
    double sum = 0.0;
    for (size_t i = 0; i < map.values.size(); ++i) {
        const double v = map.values[i];
        if (!std::isfinite(v) || v < 0.0)
            throw std::runtime_error(fmt::format(
                "exposure map '{}': texel ({}, {}) of channel '{}' is {} (a dose must be a "
                "finite, non-negative number)",
                map.file.string(), i % map.width, i / map.width, map.channel, v));
        const double dose = factor * v;
        r.min = std::min(r.min, dose);
        r.max = std::max(r.max, dose);
        sum += dose;
    }
    if (map.values.empty())
        r.min = 0.0;
    else
        r.mean = sum / static_cast<double>(map.values.size());
    return r;
}

std::vector<float> make_dose_pixels(const ExposureMap& map, const DoseTable& table,
                                    double factor, void (*progress)(size_t, void*),
                                    void* progress_data)
{
    const size_t width = static_cast<size_t>(map.width);
    std::vector<float> pixels(map.values.size() * 3);
    const DoseRow row(table);
    std::atomic<size_t> bad{std::numeric_limits<size_t>::max()};
    tbb::parallel_for(tbb::blocked_range<size_t>(0, static_cast<size_t>(map.height), 16),
                      [&](const tbb::blocked_range<size_t>& rows) {
                          for (size_t y = rows.begin(); y != rows.end(); ++y) {
                              for (size_t x = 0; x < width; ++x) {
                                  const size_t i = y * width + x;
                                  const double v = map.values[i];
                                  if (!std::isfinite(v) || v < 0.0) {
                                      size_t expected = bad.load();
                                      while (i < expected &&
                                             !bad.compare_exchange_weak(expected, i)) {
                                      }
                                      continue;
                                  }
                                  const double dose = factor * v;
                                  pixels[3 * i] = static_cast<float>(row(dose));
                                  pixels[3 * i + 1] = static_cast<float>(dose);
                                  pixels[3 * i + 2] =
                                      i < map.coverage.size() ? map.coverage[i] : 1.0f;
                              }
                          }
                          if (progress)
                              progress(rows.size(), progress_data);
                      });
    if (const size_t i = bad.load(); i != std::numeric_limits<size_t>::max())
        throw std::runtime_error(fmt::format(
            "exposure map '{}': texel ({}, {}) of channel '{}' is {} (a dose must be a finite, "
            "non-negative number)",
            map.file.string(), i % width, i / width, map.channel, map.values[i]));
    return pixels;
}

}  // namespace patina::texgen::fade
