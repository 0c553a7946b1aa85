// patina/shading/vec.h — small vectors and scalar helpers for shading plugins.
//
// Header-only, C++20, no dependencies beyond <patina/abi.h> and the standard library, so a
// plugin built out of tree can use it. Everything lives in namespace patina::shading.
//
// Vec2 and Vec3 are plain float vectors that convert implicitly to and from the ABI's
// PatinaVec2 / PatinaVec3, so a plugin can write
//
//     Vec3 wm = normalize(Vec3(wo) + Vec3(wi));   // wo, wi arrive as PatinaVec3
//     out->wi = reflect(wo, wm);                  // and leave as PatinaVec3
//
// Conventions:
//   - Nothing here allocates or throws; every function is safe to call from many threads.
//   - normalize() of a zero vector returns the zero vector rather than NaN; callers that
//     need a direction check length_squared() first.
//   - safe_sqrt / safe_acos / safe_asin clamp their argument into the domain, so a value a
//     rounding error outside it (1 + 1e-7) gives the limit instead of NaN.
#pragma once

#include <patina/abi.h>

#include <algorithm>
#include <cmath>

namespace patina::shading {

// ---------------------------------------------------------------------------------------
// Constants and scalar helpers
// ---------------------------------------------------------------------------------------

inline constexpr float kPi = 3.14159265358979323846f;
inline constexpr float kTwoPi = 6.28318530717958647692f;
inline constexpr float kPiOver2 = 1.57079632679489661923f;
inline constexpr float kPiOver4 = 0.78539816339744830962f;
inline constexpr float kInvPi = 0.31830988618379067154f;
inline constexpr float kInv2Pi = 0.15915494309189533577f;
inline constexpr float kInv4Pi = 0.07957747154594766788f;

/// x * x.
template <typename T> constexpr T sqr(T x)
{
    return x * x;
}

/// sqrt(max(x, 0)): no NaN for a value that rounding pushed slightly below zero.
inline float safe_sqrt(float x)
{
    return std::sqrt(std::max(x, 0.0f));
}
inline double safe_sqrt(double x)
{
    return std::sqrt(std::max(x, 0.0));
}

/// acos / asin with the argument clamped to [-1, 1].
inline float safe_acos(float x)
{
    return std::acos(std::clamp(x, -1.0f, 1.0f));
}
inline float safe_asin(float x)
{
    return std::asin(std::clamp(x, -1.0f, 1.0f));
}

/// True when x is neither NaN nor infinite.
inline bool is_finite(float x)
{
    return std::isfinite(x);
}

// ---------------------------------------------------------------------------------------
// Vec2
// ---------------------------------------------------------------------------------------

struct Vec2 {
    float x = 0.0f, y = 0.0f;

    constexpr Vec2() = default;
    constexpr Vec2(float x_, float y_) : x(x_), y(y_) {}
    constexpr Vec2(PatinaVec2 v) : x(v.x), y(v.y) {} // NOLINT: implicit by design
    constexpr operator PatinaVec2() const { return {x, y}; }

    constexpr float operator[](int i) const { return i == 0 ? x : y; }
    constexpr Vec2 operator-() const { return {-x, -y}; }
    constexpr Vec2& operator+=(Vec2 b)
    {
        x += b.x;
        y += b.y;
        return *this;
    }
    constexpr Vec2& operator-=(Vec2 b)
    {
        x -= b.x;
        y -= b.y;
        return *this;
    }
    constexpr Vec2& operator*=(float s)
    {
        x *= s;
        y *= s;
        return *this;
    }
};

constexpr Vec2 operator+(Vec2 a, Vec2 b)
{
    return {a.x + b.x, a.y + b.y};
}
constexpr Vec2 operator-(Vec2 a, Vec2 b)
{
    return {a.x - b.x, a.y - b.y};
}
constexpr Vec2 operator*(Vec2 a, float s)
{
    return {a.x * s, a.y * s};
}
constexpr Vec2 operator*(float s, Vec2 a)
{
    return {a.x * s, a.y * s};
}
constexpr Vec2 operator/(Vec2 a, float s)
{
    return {a.x / s, a.y / s};
}
constexpr float dot(Vec2 a, Vec2 b)
{
    return a.x * b.x + a.y * b.y;
}
constexpr float length_squared(Vec2 a)
{
    return dot(a, a);
}
inline float length(Vec2 a)
{
    return std::sqrt(length_squared(a));
}

// ---------------------------------------------------------------------------------------
// Vec3
// ---------------------------------------------------------------------------------------

struct Vec3 {
    float x = 0.0f, y = 0.0f, z = 0.0f;

    constexpr Vec3() = default;
    constexpr Vec3(float x_, float y_, float z_) : x(x_), y(y_), z(z_) {}
    constexpr Vec3(PatinaVec3 v) : x(v.x), y(v.y), z(v.z) {} // NOLINT: implicit by design
    constexpr operator PatinaVec3() const { return {x, y, z}; }

    constexpr float operator[](int i) const { return i == 0 ? x : (i == 1 ? y : z); }
    constexpr Vec3 operator-() const { return {-x, -y, -z}; }
    constexpr Vec3& operator+=(Vec3 b)
    {
        x += b.x;
        y += b.y;
        z += b.z;
        return *this;
    }
    constexpr Vec3& operator-=(Vec3 b)
    {
        x -= b.x;
        y -= b.y;
        z -= b.z;
        return *this;
    }
    constexpr Vec3& operator*=(float s)
    {
        x *= s;
        y *= s;
        z *= s;
        return *this;
    }
    constexpr Vec3& operator/=(float s)
    {
        x /= s;
        y /= s;
        z /= s;
        return *this;
    }
};

constexpr Vec3 operator+(Vec3 a, Vec3 b)
{
    return {a.x + b.x, a.y + b.y, a.z + b.z};
}
constexpr Vec3 operator-(Vec3 a, Vec3 b)
{
    return {a.x - b.x, a.y - b.y, a.z - b.z};
}
constexpr Vec3 operator*(Vec3 a, float s)
{
    return {a.x * s, a.y * s, a.z * s};
}
constexpr Vec3 operator*(float s, Vec3 a)
{
    return {a.x * s, a.y * s, a.z * s};
}
constexpr Vec3 operator/(Vec3 a, float s)
{
    return {a.x / s, a.y / s, a.z / s};
}
constexpr bool operator==(Vec3 a, Vec3 b)
{
    return a.x == b.x && a.y == b.y && a.z == b.z;
}

constexpr float dot(Vec3 a, Vec3 b)
{
    return a.x * b.x + a.y * b.y + a.z * b.z;
}
inline float abs_dot(Vec3 a, Vec3 b)
{
    return std::abs(dot(a, b));
}
constexpr Vec3 cross(Vec3 a, Vec3 b)
{
    return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x};
}
constexpr float length_squared(Vec3 a)
{
    return dot(a, a);
}
inline float length(Vec3 a)
{
    return std::sqrt(length_squared(a));
}

/// a / |a|; the zero vector stays zero (never NaN).
inline Vec3 normalize(Vec3 a)
{
    const float len2 = length_squared(a);
    return len2 > 0.0f ? a / std::sqrt(len2) : Vec3{};
}

/// v flipped, if needed, onto the side of n: dot(result, n) >= 0.
constexpr Vec3 face_forward(Vec3 v, Vec3 n)
{
    return dot(v, n) < 0.0f ? -v : v;
}

/// True when every component is finite.
inline bool is_finite(Vec3 a)
{
    return is_finite(a.x) && is_finite(a.y) && is_finite(a.z);
}

/// Two unit vectors b1, b2 completing the unit vector n to a right-handed orthonormal basis
/// (b1, b2, n), continuous everywhere except across n.z = 0's sign change.
inline void coordinate_system(Vec3 n, Vec3* b1, Vec3* b2)
{
    // Branchless ONB: Duff et al. 2017, "Building an Orthonormal Basis, Revisited",
    // JCGT 6(1), Listing 3
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z);
    const float b = n.x * n.y * a;
    *b1 = Vec3(1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x);
    *b2 = Vec3(b, sign + n.y * n.y * a, -n.y);
}

} // namespace patina::shading
