// Voxels of a row in the lanes of a vector, for the stone simulation's row kernels
// (transport_rows.cpp, front_rows.cpp): GCC vector extensions, so that one source compiles to
// SSE2 and, in target_clones, to AVX2. Each lane does a scalar operation in IEEE arithmetic
// (nothing is fused: neither ISA has FMA), so a kernel gives the bits of its scalar loop;
// std::min, std::max and std::clamp are spelled as the selects they are, which keeps even the
// sign of a zero.
#pragma once

#include <array>
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <emmintrin.h>
#include <xmmintrin.h>

// The helpers are always inlined: no vector crosses a call, whatever the clone's ISA.
#pragma GCC diagnostic ignored "-Wpsabi"

namespace patina::texgen::stone::lanes {

constexpr int kLanes = 8;
using VF = float __attribute__((vector_size(4 * kLanes)));
using VI = int32_t __attribute__((vector_size(4 * kLanes)));
using VB = uint8_t __attribute__((vector_size(kLanes)));

/// The first n lanes from p (n <= kLanes), the others 0: a row's last group may be short.
/// (Whole groups copy a constant size, which is one vector move.)
[[gnu::always_inline]] inline VF load(const float* p, int n)
{
    VF v{};
    if (n == kLanes)
        std::memcpy(&v, p, sizeof v);
    else
        for (int l = 0; l < n; ++l)
            v[l] = p[l];
    return v;
}

/// Bytes widened to lanes. A whole group is spelled in SSE2 intrinsics (zero-extending
/// unpacks, which the AVX2 clone turns into vpmovzx): GCC's own conversion of an 8-byte
/// vector goes through general registers lane by lane, some 30 instructions a load.
[[gnu::always_inline]] inline VI load(const uint8_t* p, int n)
{
    static_assert(kLanes == 8);
    if (n == kLanes) {
        using I4 = int32_t __attribute__((vector_size(16)));
        const __m128i zero = _mm_setzero_si128();
        const __m128i words =
            _mm_unpacklo_epi8(_mm_loadl_epi64(reinterpret_cast<const __m128i*>(p)), zero);
        const I4 lo = I4(_mm_unpacklo_epi16(words, zero));
        const I4 hi = I4(_mm_unpackhi_epi16(words, zero));
        return __builtin_shufflevector(lo, hi, 0, 1, 2, 3, 4, 5, 6, 7);
    }
    VB b{};
    for (int l = 0; l < n; ++l)
        b[l] = p[l];
    return __builtin_convertvector(b, VI);
}

[[gnu::always_inline]] inline void store(float* p, VF v, int n)
{
    if (n == kLanes)
        std::memcpy(p, &v, sizeof v);
    else
        for (int l = 0; l < n; ++l)
            p[l] = v[l];
}

/// Whether any lane is set (masks are 0 or -1): the halves ORed, then SSE's movmskps.
[[gnu::always_inline]] inline bool any(VI m)
{
    using I4 = int32_t __attribute__((vector_size(16)));
    static_assert(sizeof(VI) == 2 * sizeof(I4));
    I4 half[2];
    std::memcpy(half, &m, sizeof m);
    return _mm_movemask_ps(__m128(half[0] | half[1])) != 0;
}

/// Lane l's mask as bit l (masks are 0 or -1).
[[gnu::always_inline]] inline unsigned lane_bits(VI m)
{
    using I4 = int32_t __attribute__((vector_size(16)));
    static_assert(sizeof(VI) == 2 * sizeof(I4));
    I4 half[2];
    std::memcpy(half, &m, sizeof m);
    return unsigned(_mm_movemask_ps(__m128(half[0]))) |
           unsigned(_mm_movemask_ps(__m128(half[1]))) << 4;
}

/// +0 in every lane, from a value the compiler cannot see: a few arrays set to a constant
/// are otherwise merged into a `rep stos`, which costs more than a kernel's whole group.
[[gnu::always_inline]] inline VF opaque_zero()
{
    float z = 0.0f;
    asm("" : "+x"(z));
    return VF{} + z;
}

/// Square roots, correctly rounded as std::sqrt (SSE's sqrtps, in both clones).
[[gnu::always_inline]] inline VF vsqrt(VF v)
{
    using F4 = float __attribute__((vector_size(16)));
    static_assert(sizeof(VF) % sizeof(F4) == 0);
    F4 part[sizeof(VF) / sizeof(F4)];
    std::memcpy(part, &v, sizeof v);
    for (F4& x : part)
        x = _mm_sqrt_ps(x);
    std::memcpy(&v, part, sizeof v);
    return v;
}

/// std::min(a, b), std::max(a, b) and std::clamp(v, lo, hi), lane by lane.
[[gnu::always_inline]] inline VF vmin(VF a, VF b) { return b < a ? b : a; }
[[gnu::always_inline]] inline VF vmax(VF a, VF b) { return a < b ? b : a; }
[[gnu::always_inline]] inline VF vclamp(VF v, VF lo, VF hi)
{
    return v < lo ? lo : (hi < v ? hi : v);
}

/// H_aa of lattice axis a (stencil.h metric_from_weights) from the six stencil weights at
/// the n cells from `at`.
[[gnu::always_inline]] inline VF axis_metric(const std::array<const float*, 6>& w, int a,
                                             size_t at, int n)
{
    const int x = a == 0 ? 0 : a == 1 ? 1 : 2;
    const int y = a == 0 ? 3 : a == 1 ? 3 : 4;
    const int z = a == 0 ? 5 : a == 1 ? 4 : 5;
    return load(w[size_t(x)] + at, n) + load(w[size_t(y)] + at, n) +
           load(w[size_t(z)] + at, n);
}

} // namespace patina::texgen::stone::lanes
