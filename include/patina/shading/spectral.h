// patina/shading/spectral.h — per-wavelength values for shading plugins.
//
// Every radiometric value crosses the ABI as an array of `wl->count` floats, one per
// wavelength of the path (abi.h §3). This header gives plugins:
//
//   SpectralArray            a fixed array of PATINA_MAX_WAVELENGTHS floats with element-wise
//                            arithmetic; it never allocates, so evaluation code can use it
//                            freely
//   wavelength_count(wl)     the count clamped to [0, PATINA_MAX_WAVELENGTHS] (robust
//                            against a bad host value)
//   for_each_wavelength      calls f(i, lambda_nm) for each wavelength of the path
//   eval_rgb                 a reflectance PatinaRgbSpectrum at the path's wavelengths
//                            (exact: patina_rgb_spectrum_eval)
//   eval_tabulated           a PatinaTabulatedSpectrum at the path's wavelengths
//   store                    copies the first `count` values into an ABI output array
//   TabulatedSpectrum        an owned copy of a PatinaTabulatedSpectrum (the host's arrays
//                            live only during create); copying allocates, evaluating does
//                            not
//   check_tabulated          says what is wrong with a tabulated spectrum, or nullptr
//   rgb_spectrum_range       the exact minimum and maximum of a reflectance
//                            PatinaRgbSpectrum over 360-830 nm, to validate it in create
//
// Example, a reflectance parameter in a BSDF's eval:
//
//     const SpectralArray r = eval_rgb(inst->reflectance, *wl);
//     store(r * kInvPi, *wl, f);
#pragma once

#include <patina/shading/vec.h>

#include <vector>

namespace patina::shading {

/// Number of wavelengths of a path, clamped to [0, PATINA_MAX_WAVELENGTHS].
inline int wavelength_count(const PatinaWavelengths& wl)
{
    return std::clamp(wl.count, 0, PATINA_MAX_WAVELENGTHS);
}

/// Calls f(i, lambda_nm) for i in [0, wavelength_count(wl)).
template <typename F> void for_each_wavelength(const PatinaWavelengths& wl, F&& f)
{
    const int n = wavelength_count(wl);
    for (int i = 0; i < n; ++i)
        f(i, wl.lambda_nm[i]);
}

/// One value per wavelength of a path; all PATINA_MAX_WAVELENGTHS entries are always
/// initialised, so arithmetic on unused entries is harmless.
struct SpectralArray {
    float v[PATINA_MAX_WAVELENGTHS] = {};

    constexpr SpectralArray() = default;
    explicit constexpr SpectralArray(float c)
    {
        for (float& x : v)
            x = c;
    }

    constexpr float& operator[](int i) { return v[i]; }
    constexpr float operator[](int i) const { return v[i]; }

    constexpr SpectralArray& operator+=(const SpectralArray& b)
    {
        for (int i = 0; i < PATINA_MAX_WAVELENGTHS; ++i)
            v[i] += b.v[i];
        return *this;
    }
    constexpr SpectralArray& operator*=(const SpectralArray& b)
    {
        for (int i = 0; i < PATINA_MAX_WAVELENGTHS; ++i)
            v[i] *= b.v[i];
        return *this;
    }
    constexpr SpectralArray& operator*=(float s)
    {
        for (float& x : v)
            x *= s;
        return *this;
    }
};

constexpr SpectralArray operator+(SpectralArray a, const SpectralArray& b)
{
    return a += b;
}
constexpr SpectralArray operator*(SpectralArray a, const SpectralArray& b)
{
    return a *= b;
}
constexpr SpectralArray operator*(SpectralArray a, float s)
{
    return a *= s;
}
constexpr SpectralArray operator*(float s, SpectralArray a)
{
    return a *= s;
}

/// Copies the first wavelength_count(wl) values of a to out (an ABI output array).
inline void store(const SpectralArray& a, const PatinaWavelengths& wl, float* out)
{
    const int n = wavelength_count(wl);
    for (int i = 0; i < n; ++i)
        out[i] = a.v[i];
}

/// Writes `value` to the first wavelength_count(wl) entries of out.
inline void fill(float value, const PatinaWavelengths& wl, float* out)
{
    const int n = wavelength_count(wl);
    for (int i = 0; i < n; ++i)
        out[i] = value;
}

/// A reflectance PatinaRgbSpectrum (illuminant == 0) at the path's wavelengths.
inline SpectralArray eval_rgb(const PatinaRgbSpectrum& s, const PatinaWavelengths& wl)
{
    // The exact path for greys: with c0 = c1 = 0 the polynomial is the constant c2, so
    // the value is the same at every wavelength (bit for bit what the loop would give).
    if (s.c0 == 0.0f && s.c1 == 0.0f) {
        SpectralArray a;
        const float value = patina_rgb_spectrum_eval(&s, 0.0f);
        for_each_wavelength(wl, [&](int i, float) { a.v[i] = value; });
        return a;
    }
    SpectralArray a;
    for_each_wavelength(
        wl, [&](int i, float lambda) { a.v[i] = patina_rgb_spectrum_eval(&s, lambda); });
    return a;
}

/// A PatinaTabulatedSpectrum at the path's wavelengths.
inline SpectralArray eval_tabulated(const PatinaTabulatedSpectrum& s, const PatinaWavelengths& wl)
{
    SpectralArray a;
    for_each_wavelength(wl,
                        [&](int i, float lambda) { a.v[i] = patina_tabulated_eval(&s, lambda); });
    return a;
}

/// What is wrong with a tabulated spectrum (no entries, null arrays, non-finite numbers,
/// wavelengths not strictly increasing), or nullptr when it is usable.
inline const char* check_tabulated(const PatinaTabulatedSpectrum& s)
{
    if (s.count < 1)
        return "the spectrum has no entries";
    if (!s.value || (s.count > 1 && !s.lambda_nm))
        return "the spectrum's arrays are missing";
    for (int i = 0; i < s.count; ++i) {
        if (!is_finite(s.value[i]))
            return "the spectrum has a value that is not a finite number";
        if (s.count > 1 && !is_finite(s.lambda_nm[i]))
            return "the spectrum has a wavelength that is not a finite number";
        if (i > 0 && !(s.lambda_nm[i] > s.lambda_nm[i - 1]))
            return "the spectrum's wavelengths are not strictly increasing";
    }
    return nullptr;
}

/// An owned copy of a tabulated spectrum: linear interpolation, clamped ends, exactly as
/// patina_tabulated_eval. Construct it in create (allocates); evaluate anywhere.
class TabulatedSpectrum {
public:
    TabulatedSpectrum() = default;
    /// Copies s, which must pass check_tabulated().
    explicit TabulatedSpectrum(const PatinaTabulatedSpectrum& s)
        : value_(s.value, s.value + s.count)
    {
        if (s.count > 1)
            lambda_.assign(s.lambda_nm, s.lambda_nm + s.count);
        else
            lambda_.assign(1, 0.0f);
    }

    /// The ABI view of the copy (valid while this object lives).
    PatinaTabulatedSpectrum view() const
    {
        return {static_cast<int>(value_.size()), lambda_.data(), value_.data()};
    }
    float eval(float lambda_nm) const
    {
        const PatinaTabulatedSpectrum v = view();
        return patina_tabulated_eval(&v, lambda_nm);
    }
    SpectralArray eval(const PatinaWavelengths& wl) const { return eval_tabulated(view(), wl); }

    int size() const { return static_cast<int>(value_.size()); }
    float lambda_nm(int i) const { return lambda_[i]; }
    float value(int i) const { return value_[i]; }

private:
    std::vector<float> lambda_;
    std::vector<float> value_;
};

/// Exact minimum and maximum of a reflectance PatinaRgbSpectrum (illuminant ignored) over
/// [lambda_min_nm, lambda_max_nm]. The sigmoid S is monotonic, so the extremes of
/// scale · S(x(λ)) lie where the quadratic x(λ) has its extremes: at the ends of the
/// range or at the vertex λ = −c1 / (2 c0).
inline void rgb_spectrum_range(const PatinaRgbSpectrum& s, float* min_value, float* max_value,
                               float lambda_min_nm = PATINA_LAMBDA_MIN_NM,
                               float lambda_max_nm = PATINA_LAMBDA_MAX_NM)
{
    float lo = patina_rgb_spectrum_eval(&s, lambda_min_nm);
    float hi = lo;
    auto include = [&](float lambda) {
        const float v = patina_rgb_spectrum_eval(&s, lambda);
        lo = std::min(lo, v);
        hi = std::max(hi, v);
    };
    include(lambda_max_nm);
    if (s.c0 != 0.0f) {
        const float vertex = -s.c1 / (2.0f * s.c0);
        if (vertex > lambda_min_nm && vertex < lambda_max_nm)
            include(vertex);
    }
    *min_value = lo;
    *max_value = hi;
}

} // namespace patina::shading
