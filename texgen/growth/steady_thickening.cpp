#include "texgen/growth/steady_thickening.h"

#include "texgen/growth/solid_noise.h"

#include "core/sampling.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen {
namespace {

    constexpr uint64_t kStreamSamples = 0x7374736d706c6573ULL; // "stsmples"

    inline double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }

    /// The thickness of sample point (i, j, k) of the grid.
    inline double sample_thickness(uint64_t seed, int64_t i, int64_t j, int64_t k)
    {
        const uint64_t h = hash_values(seed, kStreamSamples, static_cast<uint64_t>(i),
                                       hash_values(static_cast<uint64_t>(j),
                                                   static_cast<uint64_t>(k)));
        const double u = static_cast<double>(h >> 11) * 0x1p-53;
        return 1.0 + kSteadyThickeningSpread * (2.0 * u - 1.0);
    }

    /// The sample points' thicknesses interpolated at p (in grid units), with weights that
    /// are flat at each point so that the map has no creases along the grid.
    double interpolate(uint64_t seed, double x, double y, double z)
    {
        const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
        const auto i = static_cast<int64_t>(fx), j = static_cast<int64_t>(fy),
                   k = static_cast<int64_t>(fz);
        const double wx = fade(x - fx), wy = fade(y - fy), wz = fade(z - fz);
        double sum = 0.0;
        for (int c = 0; c < 8; ++c) {
            const int dx = c & 1, dy = (c >> 1) & 1, dz = (c >> 2) & 1;
            const double w = (dx ? wx : 1.0 - wx) * (dy ? wy : 1.0 - wy) * (dz ? wz : 1.0 - wz);
            if (w > 0.0)
                sum += w * sample_thickness(seed, i + dx, j + dy, k + dz);
        }
        return sum;
    }

} // namespace

std::vector<float> steady_thickening_pattern(const Lattice& lattice, const GrowthParameters& p,
                                             uint64_t seed)
{
    if (!(p.st_spacing > 0))
        throw std::invalid_argument("ST: parameters must be resolved first");
    const SolidNoise noise(seed);
    const double grid = 1.0 / p.st_spacing;
    const double fine = 4.0 / p.st_spacing;
    std::vector<float> out(lattice.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 1 << 12),
                      [&](const tbb::blocked_range<size_t>& r) {
        for (size_t n = r.begin(); n != r.end(); ++n) {
            const auto& x = lattice.position[n];
            const double v = interpolate(seed, x.x * grid, x.y * grid, x.z * grid) +
                             p.noise_amplitude * noise.noise(x.x * fine, x.y * fine, x.z * fine);
            out[n] = static_cast<float>(std::max(0.0, v));
        }
    });
    return out;
}

} // namespace patina::texgen
