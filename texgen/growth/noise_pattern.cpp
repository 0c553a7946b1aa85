#include "texgen/growth/noise_pattern.h"

#include "texgen/growth/solid_noise.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <stdexcept>

namespace patina::texgen {

std::vector<float> noise_pattern(const Lattice& lattice, const GrowthParameters& p,
                                 uint64_t seed, bool turbulence)
{
    if (!(p.feature_size > 0))
        throw std::invalid_argument("noise: parameters must be resolved first");
    const SolidNoise noise(seed);
    const double scale = 1.0 / p.feature_size;
    std::vector<float> out(lattice.size());
    tbb::parallel_for(tbb::blocked_range<size_t>(0, out.size(), 1 << 12),
                      [&](const tbb::blocked_range<size_t>& r) {
        for (size_t i = r.begin(); i != r.end(); ++i) {
            const auto& x = lattice.position[i];
            const double px = x.x * scale, py = x.y * scale, pz = x.z * scale;
            const double v = turbulence ? noise.turbulence(px, py, pz, p.octaves)
                                        : 0.5 + 0.5 * noise.noise(px, py, pz);
            out[i] = static_cast<float>(std::clamp(v, 0.0, 1.0));
        }
    });
    return out;
}

} // namespace patina::texgen
