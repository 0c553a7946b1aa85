// patina/shading/sampling.h — warps from the unit square to disks, hemispheres and spheres.
//
// Each sample_* function maps a uniform u in [0,1)² to a point of the target domain; the
// matching *_pdf function is the density of that point with respect to area (disk) or
// solid angle (directions). Pairs are exact: the pdf is the density the warp produces,
// which is what a BSDF's pdf() must report (abi.h §3).
//
//     Vec3 wi = sample_cosine_hemisphere(u);            // z >= 0
//     float pdf = cosine_hemisphere_pdf(wi.z);          // = wi.z / π
//
// Hemisphere warps return directions about +z (z >= 0); a BSDF that must sample below the
// surface flips z. All functions are allocation-free and reentrant.
#pragma once

#include <patina/shading/vec.h>

namespace patina::shading {

/// Point on the unit disk, uniform in area, with low distortion (square rings to disk rings).
inline Vec2 sample_uniform_disk_concentric(Vec2 u)
{
    // Concentric map: Shirley & Chiu 1997, "A Low Distortion Map Between Disk and Square",
    // J. Graphics Tools 2(3), §3 (pbrt-v4 §A.5.1)
    const Vec2 uo(2.0f * u.x - 1.0f, 2.0f * u.y - 1.0f);
    if (uo.x == 0.0f && uo.y == 0.0f)
        return {};
    float r, theta;
    if (std::abs(uo.x) > std::abs(uo.y)) {
        r = uo.x;
        theta = kPiOver4 * (uo.y / uo.x);
    } else {
        r = uo.y;
        theta = kPiOver2 - kPiOver4 * (uo.x / uo.y);
    }
    return r * Vec2(std::cos(theta), std::sin(theta));
}

/// Point on the unit disk by polar coordinates r = sqrt(u.x), φ = 2π u.y (uniform in area).
inline Vec2 sample_uniform_disk_polar(Vec2 u)
{
    // Inversion of the disk's marginal cdf r²: pbrt-v4 §A.5.1
    const float r = std::sqrt(u.x);
    const float phi = kTwoPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi)};
}

/// Density of the uniform disk warps, per unit area: 1/π.
inline constexpr float uniform_disk_pdf()
{
    return kInvPi;
}

/// Direction in the +z hemisphere with density cos θ / π (Malley's method).
inline Vec3 sample_cosine_hemisphere(Vec2 u)
{
    // Malley's method, project a uniform disk point up to the hemisphere: pbrt-v4 §A.5.3
    const Vec2 d = sample_uniform_disk_concentric(u);
    const float z = safe_sqrt(1.0f - d.x * d.x - d.y * d.y);
    return {d.x, d.y, z};
}

/// Solid-angle density of sample_cosine_hemisphere: cos θ / π for cos θ > 0, else 0.
inline float cosine_hemisphere_pdf(float cos_theta)
{
    // p(ω) = cos θ / π: pbrt-v4 §A.5.3
    return cos_theta > 0.0f ? cos_theta * kInvPi : 0.0f;
}

/// Direction in the +z hemisphere, uniform in solid angle.
inline Vec3 sample_uniform_hemisphere(Vec2 u)
{
    // z uniform in [0,1] gives uniform solid angle (Archimedes): pbrt-v4 §A.5.2
    const float z = u.x;
    const float r = safe_sqrt(1.0f - z * z);
    const float phi = kTwoPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

/// Solid-angle density of sample_uniform_hemisphere: 1/(2π).
inline constexpr float uniform_hemisphere_pdf()
{
    return kInv2Pi;
}

/// Direction on the whole unit sphere, uniform in solid angle.
inline Vec3 sample_uniform_sphere(Vec2 u)
{
    // z uniform in [-1,1] gives uniform solid angle (Archimedes): pbrt-v4 §A.5.2
    const float z = 1.0f - 2.0f * u.x;
    const float r = safe_sqrt(1.0f - z * z);
    const float phi = kTwoPi * u.y;
    return {r * std::cos(phi), r * std::sin(phi), z};
}

/// Solid-angle density of sample_uniform_sphere: 1/(4π).
inline constexpr float uniform_sphere_pdf()
{
    return kInv4Pi;
}

} // namespace patina::shading
