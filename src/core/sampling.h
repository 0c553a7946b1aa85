// Renderer-side sampling utilities: the PCG32 random number generator, hashing for
// per-pixel seeds (so images never depend on the thread count or tile order), piecewise
// constant 1D and 2D distributions (environment-map importance sampling) and the MIS power
// heuristic. Direction warps live in <patina/shading/sampling.h>.
#pragma once

#include <cmath>
#include <cstdint>
#include <span>
#include <vector>

namespace patina {

/// PCG32 (O'Neill 2014, "PCG: A Family of Simple Fast Space-Efficient Statistically Good
/// Algorithms for Random Number Generation"), the pcg32 XSH-RR 64/32 variant: 64-bit state,
/// a selectable stream, period 2^64 per stream. Same sequence as pcg-c's
/// pcg32_srandom_r(initstate = offset, initseq = sequence_index) and pbrt-v4's RNG.
class Pcg32 {
public:
    /// The generator's default state and stream.
    Pcg32();
    /// Stream `sequence_index` started at `offset`.
    explicit Pcg32(uint64_t sequence_index, uint64_t offset = 0xcafef00dd15ea5e5ULL)
    {
        set_sequence(sequence_index, offset);
    }

    void set_sequence(uint64_t sequence_index, uint64_t offset = 0xcafef00dd15ea5e5ULL)
    {
        // pcg32_srandom_r: the increment must be odd; mix the offset in after one step.
        state_ = 0u;
        inc_ = (sequence_index << 1u) | 1u;
        uniform_u32();
        state_ += offset;
        uniform_u32();
    }

    /// O'Neill 2014 §6.3.1: XSH RR output of the pre-advance state. Inline: the renderer
    /// draws a dozen of these per sample.
    uint32_t uniform_u32()
    {
        const uint64_t old = state_;
        state_ = old * 0x5851f42d4c957f2dULL + inc_;  // pcg-c's 64-bit LCG multiplier
        const auto xorshifted = static_cast<uint32_t>(((old >> 18u) ^ old) >> 27u);
        const auto rot = static_cast<uint32_t>(old >> 59u);
        return (xorshifted >> rot) | (xorshifted << ((~rot + 1u) & 31u));
    }
    /// Uniform in [0, bound) without modulo bias; bound > 0.
    uint32_t uniform_u32(uint32_t bound);
    /// Uniform in [0, 1): 32 random bits scaled by 2^-32, below 1 after rounding.
    float uniform_float()
    {
        const float f = static_cast<float>(uniform_u32()) * 0x1p-32f;
        return f < 0x1.fffffep-1f ? f : 0x1.fffffep-1f;
    }
    double uniform_double();

    /// Skip ahead (or back, for negative delta) in O(log delta).
    void advance(int64_t delta);

    bool operator==(const Pcg32& o) const { return state_ == o.state_ && inc_ == o.inc_; }

private:
    uint64_t state_;
    uint64_t inc_;
};

/// 64-bit finaliser (Stafford's Mix13 as used by pbrt-v4's MixBits): a bijection that
/// spreads every input bit over the output.
inline uint64_t mix_bits(uint64_t v)
{
    // Stafford's "Mix13" variant of the MurmurHash3 64-bit finaliser.
    v ^= (v >> 31);
    v *= 0x7fb5d329728ea185ULL;
    v ^= (v >> 27);
    v *= 0x81dadef4bc2dd44dULL;
    v ^= (v >> 33);
    return v;
}

/// Hash of a few integers, order-sensitive; for seeds such as (seed, x, y, sample).
uint64_t hash_values(std::span<const uint64_t> values);
inline uint64_t hash_values(uint64_t a, uint64_t b, uint64_t c = 0, uint64_t d = 0)
{
    const uint64_t v[4] = {a, b, c, d};
    return hash_values(v);
}

/// The generator for one pixel sample: a stream per pixel (from seed, x, y) started at a
/// state hashed from the sample index, so a pixel's samples are the same whichever thread
/// or tile draws them.
Pcg32 pixel_sample_rng(uint64_t seed, int x, int y, uint64_t sample_index);
/// The two halves of pixel_sample_rng, for a loop over a pixel's samples: the pixel's
/// stream (hashed once per pixel) and the generator of one of its samples;
/// pixel_sample_rng(seed, x, y, s) == sample_rng(pixel_stream(seed, x, y), seed, s).
uint64_t pixel_stream(uint64_t seed, int x, int y);
/// Inline: it runs once per camera sample, and the renderer's loop overlaps its arithmetic
/// with the neighbouring samples' when it can see it.
inline Pcg32 sample_rng(uint64_t stream, uint64_t seed, uint64_t sample_index)
{
    return Pcg32(stream, mix_bits(sample_index ^ (seed * 0x9E3779B97F4A7C15ull)));
}

/// A piecewise-constant density over [min, max] proportional to |f| (pbrt-v4's
/// PiecewiseConstant1D). An all-zero (or empty) f is treated as constant.
class Distribution1D {
public:
    Distribution1D() = default;
    explicit Distribution1D(std::span<const float> f, float min = 0.0f, float max = 1.0f);

    int size() const { return static_cast<int>(func_.size()); }
    /// ∫ |f| over [min, max] of the original function (0 if it was all zero).
    double integral() const { return integral_; }

    /// x in [min, max) distributed by the density; `pdf` gets its density, `offset` the
    /// piece it lies in.
    float sample_continuous(float u, float* pdf = nullptr, int* offset = nullptr) const;
    /// A piece index with probability |f_i| / Σ|f|; `u_remapped` is u rescaled to [0, 1)
    /// within the piece (reusable as a fresh uniform number).
    int sample_discrete(float u, float* pmf = nullptr, float* u_remapped = nullptr) const;

    /// Density at x (0 outside [min, max]).
    float pdf(float x) const;
    /// Probability of piece i under sample_discrete.
    float discrete_pmf(int i) const;

private:
    int find_piece(float u) const;

    std::vector<float> func_; // |f|, or all ones when f was all zero
    std::vector<double> cdf_; // size + 1 entries, cdf_[0] = 0, cdf_.back() = 1
    float min_ = 0.0f, max_ = 1.0f;
    double func_integral_ = 0.0; // ∫ func_ over [min, max]
    double integral_ = 0.0;
};

/// A piecewise-constant density over [0, 1]^2 proportional to |f| given as nv rows of nu
/// values (row-major, v = row), sampled by the marginal in v and the conditional in u
/// (pbrt-v4's PiecewiseConstant2D). For a lat-long environment map multiply each row by
/// sin(theta) first and divide the pdf by 2 pi^2 sin(theta) to get a solid-angle density.
class Distribution2D {
public:
    Distribution2D() = default;
    Distribution2D(std::span<const float> f, int nu, int nv);

    struct Sample {
        float u, v; // in [0, 1)^2
        float pdf;  // density with respect to area on [0, 1]^2
    };
    Sample sample(float u0, float u1) const;
    float pdf(float u, float v) const;
    double integral() const { return marginal_.integral(); }

private:
    std::vector<Distribution1D> conditional_;
    Distribution1D marginal_;
};

/// Veach's power heuristic with beta = 2: the MIS weight of a sample from strategy f
/// (nf samples, density f_pdf) against g. An infinite f_pdf (a delta) gets weight 1.
/// Inline: the renderer takes it twice per bounce.
inline float power_heuristic(int nf, float f_pdf, int ng, float g_pdf)
{
    const float f = static_cast<float>(nf) * f_pdf, g = static_cast<float>(ng) * g_pdf;
    if (std::isinf(f * f))
        return 1.0f;
    const float denom = f * f + g * g;
    return denom > 0.0f ? f * f / denom : 0.0f;
}
/// Veach's balance heuristic.
float balance_heuristic(int nf, float f_pdf, int ng, float g_pdf);

} // namespace patina
