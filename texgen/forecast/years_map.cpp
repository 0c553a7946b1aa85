#include "texgen/forecast/years_map.h"

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
    std::vector<float> covered;
    for (size_t i = 0; i < count; ++i) {
        if (map.coverage[i] > 0.0f) {
            covered.push_back(out.years[i]);
            out.max_delta_e = std::max(out.max_delta_e, static_cast<double>(out.delta_e[i]));
        }
    }
    if (!covered.empty()) {
        const auto mid = covered.begin() + static_cast<std::ptrdiff_t>(covered.size() / 2);
        std::nth_element(covered.begin(), mid, covered.end());
        out.median_years = *mid;
        out.min_years = *std::min_element(covered.begin(), covered.end());
    }
    return out;
}

}  // namespace patina::texgen::forecast
