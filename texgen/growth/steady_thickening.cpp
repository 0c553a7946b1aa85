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

    /// The thickness of sample point (i, j, k) of the grid.
    inline double sample_thickness(uint64_t seed, int64_t i, int64_t j, int64_t k)
    {
        const uint64_t h = hash_values(seed, kStreamSamples, static_cast<uint64_t>(i),
                                       hash_values(static_cast<uint64_t>(j),
                                                   static_cast<uint64_t>(k)));
        const double u = static_cast<double>(h >> 11) * 0x1p-53;
        return 1.0 + kSteadyThickeningSpread * (2.0 * u - 1.0);
    }

    /// Uniform cubic B-spline weights at t in [0, 1) for the points at -1, 0, 1, 2 (C2,
    /// so the map has neither creases nor flat spots along the sample grid).
    inline void bspline(double t, double w[4])
    {
        const double t2 = t * t, t3 = t2 * t;
        w[0] = (1.0 - 3.0 * t + 3.0 * t2 - t3) / 6.0;
        w[1] = (4.0 - 6.0 * t2 + 3.0 * t3) / 6.0;
        w[2] = (1.0 + 3.0 * t + 3.0 * t2 - 3.0 * t3) / 6.0;
        w[3] = t3 / 6.0;
    }

    /// The sample points' thicknesses smoothly interpolated at p (in grid units).
    /// Remembers the last cell's 4 x 4 x 4 points: neighbouring nodes mostly share a cell.
    class SampleInterpolator {
    public:
        explicit SampleInterpolator(uint64_t seed) : seed_(seed) {}

        double operator()(double x, double y, double z)
        {
            const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
            const auto i = static_cast<int64_t>(fx), j = static_cast<int64_t>(fy),
                       k = static_cast<int64_t>(fz);
            if (valid_ && i == i_ + 1 && j == j_ && k == k_) {
                // One cell on along x (the common case in a texture row): shift the points.
                for (int c = 0; c < 64; c += 4) {
                    point_[c] = point_[c + 1];
                    point_[c + 1] = point_[c + 2];
                    point_[c + 2] = point_[c + 3];
                    point_[c + 3] = sample_thickness(seed_, i + 2, j - 1 + ((c >> 2) & 3),
                                                     k - 1 + (c >> 4));
                }
                i_ = i;
            } else if (!valid_ || i != i_ || j != j_ || k != k_) {
                for (int c = 0; c < 64; ++c)
                    point_[c] = sample_thickness(seed_, i - 1 + (c & 3), j - 1 + ((c >> 2) & 3),
                                                 k - 1 + (c >> 4));
                i_ = i;
                j_ = j;
                k_ = k;
                valid_ = true;
            }
            double wx[4], wy[4], wz[4];
            bspline(x - fx, wx);
            bspline(y - fy, wy);
            bspline(z - fz, wz);
            double sum = 0.0;
            for (int c = 0; c < 64; ++c)
                sum += wx[c & 3] * wy[(c >> 2) & 3] * wz[c >> 4] * point_[c];
            return sum;
        }

    private:
        uint64_t seed_;
        bool valid_ = false;
        int64_t i_ = 0, j_ = 0, k_ = 0;
        double point_[64] = {};
    };

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
        SampleInterpolator interpolate(seed);
        for (size_t n = r.begin(); n != r.end(); ++n) {
            const auto& x = lattice.position[n];
            const double v = interpolate(x.x * grid, x.y * grid, x.z * grid) +
                             p.noise_amplitude * noise.noise(x.x * fine, x.y * fine, x.z * fine);
            out[n] = static_cast<float>(std::max(0.0, v));
        }
    });
    return out;
}

} // namespace patina::texgen
