// Four wavelengths of a path in one register: a shader may run its per-wavelength loops four
// lanes at a time (GCC/Clang vector extension: SSE2 on any x86-64, no -m flags), as the
// layered model and kubelka_munk.h's km_layer4 do.
// Every lane does the very float operations the scalar code did, in the same order (IEEE
// add, multiply, divide and square root are exact per lane; exp and expm1 stay libm calls
// per lane), so the results are the same bits as a loop over wavelengths.
#pragma once

#include <patina/abi.h>
#include <patina/shading/spectral.h>

#include <cmath>
#include <cstring>

#if defined(__SSE2__)
#include <emmintrin.h>
#elif defined(__SSE__)
#include <xmmintrin.h>
#endif

namespace patina::shading::simd {

using V4 = float __attribute__((vector_size(16)));
using I4 = int __attribute__((vector_size(16)));  ///< also what a V4 comparison gives

using D2 = double __attribute__((vector_size(16)));  ///< two lanes in double

inline constexpr int kLanes = 4;
static_assert(PATINA_MAX_WAVELENGTHS % kLanes == 0);

/// Lane groups covering `count` wavelengths (1 for the usual 4 hero wavelengths).
inline int lane_groups(int count)
{
    return (count + kLanes - 1) / kLanes;
}

inline V4 splat(float x)
{
    return V4{x, x, x, x};
}

inline V4 load4(const float* p)
{
    V4 v;
    std::memcpy(&v, p, sizeof v);
    return v;
}

inline void store4(float* p, V4 v)
{
    std::memcpy(p, &v, sizeof v);
}

inline void store4(int* p, I4 v)
{
    std::memcpy(p, &v, sizeof v);
}

/// {a[0], a[1], b[0], b[1]}: two pairs of neighbouring floats.
inline V4 load2x2(const float* a, const float* b)
{
    float v[4] = {a[0], a[1], b[0], b[1]};
    return load4(v);
}

/// Lanes [o, o + 4) of a spectral array.
inline V4 load4(const shading::SpectralArray& a, int o)
{
    return load4(a.v + o);
}

inline V4 sqrt4(V4 x)
{
#if defined(__SSE__)
    return _mm_sqrt_ps(x);
#else
    for (int l = 0; l < kLanes; ++l)
        x[l] = std::sqrt(x[l]);
    return x;
#endif
}

inline D2 sqrt2(D2 x)
{
#if defined(__SSE2__)
    return _mm_sqrt_pd(x);
#else
    x[0] = std::sqrt(x[0]);
    x[1] = std::sqrt(x[1]);
    return x;
#endif
}

/// std::clamp(x, lo, hi) per lane (NaN stays NaN, as std::clamp).
inline V4 clamp4(V4 x, float lo, float hi)
{
    return x < splat(lo) ? splat(lo) : (splat(hi) < x ? splat(hi) : x);
}

/// True when every lane of a equals b (bit patterns of -0/+0 aside, as ==).
inline bool all_equal(V4 a, V4 b)
{
    const I4 eq = a == b;
    return eq[0] & eq[1] & eq[2] & eq[3];
}

}  // namespace patina::shading::simd
