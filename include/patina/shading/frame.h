// patina/shading/frame.h — the local shading frame and the geometry of one interface.
//
// A Patina BSDF works in the local shading frame (abi.h §3): +z is the shading normal, x and
// y follow dPdu and its orthonormal complement. In that frame a unit direction w has
//
//     cos θ = w.z,   sin θ = sqrt(1 − w.z²),   cos φ = w.x / sin θ,   sin φ = w.y / sin θ
//
// and the functions below read these straight from the components (pbrt-v4 §9.1, "BSDF
// Representation", the spherical-coordinate conventions of the BxDF interface). A direction
// with z < 0 lies below the surface; every function here accepts either hemisphere.
//
// reflect() and refract() work about any normal n (a microfacet normal, for instance):
//   - reflect(wo, n) mirrors wo about n; both point away from the surface.
//   - refract(wi, n, eta, &etap, &wt) bends wi through an interface whose relative index
//     η = η_below / η_above is given for the side n points to; if wi lies on the other side
//     (dot(wi, n) < 0) the interface is flipped and *etap receives 1/η. It returns false on
//     total internal reflection.
//
// Frame turns a world-space normal (and optional tangent) into a local frame, for plugins
// that receive world-space vectors from the host (attributes, textures of normals).
#pragma once

#include <patina/shading/vec.h>

namespace patina::shading {

// ---------------------------------------------------------------------------------------
// Spherical coordinates in the local frame (pbrt-v4 §3.8.3, "Spherical Coordinates")
// ---------------------------------------------------------------------------------------

inline float cos_theta(Vec3 w)
{
    return w.z;
}
inline float cos2_theta(Vec3 w)
{
    return w.z * w.z;
}
inline float abs_cos_theta(Vec3 w)
{
    return std::abs(w.z);
}
inline float sin2_theta(Vec3 w)
{
    return std::max(0.0f, 1.0f - cos2_theta(w));
}
inline float sin_theta(Vec3 w)
{
    return std::sqrt(sin2_theta(w));
}
/// tan θ; infinite at the horizon (cos θ = 0).
inline float tan_theta(Vec3 w)
{
    return sin_theta(w) / cos_theta(w);
}
/// tan² θ; infinite at the horizon.
inline float tan2_theta(Vec3 w)
{
    return sin2_theta(w) / cos2_theta(w);
}

/// cos φ; 1 along the normal, where φ is undefined.
inline float cos_phi(Vec3 w)
{
    const float s = sin_theta(w);
    return s == 0.0f ? 1.0f : std::clamp(w.x / s, -1.0f, 1.0f);
}

/// sin φ; 0 along the normal.
inline float sin_phi(Vec3 w)
{
    const float s = sin_theta(w);
    return s == 0.0f ? 0.0f : std::clamp(w.y / s, -1.0f, 1.0f);
}

/// True when a and b lie strictly on the same side of the surface (a direction exactly in
/// the tangent plane belongs to neither side).
inline bool same_hemisphere(Vec3 a, Vec3 b)
{
    return a.z * b.z > 0.0f;
}

/// Unit vector (sin θ cos φ, sin θ sin φ, cos θ).
inline Vec3 spherical_direction(float sin_theta_, float cos_theta_, float phi)
{
    const float s = std::clamp(sin_theta_, -1.0f, 1.0f);
    return Vec3(s * std::cos(phi), s * std::sin(phi), std::clamp(cos_theta_, -1.0f, 1.0f));
}

// ---------------------------------------------------------------------------------------
// Reflection and refraction about a normal
// ---------------------------------------------------------------------------------------

/// Mirror direction of wo about n (both pointing away from the surface).
inline Vec3 reflect(Vec3 wo, Vec3 n)
{
    // Law of specular reflection, vector form: pbrt-v4 §9.3 ("The Law of Specular Reflection")
    return -wo + 2.0f * dot(wo, n) * n;
}

/// Refracted direction of wi through an interface with normal n and relative index
/// eta = η_t / η_i for light arriving on the side n points to. Writes the relative index
/// actually used (1/eta when wi lies on the other side of n) to *etap when etap is not
/// null. Returns false, leaving *wt unchanged, on total internal reflection.
inline bool refract(Vec3 wi, Vec3 n, float eta, float* etap, Vec3* wt)
{
    float cos_theta_i = dot(n, wi);
    // Flip the interface orientation when wi arrives from below n
    if (cos_theta_i < 0.0f) {
        eta = 1.0f / eta;
        cos_theta_i = -cos_theta_i;
        n = -n;
    }
    // Snell's law, sin θt = sin θi / η: pbrt-v4 §9.3 ("Snell's Law")
    const float sin2_theta_i = std::max(0.0f, 1.0f - sqr(cos_theta_i));
    const float sin2_theta_t = sin2_theta_i / sqr(eta);
    if (sin2_theta_t >= 1.0f)
        return false;
    const float cos_theta_t = safe_sqrt(1.0f - sin2_theta_t);
    // Transmitted direction wt = −wi/η + (cos θi/η − cos θt) n: pbrt-v4 §9.3 ("Snell's Law")
    *wt = -wi / eta + (cos_theta_i / eta - cos_theta_t) * n;
    if (etap)
        *etap = eta;
    return true;
}

// ---------------------------------------------------------------------------------------
// Frame: local <-> world
// ---------------------------------------------------------------------------------------

/// An orthonormal frame (x, y, z); to_local() expresses a world vector in it.
struct Frame {
    Vec3 x{1.0f, 0.0f, 0.0f}, y{0.0f, 1.0f, 0.0f}, z{0.0f, 0.0f, 1.0f};

    /// Any frame with the unit normal n as z.
    static Frame from_z(Vec3 n)
    {
        Frame f;
        f.z = n;
        coordinate_system(n, &f.x, &f.y);
        return f;
    }

    /// The shading frame of abi.h: z = unit normal n, x = tangent t made orthogonal to n
    /// (Gram-Schmidt), y = z × x. Falls back to from_z when t is parallel to n or zero.
    static Frame from_xz(Vec3 t, Vec3 n)
    {
        const Vec3 x = normalize(t - dot(t, n) * n);
        if (length_squared(x) == 0.0f)
            return from_z(n);
        Frame f;
        f.z = n;
        f.x = x;
        f.y = cross(n, x);
        return f;
    }

    Vec3 to_local(Vec3 v) const { return {dot(v, x), dot(v, y), dot(v, z)}; }
    Vec3 from_local(Vec3 v) const { return v.x * x + v.y * y + v.z * z; }
};

} // namespace patina::shading
