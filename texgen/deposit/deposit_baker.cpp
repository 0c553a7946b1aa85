#include "texgen/deposit/deposit_baker.h"

#include "texgen/deposit/source_visibility.h"
#include "texgen/wetness/directional_catch.h"

#include <patina/shading/sampling.h>

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen {

void DepositParameters::validate() const
{
    const auto check = [](bool ok, const char* option, double value, const char* range) {
        if (!ok)
            throw std::runtime_error(fmt::format("{} {} must be {}", option, value, range));
    };
    check(rays >= 1, "--rays", rays, ">= 1");
    check(max_distance > 0.0f, "--max-distance", max_distance, "> 0");
    check(access_rays >= 1, "--access-rays", access_rays, ">= 1");
    check(access_distance >= 0.0f && std::isfinite(access_distance), "--access-distance",
          access_distance, ">= 0 (0: a tenth of the scene's size)");
    check(accessibility_power >= 0.0f && std::isfinite(accessibility_power),
          "--accessibility-power", accessibility_power, ">= 0");
    check(accessibility_weight >= 0.0f && std::isfinite(accessibility_weight),
          "--accessibility-weight", accessibility_weight, ">= 0");
    check(visibility_weight >= 0.0f && std::isfinite(visibility_weight), "--visibility-weight",
          visibility_weight, ">= 0");
    if (sources.empty() && uses_visibility())
        throw std::runtime_error("deposit: no deposit source: give --source or --sources FILE "
                                 "(or --visibility-weight 0 for accessibility alone)");
}

DepositBaker::DepositBaker(const EmbreeScene& scene, const Imath::Box3f& bounds,
                           const DepositParameters& parameters,
                           const std::filesystem::path& ocio_config)
    : scene_(scene), p_((parameters.validate(), parameters))
{
    access_distance_ = p_.access_distance;
    if (access_distance_ == 0.0f)
        access_distance_ = bounds.isEmpty() ? 1.0f : 0.1f * (bounds.max - bounds.min).length();
    if (!p_.accessibility_map.empty() && p_.uses_accessibility())
        accessibility_ = std::make_unique<SurfaceMap>(
            p_.accessibility_map, std::vector<std::string>{p_.accessibility_channel},
            "accessibility map", ocio_config);
}

int DepositBaker::split(int per_texel, size_t group_size) const
{
    // A per-texel budget split over the texel's samples, at least one ray each.
    const size_t n = std::max<size_t>(group_size, 1);
    return static_cast<int>(std::max<size_t>(1, (static_cast<size_t>(per_texel) + n - 1) / n));
}

size_t DepositBaker::rays_per_sample(size_t group_size) const
{
    size_t rays = 0;
    if (p_.uses_visibility())
        rays += p_.sources.size() * static_cast<size_t>(split(p_.rays, group_size));
    if (p_.uses_accessibility() && !accessibility_)
        rays += static_cast<size_t>(split(p_.access_rays, group_size));
    return rays;
}

float DepositBaker::accessibility(const SurfaceSample& s, size_t group_size, Pcg32& rng) const
{
    if (accessibility_)
        return std::clamp(accessibility_->at(s.uv), 0.0f, 1.0f);
    // Inline estimate: cosine-weighted ambient occlusion within access_distance; rays that
    // would leave below the geometric surface count as blocked.
    Imath::V3f t, b;
    orthonormal_basis(s.N, &t, &b);
    const int rays = split(p_.access_rays, group_size);
    int open = 0;
    for (int i = 0; i < rays; ++i) {
        const Imath::V2f u = jittered_sample(i, rays, rng);
        const shading::Vec3 l = shading::sample_cosine_hemisphere(shading::Vec2(u.x, u.y));
        const Imath::V3f w = l.x * t + l.y * b + l.z * s.N;
        if (s.Ng.dot(w) <= 0.0f)
            continue;
        if (!scene_.occluded(offset_ray_origin(s.P, s.Ng, w), w, 0.0f, access_distance_))
            ++open;
    }
    return static_cast<float>(open) / static_cast<float>(rays);
}

float DepositBaker::visibility(const SurfaceSample& s, size_t group_size, Pcg32& rng) const
{
    const int rays = split(p_.rays, group_size);
    double sum = 0.0;
    for (const DepositSource& source : p_.sources)
        sum += source.strength * source_visibility(scene_, s, source, rays, p_.max_distance, rng);
    return static_cast<float>(std::min(sum, 1.0));
}

void DepositBaker::evaluate(const SurfaceSample& s, size_t group_size, Pcg32& rng, float* out) const
{
    // Accessibility combined with visibility to deposit sources: Dorsey et al. 1999 §6.
    const float hidden =
        p_.uses_accessibility()
            ? std::pow(1.0f - accessibility(s, group_size, rng), p_.accessibility_power)
            : 0.0f;
    const float seen = p_.uses_visibility() ? visibility(s, group_size, rng) : 0.0f;
    const float value = p_.combine == DepositParameters::Combine::Product
                            ? hidden * seen
                            : p_.accessibility_weight * hidden + p_.visibility_weight * seen;
    out[0] = std::clamp(value, 0.0f, 1.0f);
}

} // namespace patina::texgen
