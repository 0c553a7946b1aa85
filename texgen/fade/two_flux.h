// The depth-discretised two-flux model (Kimmel et al. 2013, §4.1): N sublayers of uniform
// absorption and scattering, each with Kubelka's reflectance and transmittance (Eqs. 22,
// 23); the irradiances E^u_i, E^d_i at the N + 1 sublayer boundaries solve the block
// tridiagonal system E = M E + E_0 (Eqs. 24-34), here in O(N) by the adding method
// (Kubelka 1948): the block elimination of the system from the ground up.
//
// The formulas are templates on the lane type, double or Vec4 (four wavelengths at once),
// so that the scalar functions the tests check and the vector kernels of the fading
// simulation (fading_simulation.cpp) compute the same thing; float and Vec8f (eight
// wavelengths) for the simulation's single-precision kernel.
#pragma once

#include <cstddef>
#include <new>
#include <span>
#include <vector>

namespace patina::texgen::fade {

/// Four doubles or eight floats, one wavelength each (GCC vector extensions): one AVX
/// register where a kernel is compiled for AVX2, two SSE2 registers elsewhere.
using Vec4 = double __attribute__((vector_size(32)));
using Vec4i = long long __attribute__((vector_size(32)));
using Vec8f = float __attribute__((vector_size(32)));
using Vec8i = int __attribute__((vector_size(32)));

/// Heap storage of vectors aligned for AVX loads: alignof(Vec4) is only 16 where AVX is
/// not enabled, and the AVX2 kernels load them with 32-byte aligned moves.
template <class T>
struct Align32Allocator {
    using value_type = T;
    Align32Allocator() = default;
    template <class U>
    Align32Allocator(const Align32Allocator<U>&) noexcept {}
    T* allocate(size_t n)
    {
        return static_cast<T*>(::operator new(n * sizeof(T), std::align_val_t{32}));
    }
    void deallocate(T* p, size_t) noexcept { ::operator delete(p, std::align_val_t{32}); }
    template <class U>
    bool operator==(const Align32Allocator<U>&) const noexcept { return true; }
};
using Vec4Vector = std::vector<Vec4, Align32Allocator<Vec4>>;
using Vec8fVector = std::vector<Vec8f, Align32Allocator<Vec8f>>;

/// A lane type's element type and the integer type of the same width (bit manipulation).
template <class T>
struct LaneTraits;
template <>
struct LaneTraits<double> {
    using Elem = double;
    using Bits = long long;
};
template <>
struct LaneTraits<Vec4> {
    using Elem = double;
    using Bits = Vec4i;
};
template <>
struct LaneTraits<float> {
    using Elem = float;
    using Bits = int;
};
template <>
struct LaneTraits<Vec8f> {
    using Elem = float;
    using Bits = Vec8i;
};

// Vector arguments of inline functions: no ABI is involved once inlined.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wpsabi"

/// exp(y) for y <= 0, without branches or library calls, so that loops over wavelengths
/// vectorise: y = n ln2 + r, |r| <= ln2/2, e^r by its Taylor polynomial, 2^n from the
/// exponent bits. Double: degree 12 (remainder < 2e-16), relative error < 4e-16, y < -708
/// gives ~1e-308, not 0. Float: degree 7 (remainder < 6e-9), relative error < 2e-7,
/// y < -87 gives ~1e-38.
template <class T>
[[gnu::always_inline]] inline T exp_nonpositive(T y)
{
    using E = typename LaneTraits<T>::Elem;
    using I = typename LaneTraits<T>::Bits;
    // Plain selects and builtins, not std:: wrappers: they inline into callers compiled with
    // other floating-point options (fading_simulation.cpp) and keep the loops vectorisable.
    if constexpr (sizeof(E) == 8) {
        y = y < -708.0 ? -708.0 : y;
        y = y > 0.0 ? 0.0 : y;
        constexpr double kShift = 6755399441055744.0;  // 1.5 * 2^52: rounds to an integer
        const T t = y * 1.4426950408889634 + kShift;
        const T n = t - kShift;
        // ln 2 split as in fdlibm (Cody-Waite): n * kLn2Hi is exact for |n| < 2^11.
        const T r = (y - n * 6.93147180369123816490e-01) - n * 1.90821492927058770002e-10;
        T p = r * (1.0 / 479001600.0) + 1.0 / 39916800.0;
        p = p * r + 1.0 / 3628800.0;
        p = p * r + 1.0 / 362880.0;
        p = p * r + 1.0 / 40320.0;
        p = p * r + 1.0 / 5040.0;
        p = p * r + 1.0 / 720.0;
        p = p * r + 1.0 / 120.0;
        p = p * r + 1.0 / 24.0;
        p = p * r + 1.0 / 6.0;
        p = p * r + 0.5;
        p = p * r + 1.0;
        p = p * r + 1.0;
        // The low bits of t hold n; 2^n = (n + 1023) << 52.
        const I n_int = __builtin_bit_cast(I, t) - __builtin_bit_cast(long long, kShift);
        return p * __builtin_bit_cast(T, (n_int + 1023) << 52);
    } else {
        y = y < -87.0f ? -87.0f : y;
        y = y > 0.0f ? 0.0f : y;
        constexpr float kShift = 12582912.0f;  // 1.5 * 2^23
        const T t = y * 1.44269504f + kShift;
        const T n = t - kShift;
        // ln 2 split as in Cephes: n * 0.693359375 is exact for |n| < 2^8.
        const T r = (y - n * 0.693359375f) - n * -2.12194440e-4f;
        T p = r * E(1.0 / 5040.0) + E(1.0 / 720.0);
        p = p * r + E(1.0 / 120.0);
        p = p * r + E(1.0 / 24.0);
        p = p * r + E(1.0 / 6.0);
        p = p * r + 0.5f;
        p = p * r + 1.0f;
        p = p * r + 1.0f;
        const I n_int = __builtin_bit_cast(I, t) - __builtin_bit_cast(int, kShift);
        return p * __builtin_bit_cast(T, (n_int + 127) << 23);
    }
}

/// 1 / sqrt(max(v, tiny)) without a library call or division: from the exponent bits
/// (error < 4%), then Newton steps (quadratic): four for double (relative error < 1e-15),
/// three for float (< 2e-7).
template <class T>
[[gnu::always_inline]] inline T rsqrt_positive(T v)
{
    using E = typename LaneTraits<T>::Elem;
    using I = typename LaneTraits<T>::Bits;
    if constexpr (sizeof(E) == 8) {
        const T safe = v > 1e-300 ? v : 1e-300;
        T y = __builtin_bit_cast(T, 0x5fe6eb50c7b537a9LL - (__builtin_bit_cast(I, safe) >> 1));
        const T half = 0.5 * safe;
        y = y * (1.5 - half * y * y);
        y = y * (1.5 - half * y * y);
        y = y * (1.5 - half * y * y);
        y = y * (1.5 - half * y * y);
        return y;
    } else {
        const T safe = v > 1e-30f ? v : 1e-30f;
        T y = __builtin_bit_cast(T, 0x5f375a86 - (__builtin_bit_cast(I, safe) >> 1));
        const T half = 0.5f * safe;
        y = y * (1.5f - half * y * y);
        y = y * (1.5f - half * y * y);
        y = y * (1.5f - half * y * y);
        return y;
    }
}

/// sqrt(v) for v >= 0 (relative error < 1e-15), without the errno branch of std::sqrt.
template <class T>
[[gnu::always_inline]] inline T sqrt_nonnegative(T v)
{
    v = v > 0.0 ? v : 0.0;
    return v * rsqrt_positive(v);
}

/// One sublayer's Eqs. (22), (23) as rho = a / d, tau = t / d (d >= 1): the kernels fold
/// the division by d into the adding method's one division.
template <class T>
struct SublayerTerms {
    T a, t, d;
};

/// Eqs. (22), (23) for absorption mu_a and scattering mu_s (1/m) and thickness dz (m).
/// With K = mu_a, S = mu_s, b S = sqrt(K^2 + 2 K S), x = b S dz, e = exp(-x) and
/// q = (1 - e^2) / x (its series for x < 1e-2):
///   rho = S q dz / D, tau = 2 e / D, D = (K + S) q dz + 1 + e^2,
/// Kubelka's formulas multiplied through by 2 e / x: finite for S = 0 (rho = 0,
/// tau = exp(-K dz)) and K = 0 (rho = S dz / (1 + S dz)), no overflow for any thickness,
/// and branch-free so that loops over wavelengths vectorise. 1/x comes from the square
/// root's 1/sqrt: no division.
/// The same with the thickness d > 0 and 1 / d given (hoisted out of the kernels' loops),
/// for K, S >= 0 (the kernels' sums of non-negative terms).
template <class T>
[[gnu::always_inline]] inline SublayerTerms<T> sublayer_terms_nonnegative(
    T K, T S, typename LaneTraits<T>::Elem d, typename LaneTraits<T>::Elem inv_d)
{
    using E = typename LaneTraits<T>::Elem;
    // The series below x = 1e-2 (double) or 0.1 (float: 1 - e^2 loses more digits to
    // cancellation); its truncation error there is < x^8 / 9! (3e-14 at 0.1).
    constexpr E kSeriesBelow = sizeof(E) == 8 ? E(1e-2) : E(0.1);
    const T v = K * (K + E(2) * S);
    const T inv_root = rsqrt_positive(v);
    const T x = v * inv_root * d;  // sqrt(v) dz (v <= 0: 0)
    const T e = exp_nonpositive(-x);
    const T e2 = e * e;
    // 2 e sinh(x) / x: (1 - e^2)/x, or 2 e (1 + x^2/6 + x^4/120 + x^6/5040) near 0.
    const T x2 = x * x;
    const T series =
        E(2) * e * (E(1) + x2 * (E(1.0 / 6.0) + x2 * (E(1.0 / 120.0) + x2 * E(1.0 / 5040.0))));
    // Both computed, then selected: no branch (big is meaningless where x is small).
    const T big = (E(1) - e2) * (inv_root * inv_d);
    const T q = x < kSeriesBelow ? series : big;
    const T qd = q * d;
    return {S * qd, E(2) * e, (K + S) * qd + E(1) + e2};
}

template <class T>
[[gnu::always_inline]] inline SublayerTerms<T> sublayer_terms(T mu_a, T mu_s,
                                                              typename LaneTraits<T>::Elem dz)
{
    using E = typename LaneTraits<T>::Elem;
    const E d = dz > E(0) ? dz : E(0);
    const E inv_d = dz > E(0) ? E(1) / dz : E(0);
    return sublayer_terms_nonnegative(mu_a > E(0) ? mu_a : E(0), mu_s > E(0) ? mu_s : E(0), d,
                                      inv_d);
}

/// Rho and tau of one sublayer (the same from either side).
struct SublayerOptics {
    double rho = 0.0;
    double tau = 1.0;
};

[[gnu::always_inline]] inline SublayerOptics sublayer_optics(double mu_a, double mu_s, double dz)
{
    const SublayerTerms<double> s = sublayer_terms(mu_a, mu_s, dz);
    const double inv = 1.0 / s.d;
    return {s.a * inv, s.t * inv};
}

/// sublayer_optics for n values at once.
void sublayer_optics(const double* mu_a, const double* mu_s, double dz, double* rho,
                     double* tau, size_t n);

/// One step of the adding method, from the ground up: sublayer i (rho = a / d,
/// tau = t / d) over everything below boundary i + 1, which reflects `r_below` of the light
/// coming down and sends up `src_below` of its own (light entered from below):
/// E^u_{i+1} = r_below E^d_{i+1} + src_below. Interreflections between the sublayer and
/// what is below sum to 1 / (1 - rho r_below) = d / p, p = d - a r_below; then
///   R_i = rho + tau^2 r_below d / p = (a p + t^2 r_below) / (d p),
///   E^d_{i+1} = (tau E^d_i + rho src_below) d / p = t/p E^d_i + a/p src_below,
///   src_i = tau src_below d / p = t/p src_below.
/// One division.
template <class T>
struct AddingStep {
    T r;        // R_i: E^u_i = R_i E^d_i + src_i
    T t_over_p;  // E^d_{i+1} = t_over_p E^d_i + a_over_p src_below
    T a_over_p;
};

template <class T>
[[gnu::always_inline]] inline AddingStep<T> adding_step(const SublayerTerms<T>& s, T r_below)
{
    using E = typename LaneTraits<T>::Elem;
    const T p = s.d - s.a * r_below;
    const T inv_dp = E(1) / (s.d * p);
    const T inv_p = s.d * inv_dp;
    return {(s.a * p + s.t * s.t * r_below) * inv_dp, s.t * inv_p, s.a * inv_p};
}

#pragma GCC diagnostic pop

/// The boundary conditions: irradiance E_0 entering at the top (Eq. 24), an optional
/// irradiance entering from below through the ground (illumination from both sides; 0 for
/// an opaque substrate), and the ground reflectance rho_N = rho* (Eq. 27).
struct TwoFluxBoundary {
    double top_irradiance = 1.0;
    double bottom_irradiance = 0.0;
    double ground_reflectance = 0.0;
};

/// Solve Eqs. (24)-(27) for the N + 1 boundary irradiances (index 0: top surface) in O(N).
/// rho and tau hold the N sublayers (top first); down and up have N + 1 entries.
/// Row i of (I - M) E = E_0, unknowns x_i = (E^u_i, E^d_i):
///   E^u_i - rho_i E^d_i - tau_i E^u_{i+1} = 0   (i < N; i = N: E^u_N - rho* E^d_N = E_below)
///   E^d_i - rho_{i-1} E^u_i - tau_{i-1} E^d_{i-1} = 0   (i > 0; i = 0: E^d_0 = E_0)
/// By adding_step from the ground up (R_N = rho*, src_N = E_below), then from the top down
/// (E^d_0 = E_0, E^u_i = R_i E^d_i + src_i): the same sweeps as the simulation's kernel.
void solve_two_flux(std::span<const double> rho, std::span<const double> tau,
                    const TwoFluxBoundary& boundary, std::span<double> down,
                    std::span<double> up);

/// The mean fluence rate in every sublayer (§4.1): F = E^d + E^u at the boundaries,
/// averaged over the two boundaries of a sublayer. `fluence` has N entries.
void sublayer_fluence_rate(std::span<const double> down, std::span<const double> up,
                           std::span<double> fluence);

}  // namespace patina::texgen::fade
