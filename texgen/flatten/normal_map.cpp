#include "texgen/flatten/normal_map.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen {

std::vector<float> normal_map_from_height(std::span<const float> height_um, int width,
                                          int height, double texel_size_um, double scale)
{
    if (width <= 0 || height <= 0 || height_um.size() != static_cast<size_t>(width) * height)
        throw std::invalid_argument("normal_map_from_height: size does not match the image");
    if (!(texel_size_um > 0.0) || !std::isfinite(scale))
        throw std::invalid_argument("normal_map_from_height: texel size must be positive");
    std::vector<float> out(static_cast<size_t>(width) * height * 3);
    const auto h = [&](int x, int y) {
        x = std::clamp(x, 0, width - 1);
        y = std::clamp(y, 0, height - 1);
        return static_cast<double>(height_um[static_cast<size_t>(y) * width + x]);
    };
    tbb::parallel_for(0, height, [&](int y) {
        // One-sided at a border: the span is 1 texel there, 2 inside.
        const double dv_span = (std::min(y + 1, height - 1) - std::max(y - 1, 0)) * texel_size_um;
        for (int x = 0; x < width; ++x) {
            const double du_span =
                (std::min(x + 1, width - 1) - std::max(x - 1, 0)) * texel_size_um;
            const double dh_du = du_span > 0 ? scale * (h(x + 1, y) - h(x - 1, y)) / du_span : 0.0;
            // Rows run downwards while v runs upwards: the row above (y - 1) is at larger v.
            const double dh_dv = dv_span > 0 ? scale * (h(x, y - 1) - h(x, y + 1)) / dv_span : 0.0;
            const double len = std::sqrt(dh_du * dh_du + dh_dv * dh_dv + 1.0);
            float* n = &out[(static_cast<size_t>(y) * width + x) * 3];
            n[0] = static_cast<float>(0.5 - 0.5 * dh_du / len);
            n[1] = static_cast<float>(0.5 - 0.5 * dh_dv / len);
            n[2] = static_cast<float>(0.5 + 0.5 / len);
        }
    });
    return out;
}

}  // namespace patina::texgen
