// Spectral basics: the CIE 1931 2° observer and standard illuminants as embedded tables,
// colorimetric integration, hero-wavelength sampling over 360-830 nm, and the small
// fixed-size SampledSpectrum the renderer carries along a path.
#pragma once

#include <patina/abi.h>

#include <array>
#include <cassert>
#include <cstdint>
#include <cstring>
#include <functional>
#include <span>

namespace patina {

/// Range of the embedded CIE tables and of wavelength sampling, in nm.
constexpr float kLambdaMinNm = PATINA_LAMBDA_MIN_NM;
constexpr float kLambdaMaxNm = PATINA_LAMBDA_MAX_NM;
/// The CIE tables are sampled every 5 nm from 360 to 830 nm.
constexpr int kCieSamples = 95;
constexpr float kCieStepNm = 5.0f;

/// Integral of ȳ(λ) dλ over 360-830 nm of the embedded table (linear interpolation, so the
/// trapezoid sum on the 5 nm grid). Dividing ∫ L ȳ dλ by it gives the Y of a radiance L in
/// units where a spectrum constant 1 has Y = 1 (pbrt-v4's CIE_Y_integral convention).
constexpr double kCieYIntegral = 106.857028330325;

/// CIE 1931 2° colour matching functions, linearly interpolated, 0 outside 360-830 nm.
float cie_x(float lambda_nm);
float cie_y(float lambda_nm);
float cie_z(float lambda_nm);

/// CIE standard illuminant D65, relative SPD (100 at 560 nm, CIE 15:2004 table), linearly
/// interpolated; 0 outside 360-830 nm.
float d65(float lambda_nm);

/// CIE standard illuminant A from its defining Planck formula (CIE 15:2004),
/// 100 at 560 nm; defined for any positive wavelength.
float illuminant_a(float lambda_nm);

/// A spectral function of wavelength in nm.
using SpectrumFn = std::function<double(double)>;
using Xyz = std::array<double, 3>;

/// CIE XYZ of a reflectance seen under `illuminant`, normalised so that the illuminant
/// itself (a perfect white reflector) has Y = 1. Integrated on a 1 nm grid over 360-830 nm.
Xyz spectrum_to_xyz(const SpectrumFn& reflectance, const SpectrumFn& illuminant = d65);

/// CIE XYZ of a radiance spectrum: ∫ L x̄ dλ / kCieYIntegral (a constant 1 has Y = 1).
Xyz emission_to_xyz(const SpectrumFn& radiance);

// ---------------------------------------------------------------------------------------
// Wavelength sampling (hero wavelength: one u, `count` wavelengths by rotating u by i/count)
// ---------------------------------------------------------------------------------------

/// pbrt-v4's visible-wavelength importance density: p(λ) ∝ 1/cosh²(0.0072 (λ − 538)),
/// normalised over 360-830 nm; 0 outside.
float visible_wavelength_pdf(float lambda_nm);
/// Invert the CDF of visible_wavelength_pdf for u in [0, 1).
float sample_visible_wavelength(float u);
/// `count` (1..PATINA_MAX_WAVELENGTHS) wavelengths from u_i = frac(u + i/count), each
/// distributed by visible_wavelength_pdf; lambda_nm[0] is the hero wavelength.
PatinaWavelengths sample_wavelengths_visible(float u, int count);

struct SampledSpectrum;
/// As above, and the pdf of each wavelength into `pdf` (from the sampling step itself,
/// cheaper than visible_wavelength_pdf).
PatinaWavelengths sample_wavelengths_visible(float u, int count, SampledSpectrum& pdf);

/// Steps of u in the table of sample_wavelengths_tabulated.
constexpr int kWavelengthTableSize = 512;
/// As sample_wavelengths_visible(u, count, pdf), from a tabulated inverse CDF of
/// visible_wavelength_pdf built once: kWavelengthTableSize equal steps of u, λ linear in u
/// within each step. Its density is therefore constant over each step's λ interval,
/// 1 / (N Δλ_j), and that is the pdf returned (exact for this sampler, integrating to 1);
/// it follows visible_wavelength_pdf to within 6 % (0.6 % over 450-650 nm), with the same
/// mass in every step. No transcendental function per sample.
PatinaWavelengths sample_wavelengths_tabulated(float u, int count, SampledSpectrum& pdf);
/// The density of the wavelengths sample_wavelengths_tabulated draws, at λ; 0 outside
/// 360-830 nm.
float tabulated_wavelength_pdf(float lambda_nm);

/// Uniform density 1/(830 − 360) over 360-830 nm; 0 outside.
float uniform_wavelength_pdf(float lambda_nm);
/// As sample_wavelengths_visible, with uniformly distributed wavelengths.
PatinaWavelengths sample_wavelengths_uniform(float u, int count);

// ---------------------------------------------------------------------------------------
// SampledSpectrum: values at the wavelengths of one path
// ---------------------------------------------------------------------------------------

/// `count` values, one per wavelength of a PatinaWavelengths. Binary operations take the
/// count of the left operand; both operands must have the same count.
///
/// Arithmetic runs over all PATINA_MAX_WAVELENGTHS entries, without a branch on the count:
/// fixed-length loops the compiler turns into SIMD operations. The entries past `count`
/// start at 0 and never mix with the others; reductions (average, max_value, min_value,
/// is_black) and conversions look at the first `count` entries only.
struct SampledSpectrum {
    static constexpr int kLanes = PATINA_MAX_WAVELENGTHS;
    static_assert(kLanes % 4 == 0, "lanes come in SIMD blocks of four");
    /// Four lanes in one SIMD register (GCC vector extension: SSE on x86-64, no -m flags).
    using Block = float __attribute__((vector_size(16)));
    using Mask = int32_t __attribute__((vector_size(16)));
    int count = 0;
    float v[kLanes] = {};

    SampledSpectrum() = default;
    SampledSpectrum(int n, float value) : count(n)
    {
        assert(n >= 0 && n <= kLanes);
        for (int i = 0; i < kLanes; ++i)
            v[i] = i < n ? value : 0.0f;
    }
    /// Copy n values (e.g. the float[PATINA_MAX_WAVELENGTHS] output of a plugin).
    static SampledSpectrum from_array(int n, const float* values)
    {
        SampledSpectrum s;
        s.count = n;
        for (int i = 0; i < n; ++i)
            s.v[i] = values[i];
        return s;
    }
    /// The first n values of a whole PATINA_MAX_WAVELENGTHS array (a plugin's output array),
    /// lanes past n 0: a fixed-length copy, cheaper than from_array's (a call to memcpy).
    static SampledSpectrum from_lanes(int n, const float (&values)[kLanes])
    {
        SampledSpectrum s;
        s.count = n;
        for (int i = 0; i < kLanes; ++i)
            s.v[i] = i < n ? values[i] : 0.0f;
        return s;
    }
    /// Evaluate fn at each wavelength.
    template <class Fn> static SampledSpectrum from_function(const PatinaWavelengths& wl, Fn&& fn)
    {
        SampledSpectrum s(wl.count, 0.0f);
        for (int i = 0; i < wl.count; ++i)
            s.v[i] = static_cast<float>(fn(wl.lambda_nm[i]));
        return s;
    }

    float& operator[](int i) { return v[i]; }
    float operator[](int i) const { return v[i]; }
    float* data() { return v; }
    const float* data() const { return v; }

    SampledSpectrum& operator+=(const SampledSpectrum& o)
    {
        assert(count == o.count);
        for (int i = 0; i < kLanes; ++i)
            v[i] += o.v[i];
        return *this;
    }
    SampledSpectrum& operator-=(const SampledSpectrum& o)
    {
        assert(count == o.count);
        for (int i = 0; i < kLanes; ++i)
            v[i] -= o.v[i];
        return *this;
    }
    SampledSpectrum& operator*=(const SampledSpectrum& o)
    {
        assert(count == o.count);
        for (int i = 0; i < kLanes; ++i)
            v[i] *= o.v[i];
        return *this;
    }
    /// Elementwise division; a zero divisor gives 0 (never Inf or NaN).
    SampledSpectrum& operator/=(const SampledSpectrum& o)
    {
        assert(count == o.count);
        // Four lanes at a time (GCC leaves the per-lane select scalar); a lane divided by 0
        // gives inf or NaN in the register and is replaced by 0 before it is stored.
        for (int b = 0; b < kLanes; b += 4) {
            Block x, d;
            std::memcpy(&x, v + b, sizeof x);
            std::memcpy(&d, o.v + b, sizeof d);
            const Block q = d != 0.0f ? x / d : Block{};
            std::memcpy(v + b, &q, sizeof q);
        }
        return *this;
    }
    SampledSpectrum& operator*=(float s)
    {
        for (int i = 0; i < kLanes; ++i)
            v[i] *= s;
        return *this;
    }
    SampledSpectrum& operator/=(float s)
    {
        if (s == 0.0f)
            return *this = SampledSpectrum(count, 0.0f);
        for (int i = 0; i < kLanes; ++i)
            v[i] /= s;
        return *this;
    }

    float average() const;
    float max_value() const
    {
        float m = count > 0 ? v[0] : 0.0f;
        for (int i = 1; i < count; ++i)
            m = v[i] > m ? v[i] : m;
        return m;
    }
    float min_value() const;
    bool is_black() const
    {
        // Four lanes at a time: the per-lane loop compiled to scalar code with a branch per
        // lane (~45 instructions a call, the renderer's most frequent test).
        Mask nonzero = {};
        for (int b = 0; b < kLanes; b += 4) {
            Block x;
            std::memcpy(&x, v + b, sizeof x);
            const Mask lane = Mask{0, 1, 2, 3} + b;
            nonzero |= (x != 0.0f) & (lane < count);
        }
#if defined(__SSE__)
        // One movmskps of the lane signs (the mask lanes are 0 or -1) instead of three
        // extracts and ORs.
        Block signs;
        std::memcpy(&signs, &nonzero, sizeof signs);
        return __builtin_ia32_movmskps(signs) == 0;
#else
        return (nonzero[0] | nonzero[1] | nonzero[2] | nonzero[3]) == 0;
#endif
    }
};

inline SampledSpectrum operator+(SampledSpectrum a, const SampledSpectrum& b)
{
    return a += b;
}
inline SampledSpectrum operator-(SampledSpectrum a, const SampledSpectrum& b)
{
    return a -= b;
}
inline SampledSpectrum operator*(SampledSpectrum a, const SampledSpectrum& b)
{
    return a *= b;
}
inline SampledSpectrum operator/(SampledSpectrum a, const SampledSpectrum& b)
{
    return a /= b;
}
inline SampledSpectrum operator*(SampledSpectrum a, float s)
{
    return a *= s;
}
inline SampledSpectrum operator*(float s, SampledSpectrum a)
{
    return a *= s;
}
inline SampledSpectrum operator/(SampledSpectrum a, float s)
{
    return a /= s;
}

/// Elementwise exp(s), e.g. Beer-Lambert transmittance exp(-sigma_t * t).
SampledSpectrum exp(const SampledSpectrum& s);
/// Elementwise sqrt of max(s, 0).
SampledSpectrum sqrt(const SampledSpectrum& s);

/// visible_wavelength_pdf at each wavelength of wl.
SampledSpectrum visible_wavelength_pdf(const PatinaWavelengths& wl);

/// XYZ estimate of a radiance sample L carried at the wavelengths wl: the average over i of
/// L_i x̄(λ_i) / pdf_i, divided by kCieYIntegral (a constant radiance 1 gives Y = 1 in
/// expectation). Wavelengths with pdf_i == 0 (terminated secondary wavelengths) contribute
/// nothing but still count in the average.
Xyz xyz_from_samples(const SampledSpectrum& L, const PatinaWavelengths& wl,
                     const SampledSpectrum& pdf);
/// As above, for wavelengths drawn by sample_wavelengths_visible.
Xyz xyz_from_samples(const SampledSpectrum& L, const PatinaWavelengths& wl);

/// x̄, ȳ, z̄ (cie_x, cie_y, cie_z) and D65 (d65) at every wavelength of a path, looked up
/// once per path: one position in the 5 nm tables per wavelength serves all four.
struct CieAtWavelengths {
    SampledSpectrum x, y, z;
    SampledSpectrum d65;
};
CieAtWavelengths cie_at_wavelengths(const PatinaWavelengths& wl);
/// The renderer's per-sample spectral set-up in one pass: sample_wavelengths_tabulated(u,
/// count, pdf) and cie_at_wavelengths of its wavelengths into `cie` (the same values as the
/// two calls; one straight pass for count 4).
void sample_wavelengths_tabulated(float u, int count, PatinaWavelengths& wl,
                                  SampledSpectrum& pdf, CieAtWavelengths& cie);
/// The same, returning the wavelengths. The renderer uses the form above, which writes them
/// in place: a returned copy is read back as one vector from pieces written apart, which
/// no store forwards to (a stall per sample).
inline PatinaWavelengths sample_wavelengths_tabulated(float u, int count, SampledSpectrum& pdf,
                                                      CieAtWavelengths& cie)
{
    PatinaWavelengths wl;
    sample_wavelengths_tabulated(u, count, wl, pdf, cie);
    return wl;
}
/// Where the per-sample spectral set-up of one sample goes.
struct SpectralSetUp {
    PatinaWavelengths* wl;
    SampledSpectrum* pdf;
    CieAtWavelengths* cie;
};
/// The set-up of several samples of 4 wavelengths each: out[i] gets bit for bit what
/// sample_wavelengths_tabulated(u[i], 4, ...) gives, with the samples' look-ups interleaved
/// so that their latencies overlap (one call for a whole batch of camera samples).
void sample_wavelengths_tabulated4(std::span<const float> u, std::span<const SpectralSetUp> out);
/// xyz_from_samples with the matching functions already looked up for L's wavelengths.
Xyz xyz_from_samples(const SampledSpectrum& L, const CieAtWavelengths& cie,
                     const SampledSpectrum& pdf);

} // namespace patina
