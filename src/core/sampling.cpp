// PCG32, hashing, piecewise-constant distributions and MIS heuristics.
#include "core/sampling.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace patina {
namespace {

    // pcg-c's constants (pcg_basic.h: PCG32_INITIALIZER and the 64-bit LCG multiplier).
    constexpr uint64_t kPcgMult = 0x5851f42d4c957f2dULL;
    constexpr uint64_t kPcgDefaultState = 0x853c49e6748fea9bULL;
    constexpr uint64_t kPcgDefaultStream = 0xda3e39cb94b95bdbULL;
    constexpr float kOneMinusEpsilon = 0x1.fffffep-1f;

} // namespace

Pcg32::Pcg32() : state_(kPcgDefaultState), inc_(kPcgDefaultStream) {}

uint32_t Pcg32::uniform_u32(uint32_t bound)
{
    // Reject the low 2^32 mod bound values so every residue is equally likely.
    const uint32_t threshold = (~bound + 1u) % bound;
    for (;;) {
        const uint32_t r = uniform_u32();
        if (r >= threshold)
            return r % bound;
    }
}

double Pcg32::uniform_double()
{
    const uint64_t bits = (static_cast<uint64_t>(uniform_u32()) << 32) | uniform_u32();
    return static_cast<double>(bits >> 11) * 0x1p-53;
}

void Pcg32::advance(int64_t delta)
{
    // Brown 1994, "Random number generation with arbitrary strides": compose the LCG step
    // with itself by repeated squaring; a negative delta wraps modulo 2^64.
    uint64_t cur_mult = kPcgMult, cur_plus = inc_, acc_mult = 1u, acc_plus = 0u;
    auto d = static_cast<uint64_t>(delta);
    while (d > 0) {
        if (d & 1) {
            acc_mult *= cur_mult;
            acc_plus = acc_plus * cur_mult + cur_plus;
        }
        cur_plus = (cur_mult + 1) * cur_plus;
        cur_mult *= cur_mult;
        d /= 2;
    }
    state_ = acc_mult * state_ + acc_plus;
}

uint64_t hash_values(std::span<const uint64_t> values)
{
    // Fold each value into the running hash through the bijective mixer; the position
    // enters through the golden-ratio increment, so (a, b) and (b, a) differ.
    uint64_t h = 0x9e3779b97f4a7c15ULL * (values.size() + 1);
    for (uint64_t v : values)
        h = mix_bits(h ^ mix_bits(v + 0x9e3779b97f4a7c15ULL)) + 0x632be59bd9b4e019ULL;
    return mix_bits(h);
}

Pcg32 pixel_sample_rng(uint64_t seed, int x, int y, uint64_t sample_index)
{
    // The pixel picks the stream, a hash of the sample index the starting state: as
    // independent as advancing by sample_index * 65536, without the O(log n) jump per sample.
    return sample_rng(pixel_stream(seed, x, y), seed, sample_index);
}

uint64_t pixel_stream(uint64_t seed, int x, int y)
{
    return hash_values(seed, static_cast<uint32_t>(x), static_cast<uint32_t>(y));
}

Distribution1D::Distribution1D(std::span<const float> f, float min, float max)
    : func_(f.begin(), f.end()), min_(min), max_(max)
{
    if (!(max > min))
        throw std::invalid_argument("Distribution1D: empty domain");
    if (func_.empty())
        func_.assign(1, 0.0f);
    for (float& v : func_)
        v = std::isfinite(v) ? std::abs(v) : 0.0f;
    const int n = size();
    const double width = (static_cast<double>(max_) - min_) / n;
    // Running sum in double so long rows (environment maps) keep their precision.
    cdf_.assign(n + 1, 0.0);
    for (int i = 0; i < n; ++i)
        cdf_[i + 1] = cdf_[i] + func_[i] * width;
    integral_ = cdf_[n];
    if (integral_ <= 0.0) {
        // Nothing to importance-sample: fall back to the uniform density.
        std::fill(func_.begin(), func_.end(), 1.0f);
        for (int i = 0; i <= n; ++i)
            cdf_[i] = static_cast<double>(i) / n;
        func_integral_ = max_ - min_;
    } else {
        for (double& c : cdf_)
            c /= integral_;
        func_integral_ = integral_;
    }
    cdf_[n] = 1.0;
}

int Distribution1D::find_piece(float u) const
{
    // Largest i with cdf[i] <= u, skipping zero-width pieces (f_i = 0 is never chosen).
    const auto it = std::upper_bound(cdf_.begin(), cdf_.end(), static_cast<double>(u));
    return std::clamp(static_cast<int>(it - cdf_.begin()) - 1, 0, size() - 1);
}

float Distribution1D::sample_continuous(float u, float* pdf, int* offset) const
{
    const int o = find_piece(u);
    const double width = cdf_[o + 1] - cdf_[o];
    const double du = width > 0.0 ? (u - cdf_[o]) / width : 0.0;
    if (pdf)
        *pdf = static_cast<float>(func_[o] / func_integral_);
    if (offset)
        *offset = o;
    const double t = (o + std::clamp(du, 0.0, 1.0)) / size();
    const float x = static_cast<float>(min_ + t * (static_cast<double>(max_) - min_));
    return std::min(x, std::nextafter(max_, min_));
}

int Distribution1D::sample_discrete(float u, float* pmf, float* u_remapped) const
{
    const int o = find_piece(u);
    const double p = cdf_[o + 1] - cdf_[o];
    if (pmf)
        *pmf = static_cast<float>(p);
    if (u_remapped)
        *u_remapped =
            p > 0.0 ? std::min(kOneMinusEpsilon, static_cast<float>((u - cdf_[o]) / p)) : 0.0f;
    return o;
}

float Distribution1D::pdf(float x) const
{
    if (!(x >= min_ && x <= max_))
        return 0.0f;
    const int n = size();
    const int o = std::clamp(static_cast<int>((x - min_) / (max_ - min_) * n), 0, n - 1);
    return static_cast<float>(func_[o] / func_integral_);
}

float Distribution1D::discrete_pmf(int i) const
{
    if (i < 0 || i >= size())
        return 0.0f;
    return static_cast<float>(cdf_[i + 1] - cdf_[i]);
}

Distribution2D::Distribution2D(std::span<const float> f, int nu, int nv)
{
    if (nu <= 0 || nv <= 0 || f.size() != static_cast<size_t>(nu) * nv)
        throw std::invalid_argument("Distribution2D: f must hold nu * nv values");
    conditional_.reserve(nv);
    std::vector<float> row_integrals(nv);
    for (int v = 0; v < nv; ++v) {
        conditional_.emplace_back(f.subspan(static_cast<size_t>(v) * nu, nu));
        row_integrals[v] = static_cast<float>(conditional_.back().integral());
    }
    marginal_ = Distribution1D(row_integrals);
}

Distribution2D::Sample Distribution2D::sample(float u0, float u1) const
{
    // pbrt-v4 PiecewiseConstant2D::Sample: the row by the marginal, then u within it.
    float pdf_v = 0.0f, pdf_u = 0.0f;
    int row = 0;
    const float v = marginal_.sample_continuous(u1, &pdf_v, &row);
    const float u = conditional_[row].sample_continuous(u0, &pdf_u);
    return {u, v, pdf_u * pdf_v};
}

float Distribution2D::pdf(float u, float v) const
{
    if (!(u >= 0.0f && u <= 1.0f && v >= 0.0f && v <= 1.0f))
        return 0.0f;
    const int nv = static_cast<int>(conditional_.size());
    const int row = std::clamp(static_cast<int>(v * nv), 0, nv - 1);
    return marginal_.pdf(v) * conditional_[row].pdf(u);
}

float balance_heuristic(int nf, float f_pdf, int ng, float g_pdf)
{
    const float f = static_cast<float>(nf) * f_pdf, g = static_cast<float>(ng) * g_pdf;
    if (std::isinf(f))
        return 1.0f;
    return f + g > 0.0f ? f / (f + g) : 0.0f;
}

} // namespace patina
