#include "texgen/wetness/wetness_baker.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace patina::texgen {

namespace {

    constexpr float kDegree = std::numbers::pi_v<float> / 180.0f;

    Imath::V3f unit(const Imath::V3f& v, const char* option)
    {
        const float length = v.length();
        if (!(length > 0.0f) || !std::isfinite(length))
            throw std::runtime_error(fmt::format("{} ({}, {}, {}) must be a finite non-zero vector",
                                                 option, v.x, v.y, v.z));
        return v / length;
    }

} // namespace

void WetnessParameters::validate() const
{
    unit(rain_direction, "--rain-dir");
    unit(up, "--up");
    const auto check = [](bool ok, const char* option, double value, const char* range) {
        if (!ok)
            throw std::runtime_error(fmt::format("{} {} must be {}", option, value, range));
    };
    check(spread_deg >= 0.0f && spread_deg < 90.0f, "--spread-deg", spread_deg, "in [0, 90)");
    check(inclination_power >= 0.0f && std::isfinite(inclination_power), "--inclination-power",
          inclination_power, ">= 0");
    check(rays >= 1, "--rays", rays, ">= 1");
    check(max_distance > 0.0f, "--max-distance", max_distance, "> 0");
    check(drying >= 0.0f && drying <= 1.0f, "--drying", drying, "in [0, 1]");
    check(exposure_scale >= 0.0f && std::isfinite(exposure_scale), "--exposure-scale",
          exposure_scale, ">= 0 (0: the map's maximum)");
    check(base_height >= 0.0f && std::isfinite(base_height), "--base-height", base_height,
          ">= 0 (0: off)");
    check(base_amount >= 0.0f && std::isfinite(base_amount), "--base-amount", base_amount, ">= 0");
    if (base_level)
        check(std::isfinite(*base_level), "--base-level", *base_level, "finite");
}

float lowest_along(const TriangleMesh& mesh, const Imath::V3f& up)
{
    float lowest = std::numeric_limits<float>::infinity();
    for (const Imath::V3f& p : mesh.positions)
        lowest = std::min(lowest, p.dot(up));
    return lowest;
}

WetnessBaker::WetnessBaker(const EmbreeScene& scene, const TriangleMesh& target,
                           const WetnessParameters& parameters,
                           const std::filesystem::path& ocio_config)
    : scene_(scene), p_((parameters.validate(), parameters)),
      cone_(parameters.rain_direction, parameters.spread_deg * kDegree),
      up_(unit(parameters.up, "--up"))
{
    base_level_ = p_.base_level ? *p_.base_level : lowest_along(target, up_);
    if (!p_.exposure_map.empty()) {
        std::vector<std::string> names = {"exposure", "irradiance"};
        if (!p_.exposure_channel.empty())
            names = {p_.exposure_channel};
        exposure_ =
            std::make_unique<SurfaceMap>(p_.exposure_map, names, "exposure map", ocio_config);
        exposure_scale_ = p_.exposure_scale > 0.0f ? p_.exposure_scale : exposure_->maximum();
    }
}

size_t WetnessBaker::rays_per_sample(size_t group_size) const
{
    if (cone_.spread() == 0.0f)
        return 1;
    // The per-texel budget is split over the texel's samples, at least one ray each.
    const size_t n = std::max<size_t>(group_size, 1);
    return std::max<size_t>(1, (static_cast<size_t>(p_.rays) + n - 1) / n);
}

void WetnessBaker::evaluate(const SurfaceSample& s, size_t group_size, Pcg32& rng, float* out) const
{
    // Rain caught, with visibility: Dorsey et al. 1999 §6.
    const float rain = directional_catch(
        scene_, s, cone_, static_cast<int>(rays_per_sample(group_size)), p_.max_distance, rng);
    // Inclined surfaces shed water: D&H 1996 §5.2 ("decreases the average wetness of
    // inclined surfaces"), as a power of the cosine to the up axis.
    const float incline = std::pow(std::max(0.0f, s.N.dot(up_)), p_.inclination_power);
    // Water collecting near the base: D&H 1996 §5.2 (the "base" curve), a linear ramp.
    float base = 0.0f;
    if (p_.base_height > 0.0f)
        base =
            p_.base_amount * std::max(0.0f, 1.0f - (s.P.dot(up_) - base_level_) / p_.base_height);
    // Drying by exposure: D&H 1996 §5.2-5.3 (exposed, sunny areas are dryer).
    float dry = 1.0f;
    if (exposure_) {
        const float e = exposure_scale_ > 0.0f ? exposure_->at(s.uv) / exposure_scale_ : 0.0f;
        dry = 1.0f - p_.drying * std::clamp(e, 0.0f, 1.0f);
    }
    out[0] = std::clamp((rain * incline + base) * dry, 0.0f, 1.0f);
}

Metadata WetnessBaker::resolved_parameters() const
{
    Metadata m = {{"base_level", base_level_}};
    if (exposure_)
        m.emplace_back("exposure_scale", exposure_scale_);
    return m;
}

} // namespace patina::texgen
