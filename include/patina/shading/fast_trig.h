// patina/shading/fast_trig.h — cos and sin of the angles the square-to-disk and
// square-to-sphere warps need, by polynomials instead of libm's sincosf.
//
// The warps only ever ask for an angle a quarter turn wide around a known centre, so no
// argument reduction is needed beyond picking the quarter: Cephes' minimax polynomials for
// [-π/4, π/4]. Results differ from std::cos/std::sin by a few float ulps at most; the warps
// built on them keep their densities.
//
//     float c, s;
//     sincos_quarter(0.3f, c, s);      // |a| <= π/4
//     sincos_turn(0.8f, c, s);         // cos, sin of 2π t for t in [0, 1)
#pragma once

#include <patina/shading/vec.h>

#include <cstdint>
#include <cstring>

namespace patina::shading {

/// cos a and sin a for |a| <= π/4: the minimax polynomials of Cephes' single-precision
/// cosf and sinf for that range (Moshier, Cephes Math Library, sinf.c), relative error a
/// few 1e-8.
inline void sincos_quarter(float a, float& c, float& s)
{
    const float z = a * a;
    c = ((2.443315711809948e-5f * z - 1.388731625493765e-3f) * z + 4.166664568298827e-2f) * z * z -
        0.5f * z + 1.0f;
    s = ((-1.9515295891e-4f * z + 8.3321608736e-3f) * z - 1.6666654611e-1f) * z * a + a;
}

/// cos(2π t) and sin(2π t) for t in [0, 1]: the nearest quarter turn q, then the rest
/// (at most an eighth of a turn) by sincos_quarter, rotated by q quarter turns.
inline void sincos_turn(float t, float& c, float& s)
{
    const int q = static_cast<int>(4.0f * t + 0.5f);  // 0 .. 4
    float cr, sr;
    sincos_quarter(kTwoPi * (t - 0.25f * static_cast<float>(q)), cr, sr);
    // A quarter turn maps (c, s) to (-s, c): odd quarters swap the two, and the sign of c
    // flips in quarters 1 and 2, that of s in quarters 2 and 3 (sign bits set without
    // branches).
    const bool odd = (q & 1) != 0;
    const float x = odd ? sr : cr, y = odd ? cr : sr;
    const uint32_t flip_c = static_cast<uint32_t>((q + 1) & 2) << 30;
    const uint32_t flip_s = static_cast<uint32_t>(q & 2) << 30;
    uint32_t bx, by;
    std::memcpy(&bx, &x, sizeof bx);  // bit copies (C++17: no std::bit_cast)
    std::memcpy(&by, &y, sizeof by);
    bx ^= flip_c;
    by ^= flip_s;
    std::memcpy(&c, &bx, sizeof c);
    std::memcpy(&s, &by, sizeof s);
}

/// sample_uniform_disk_concentric (patina/shading/sampling.h) with sincos_quarter: the same
/// map (Shirley & Chiu 1997), the same density 1/π, to within a few float ulps.
inline Vec2 sample_uniform_disk_concentric_poly(Vec2 u)
{
    const Vec2 uo(2.0f * u.x - 1.0f, 2.0f * u.y - 1.0f);
    if (uo.x == 0.0f && uo.y == 0.0f)
        return {};
    float c, s;
    if (std::abs(uo.x) > std::abs(uo.y)) {
        // θ = π/4 (y/x) in [-π/4, π/4]
        sincos_quarter(kPiOver4 * (uo.y / uo.x), c, s);
        return {uo.x * c, uo.x * s};
    }
    // θ = π/2 - a with a = π/4 (x/y): cos θ = sin a, sin θ = cos a
    sincos_quarter(kPiOver4 * (uo.x / uo.y), c, s);
    return {uo.y * s, uo.y * c};
}

/// sample_cosine_hemisphere (Malley's method) on sample_uniform_disk_concentric_poly:
/// density cos θ / π (cosine_hemisphere_pdf).
inline Vec3 sample_cosine_hemisphere_poly(Vec2 u)
{
    const Vec2 d = sample_uniform_disk_concentric_poly(u);
    const float z = safe_sqrt(1.0f - d.x * d.x - d.y * d.y);
    return {d.x, d.y, z};
}

}  // namespace patina::shading
