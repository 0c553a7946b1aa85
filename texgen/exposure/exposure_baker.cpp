#include "texgen/exposure/exposure_baker.h"

#include <vector>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen {

namespace {

constexpr double kPi = 3.14159265358979323846;

// A unit direction uniformly distributed in the cone of half-angle acos(cos_max) about the
// unit vector `axis` (pbrt-v4 §A.5.4, uniform cone sampling).
Imath::V3f sample_cone(const Imath::V3f& axis, float cos_max, float u0, float u1)
{
    const float cos_theta = 1.0f - u0 * (1.0f - cos_max);
    const float sin_theta = std::sqrt(std::max(0.0f, 1.0f - cos_theta * cos_theta));
    const float phi = static_cast<float>(2.0 * kPi) * u1;
    // Orthonormal basis about the axis (Duff et al. 2017, "Building an Orthonormal Basis,
    // Revisited").
    const float sign = std::copysign(1.0f, axis.z);
    const float a = -1.0f / (sign + axis.z);
    const float b = axis.x * axis.y * a;
    const Imath::V3f t(1.0f + sign * axis.x * axis.x * a, sign * b, -sign * axis.x);
    const Imath::V3f bt(b, sign + axis.y * axis.y * a, -axis.y);
    Imath::V3f w = axis * cos_theta + (t * std::cos(phi) + bt * std::sin(phi)) * sin_theta;
    return w.normalize();
}

}  // namespace

ExposureBaker::ExposureBaker(const EmbreeScene& scene, const ExposureSky& sky,
                             const ExposureOptions& options)
    : scene_(scene), sky_(sky), options_(options)
{
    if (!(options.max_distance > 0.0f))
        throw std::runtime_error("--max-distance must be positive");
    if (!(options.sun_diameter_deg >= 0.0f && options.sun_diameter_deg < 10.0f))
        throw std::runtime_error("the sun's angular diameter must be in [0, 10) degrees");
    if (options.average) {
        if (!(sky.duration_s > 0.0))
            throw std::runtime_error("--average needs a period of positive length");
        scale_ = 1.0 / sky.duration_s;
    }
    cos_sun_radius_ = static_cast<float>(std::cos(0.5 * options.sun_diameter_deg * kPi / 180.0));

    // H: the sun bins seen from flat open ground, the sky cells at their centres.
    for (const SunBin& bin : sky.sun_bins)
        horizontal_ += std::max(0.0, bin.weighted.y);
    const int res = sky.sky_resolution;
    for (int i = 0; i < res; ++i)
        for (int j = 0; j < res; ++j) {
            const Imath::V3d w = hemisphere_direction((j + 0.5) / res, (i + 0.5) / res);
            horizontal_ += sky.sky_radiance_time[static_cast<size_t>(i) * res + j] *
                           std::max(0.0, w.y) * sky.cell_solid_angle;
        }
}

std::vector<std::string> ExposureBaker::channels() const
{
    std::vector<std::string> names{options_.average ? "irradiance" : "exposure"};
    if (options_.components) {
        names.push_back("direct");
        names.push_back("sky");
    }
    names.push_back("relative");
    return names;
}

size_t ExposureBaker::rays_per_sample(size_t group_size) const
{
    (void)group_size;
    return sky_.sun_bins.size() + static_cast<size_t>(sky_.non_empty_sky_cells);
}

void ExposureBaker::evaluate(const SurfaceSample& s, size_t group_size, Pcg32& rng,
                             float* out) const
{
    (void)group_size;
    const Imath::V3d n(s.N.x, s.N.y, s.N.z);
    // Every shadow ray of the sample, with the energy it carries if unoccluded, traced as one
    // Embree stream. is_sun[i] says which term a ray belongs to.
    thread_local std::vector<ShadowRay> rays;
    thread_local std::vector<double> weights;
    thread_local std::vector<uint8_t> is_sun, visible;
    rays.clear();
    weights.clear();
    is_sun.clear();
    const auto add = [&](const Imath::V3f& dir, double weight, bool sun) {
        // A direction below the facet's geometric plane would go through the surface itself.
        if (s.Ng.dot(dir) <= 0.0f)
            return;
        rays.push_back({offset_ray_origin(s.P, s.Ng, dir), dir, options_.max_distance});
        weights.push_back(weight);
        is_sun.push_back(sun ? 1 : 0);
    };

    // Direct sun: one shadow ray per bin the surface faces, jittered over the solar disc.
    for (const SunBin& bin : sky_.sun_bins) {
        const double facing = n.dot(bin.weighted);
        if (facing <= 0.0)
            continue;
        const float u0 = rng.uniform_float();
        const float u1 = rng.uniform_float();
        const Imath::V3f dir = cos_sun_radius_ < 1.0f
                                   ? sample_cone(bin.direction, cos_sun_radius_, u0, u1)
                                   : bin.direction;
        add(dir, facing, true);
    }

    // Sky: one ray per cell, uniform within the cell (stratified over the hemisphere).
    const int res = sky_.sky_resolution;
    for (int i = 0; i < res; ++i)
        for (int j = 0; j < res; ++j) {
            const double radiance_time = sky_.sky_radiance_time[static_cast<size_t>(i) * res + j];
            if (radiance_time <= 0.0)
                continue;
            const double u = (j + rng.uniform_double()) / res;
            const double v = (i + rng.uniform_double()) / res;
            const Imath::V3d w = hemisphere_direction(u, v);
            const double cos_n = n.dot(w);
            if (cos_n <= 0.0)
                continue;
            const Imath::V3f dir(static_cast<float>(w.x), static_cast<float>(w.y),
                                 static_cast<float>(w.z));
            add(dir, radiance_time * cos_n * sky_.cell_solid_angle, false);
        }

    visible.resize(rays.size());
    scene_.trace_shadow_rays(rays, visible);
    double direct = 0.0, sky = 0.0;
    for (size_t r = 0; r < rays.size(); ++r)
        if (visible[r])
            (is_sun[r] ? direct : sky) += weights[r];

    out[0] = static_cast<float>((direct + sky) * scale_);
    if (options_.components) {
        out[1] = static_cast<float>(direct * scale_);
        out[2] = static_cast<float>(sky * scale_);
    }
    out[options_.components ? 3 : 1] =
        horizontal_ > 0.0 ? static_cast<float>((direct + sky) / horizontal_) : 0.0f;
}

}  // namespace patina::texgen
