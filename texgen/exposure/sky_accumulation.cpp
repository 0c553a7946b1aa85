#include "texgen/exposure/sky_accumulation.h"

#include "core/cancel.h"
#include "core/progress.h"

#include <patina/shading/sampling.h>

#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>

namespace patina::texgen {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kRadToDeg = 180.0 / kPi;
// Sun-direction bins within which the sky's luminance distribution is taken as fixed.
constexpr double kSkySunBinDeg = 2.0;
// Quadrature points per sky cell, along each axis.
constexpr int kCellPoints = 4;

// Direction bins on the sphere: rings of `size_deg` in zenith angle, each cut into
// azimuth segments of about `size_deg` of arc at the ring's middle.
struct DirectionBinning {
    double size_deg;

    int64_t key(const Imath::V3d& w) const
    {
        const double horizontal = std::sqrt(w.x * w.x + w.z * w.z);
        const double zenith = std::atan2(horizontal, w.y) * kRadToDeg;  // 0..180
        double azimuth = std::atan2(w.x, -w.z) * kRadToDeg;             // from north, east +
        if (azimuth < 0.0)
            azimuth += 360.0;
        const int rings = static_cast<int>(std::ceil(180.0 / size_deg));
        const int ring = std::min(static_cast<int>(zenith / size_deg), rings - 1);
        const double middle = (ring + 0.5) * size_deg / kRadToDeg;
        const int segments =
            std::max(1, static_cast<int>(std::ceil(360.0 * std::sin(middle) / size_deg)));
        const int segment = std::min(static_cast<int>(azimuth / 360.0 * segments), segments - 1);
        return static_cast<int64_t>(ring) * 1000000 + segment;
    }
};

struct WeightedDirection {
    double weight = 0;
    Imath::V3d sum{0, 0, 0};
};

}  // namespace

Imath::V3d hemisphere_direction(double u, double v)
{
    const shading::Vec2 d = shading::sample_uniform_disk_concentric(
        shading::Vec2(static_cast<float>(u), static_cast<float>(v)));
    // Lambert equal-area: disk radius r -> cos(zenith) = 1 - r^2, so uniform area on the
    // disk is uniform solid angle on the hemisphere (pbrt-v4 §A.5.2 / §3.8.3).
    const double x = d.x, y = d.y;
    const double r2 = std::min(1.0, x * x + y * y);
    const double scale = std::sqrt(std::max(0.0, 2.0 - r2));
    Imath::V3d w(x * scale, 1.0 - r2, y * scale);
    return w.normalize();
}

ExposureSky accumulate_exposure(const ExposurePeriod& period, const CieSky& sky,
                                const AccumulationOptions& options)
{
    if (!(options.sun_bin_deg > 0.0 && options.sun_bin_deg <= 10.0))
        throw std::runtime_error("--sun-bins-deg must be in (0, 10] degrees, got " +
                                 std::to_string(options.sun_bin_deg));
    if (options.sky_cells < 4)
        throw std::runtime_error("--sky-samples must be at least 4, got " +
                                 std::to_string(options.sky_cells));
    ExposureSky out;
    out.duration_s = period.duration_s;
    const int n = std::max(2, static_cast<int>(std::lround(std::sqrt(options.sky_cells))));
    out.sky_resolution = n;
    out.cell_solid_angle = 2.0 * kPi / (static_cast<double>(n) * n);
    out.sky_radiance_time.assign(static_cast<size_t>(n) * n, 0.0);

    // Sun energy into fine direction bins; diffuse energy into coarse bins of the sun's
    // direction (the sky's shape follows the sun).
    const DirectionBinning sun_binning{options.sun_bin_deg};
    const DirectionBinning sky_binning{kSkySunBinDeg};
    std::map<int64_t, WeightedDirection> sun_bins, sky_bins;
    Progress progress(period.step_bound, !options.progress, "exposure: sun path");
    size_t visited = 0;
    period.for_each_step([&](const IrradianceStep& step) {
        if ((++visited & 4095) == 0) {
            progress.step(4096);
            throw_if_cancelled();
        }
        out.steps += step.dni > 0.0 || step.dhi > 0.0;
        if (step.dni > 0.0) {
            const double e = step.dni * step.duration_s;
            WeightedDirection& b = sun_bins[sun_binning.key(step.sun)];
            b.weight += e;
            b.sum += step.sun * e;
            out.direct_normal += e;
        }
        if (step.dhi > 0.0) {
            const double e = step.dhi * step.duration_s;
            WeightedDirection& b = sky_bins[sky_binning.key(step.sun)];
            b.weight += e;
            b.sum += step.sun * e;
            out.diffuse_horizontal += e;
        }
    });
    progress.finish();
    for (const auto& [key, b] : sun_bins) {
        SunBin bin;
        bin.weighted = b.sum;
        bin.energy = b.weight;
        const Imath::V3d mean = b.sum.length() > 0.0 ? b.sum.normalized() : Imath::V3d(0, 1, 0);
        bin.direction = Imath::V3f(static_cast<float>(mean.x), static_cast<float>(mean.y),
                                   static_cast<float>(mean.z));
        bin.direction.normalize();
        out.sun_bins.push_back(bin);
    }

    // Quadrature points of every cell (midpoints of a 4 x 4 grid in the square, equal
    // solid angle each) and the cell's mean cosine to the zenith.
    const size_t cells = static_cast<size_t>(n) * n;
    std::vector<Imath::V3d> points(cells * kCellPoints * kCellPoints);
    std::vector<double> mean_cos(cells, 0.0);
    for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
            const size_t c = static_cast<size_t>(i) * n + j;
            for (int a = 0; a < kCellPoints; ++a)
                for (int b = 0; b < kCellPoints; ++b) {
                    const double u = (j + (b + 0.5) / kCellPoints) / n;
                    const double v = (i + (a + 0.5) / kCellPoints) / n;
                    const Imath::V3d w = hemisphere_direction(u, v);
                    points[(c * kCellPoints + a) * kCellPoints + b] = w;
                    mean_cos[c] += w.y / (kCellPoints * kCellPoints);
                }
        }

    // Per sky bin: the relative luminance averaged over each cell, scaled so that
    // sum_c L_c cos_c Omega = DHI (the normalisation of CIE S 011 against the measured or
    // modelled diffuse horizontal irradiance), times the bin's duration-weighted DHI.
    std::vector<double> relative(cells);
    for (const auto& [key, b] : sky_bins) {
        const Imath::V3d sun = b.sum.length() > 0.0 ? b.sum.normalized() : Imath::V3d(0, 1, 0);
        double horizontal = 0.0;
        for (size_t c = 0; c < cells; ++c) {
            double sum = 0.0;
            for (int k = 0; k < kCellPoints * kCellPoints; ++k)
                sum += relative_luminance(sky, points[c * kCellPoints * kCellPoints + k], sun);
            relative[c] = sum / (kCellPoints * kCellPoints);
            horizontal += relative[c] * mean_cos[c] * out.cell_solid_angle;
        }
        if (!(horizontal > 0.0))
            continue;
        const double scale = b.weight / horizontal;  // zenith radiance-time, J/(m^2 sr)
        for (size_t c = 0; c < cells; ++c)
            out.sky_radiance_time[c] += scale * relative[c];
    }
    for (double r : out.sky_radiance_time)
        out.non_empty_sky_cells += r > 0.0 ? 1 : 0;
    return out;
}

}  // namespace patina::texgen
