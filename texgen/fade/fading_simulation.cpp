// Comparisons here raise no floating-point exception anyone looks at: with that known, the
// selects of the sublayer optics (two_flux.h) are branch-free and the kernels' loops have
// no library call or branch.
#pragma GCC optimize("no-trapping-math")
// Vec4 values passed between the kernels' inline functions: no ABI is involved.
#pragma GCC diagnostic ignored "-Wpsabi"

#include "texgen/fade/fading_simulation.h"

#include "texgen/fade/two_flux.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen::fade {

namespace {

// A block of kVecs vectors (16 wavelengths in double, 32 in float) goes through all
// sublayers at once: independent lanes for the recurrences of the adding method to
// overlap, and a block's rows (2-4 arrays of N + 1 rows of 128 bytes) stay in the L1 cache.
constexpr size_t kVecs = 4;
constexpr size_t kMaxBlock = 8 * kVecs;  // wavelengths are padded to whole float blocks

template <class V>
constexpr size_t kLanes = sizeof(V) / sizeof(typename LaneTraits<V>::Elem);

template <class V>
V splat(typename LaneTraits<V>::Elem x)
{
    V v = {};
    return v + x;
}

// (exp(-a T) - exp(-b T)) / (b - a) = exp(-a T) T phi((b - a) T), phi(x) = (1 - e^-x) / x:
// the product of a first-order chain parent -> product over one step, stable for a = b.
double chain_gain(double a, double b, double T)
{
    const double x = (b - a) * T;
    const double phi = std::abs(x) < 1e-8 ? 1.0 - 0.5 * x : -std::expm1(-x) / x;
    return std::exp(-a * T) * T * phi;
}

// What the kernels read of the simulation, in the kernel's precision (V: Vec4 or Vec8f).
template <class V>
struct KernelView {
    using E = typename LaneTraits<V>::Elem;
    size_t sublayers = 0, colorants = 0, vecs = 0;  // vecs: vectors per spectrum
    E dz = 0, inv_dz = 0;          // sublayer thickness (> 0) and its inverse
    const E* fractions = nullptr;  // [i * colorants + j]
    const V* absorption = nullptr;  // [j * vecs + v]
    const V* scattering = nullptr;
    const size_t* absorbers = nullptr;
    size_t n_absorbers = 0;
    const size_t* scatterers = nullptr;
    size_t n_scatterers = 0;
    const V* substrate = nullptr;  // [v]
};

// One solve of the two-flux system at every wavelength (step(), fluence_rates()).
template <class V>
struct SolveJob {
    const V* top = nullptr;           // [v]
    const V* bottom = nullptr;        // [v], or nullptr: no light from below
    const V* rates = nullptr;         // [k * vecs + v]
    size_t n_rates = 0;
    const char* block_has_rate = nullptr;  // skip blocks without (nullptr: none skipped)
    V* work = nullptr;                // 4 (N + 1) kVecs
    V* acc = nullptr;                 // [i * n_rates + k]: lane sums of rate x fluence
    double* fluence = nullptr;        // optional: [i * lanes * vecs + w]
    // The sublayer terms of the last solve, [((b * N + i) * 3 + term) * kVecs + v], reused
    // for the rows whose fractions are bitwise those of the last solve (same inputs, same
    // bits): row_same[i], valid for block b if block_fresh[b] (it was solved last time).
    // nullptr: no cache (the double kernel).
    V* terms_cache = nullptr;
    const char* row_same = nullptr;
    char* block_fresh = nullptr;
};

// The layer's R_top, T, R_bottom at every wavelength (spectra()).
struct FoldJob {
    double* r_top = nullptr;  // [w], padded
    double* t = nullptr;
    double* r_bottom = nullptr;
};

// Eqs. (12), (13), (22), (23): the terms of sublayer i for the kVecs vectors of a block
// from v0. The fractions and spectra are non-negative (validated), so are K and S.
template <class V>
[[gnu::always_inline]] inline void row_terms(const KernelView<V>& k, size_t i, size_t v0,
                                             SublayerTerms<V> (&out)[kVecs])
{
    using E = typename LaneTraits<V>::Elem;
    const E* f = k.fractions + i * k.colorants;
    V K[kVecs], S[kVecs];
    for (size_t v = 0; v < kVecs; ++v)
        K[v] = S[v] = splat<V>(0);
    for (size_t n = 0; n < k.n_absorbers; ++n) {
        const size_t j = k.absorbers[n];
        const V* a = k.absorption + j * k.vecs + v0;
        const E fj = f[j];
        for (size_t v = 0; v < kVecs; ++v)
            K[v] += fj * a[v];
    }
    for (size_t n = 0; n < k.n_scatterers; ++n) {
        const size_t j = k.scatterers[n];
        const V* s = k.scattering + j * k.vecs + v0;
        const E fj = f[j];
        for (size_t v = 0; v < kVecs; ++v)
            S[v] += fj * s[v];
    }
    for (size_t v = 0; v < kVecs; ++v)
        out[v] = sublayer_terms_nonnegative(K[v], S[v], k.dz, k.inv_dz);
}

// The two-flux solve of one block (solve_two_flux's sweeps, one wavelength per lane): the
// sublayer optics and the adding method from the ground up, then the irradiances from the
// top down, the fluence per sublayer and its products with the rate spectra.
template <class V, bool kBottom>
[[gnu::always_inline]] inline void solve_block(const KernelView<V>& k, const SolveJob<V>& job,
                                               size_t block)
{
    constexpr size_t L = kLanes<V>;
    const size_t N = k.sublayers;
    const size_t v0 = block * kVecs;
    V* r = job.work;                         // R_i, rows 0..N
    V* t_over_p = r + (N + 1) * kVecs;       // rows 0..N-1
    V* a_over_p = t_over_p + (N + 1) * kVecs;
    V* src = a_over_p + (N + 1) * kVecs;     // rows 0..N
    V r_below[kVecs], src_below[kVecs];
    for (size_t v = 0; v < kVecs; ++v) {
        r_below[v] = r[N * kVecs + v] = k.substrate[v0 + v];
        if constexpr (kBottom)
            src_below[v] = src[N * kVecs + v] = job.bottom[v0 + v];
    }
    const bool fresh = job.terms_cache && job.block_fresh[block] != 0;
    for (size_t i = N; i-- > 0;) {
        SublayerTerms<V> terms[kVecs];
        V* cache = job.terms_cache ? job.terms_cache + (block * N + i) * 3 * kVecs : nullptr;
        if (fresh && job.row_same[i]) {
            for (size_t v = 0; v < kVecs; ++v)
                terms[v] = {cache[v], cache[kVecs + v], cache[2 * kVecs + v]};
        } else {
            row_terms(k, i, v0, terms);
            for (size_t v = 0; job.terms_cache && v < kVecs; ++v) {
                cache[v] = terms[v].a;
                cache[kVecs + v] = terms[v].t;
                cache[2 * kVecs + v] = terms[v].d;
            }
        }
        for (size_t v = 0; v < kVecs; ++v) {
            const AddingStep<V> s = adding_step(terms[v], r_below[v]);
            r_below[v] = r[i * kVecs + v] = s.r;
            t_over_p[i * kVecs + v] = s.t_over_p;
            if constexpr (kBottom) {
                a_over_p[i * kVecs + v] = s.a_over_p;
                src_below[v] = src[i * kVecs + v] = s.t_over_p * src_below[v];
            }
        }
    }
    // Top down: E^d_0 = E_0, E^d_{i+1} = t/p E^d_i + a/p src_{i+1}, E^u_i = R_i E^d_i + src_i;
    // F_i = E^d_i + E^u_i + E^d_{i+1} + E^u_{i+1} (the 0.5 of the mean is in the rates).
    V down[kVecs], above[kVecs];  // E^d_i and E^d_i + E^u_i
    for (size_t v = 0; v < kVecs; ++v) {
        down[v] = job.top[v0 + v];
        V up = r[v] * down[v];
        if constexpr (kBottom)
            up += src[v];
        above[v] = down[v] + up;
    }
    for (size_t i = 0; i < N; ++i) {
        const size_t row = i * kVecs, next = (i + 1) * kVecs;
        V fluence[kVecs];
        for (size_t v = 0; v < kVecs; ++v) {
            V d = t_over_p[row + v] * down[v];
            if constexpr (kBottom)
                d += a_over_p[row + v] * src[next + v];
            V u = r[next + v] * d;
            if constexpr (kBottom)
                u += src[next + v];
            fluence[v] = above[v] + d + u;
            above[v] = d + u;
            down[v] = d;
        }
        for (size_t n = 0; n < job.n_rates; ++n) {
            const V* rate = job.rates + n * k.vecs + v0;
            V sum = rate[0] * fluence[0];
            for (size_t v = 1; v < kVecs; ++v)
                sum += rate[v] * fluence[v];
            job.acc[i * job.n_rates + n] += sum;
        }
        if (job.fluence)
            for (size_t v = 0; v < kVecs; ++v)
                for (size_t l = 0; l < L; ++l)
                    job.fluence[i * L * k.vecs + L * (v0 + v) + l] = 0.5 * fluence[v][l];
    }
}

template <class V>
[[gnu::always_inline]] inline void solve_blocks(const KernelView<V>& k, const SolveJob<V>& job)
{
    for (size_t b = 0; b < k.vecs / kVecs; ++b) {
        if (job.block_has_rate && !job.block_has_rate[b]) {
            job.block_fresh[b] = 0;
            continue;
        }
        // Unlit blocks have zero fluence everywhere.
        bool lit = false;
        for (size_t v = 0; v < kVecs; ++v)
            for (size_t l = 0; l < kLanes<V>; ++l)
                lit |= job.top[b * kVecs + v][l] != 0 ||
                       (job.bottom && job.bottom[b * kVecs + v][l] != 0);
        if (!lit && !job.fluence) {
            job.block_fresh[b] = 0;  // its cached terms are not updated
            continue;
        }
        if (job.bottom)
            solve_block<V, true>(k, job, b);
        else
            solve_block<V, false>(k, job, b);
        job.block_fresh[b] = 1;
    }
}

[[gnu::always_inline]] inline void fold_blocks(const KernelView<Vec4>& k, const FoldJob& job)
{
    for (size_t b = 0; b < k.vecs / kVecs; ++b) {
        const size_t v0 = b * kVecs;
        Vec4 r_top[kVecs], t[kVecs], r_bottom[kVecs];
        for (size_t v = 0; v < kVecs; ++v) {
            r_top[v] = r_bottom[v] = splat<Vec4>(0.0);
            t[v] = splat<Vec4>(1.0);
        }
        for (size_t i = 0; i < k.sublayers; ++i) {
            SublayerTerms<Vec4> terms[kVecs];
            row_terms(k, i, v0, terms);
            for (size_t v = 0; v < kVecs; ++v)
                fold_sublayer(r_top[v], t[v], r_bottom[v], terms[v].a, terms[v].t, terms[v].d);
        }
        for (size_t v = 0; v < kVecs; ++v)
            for (size_t l = 0; l < 4; ++l) {
                const size_t w = 4 * (v0 + v) + l;
                job.r_top[w] = r_top[v][l];
                job.t[w] = t[v][l];
                job.r_bottom[w] = r_bottom[v][l];
            }
    }
}

// The kernels compiled twice: for AVX2 + FMA (4 doubles or 8 floats per instruction) and
// for the x86-64 baseline (SSE2, half that); the caller picks by the CPU.
[[gnu::target("avx2,fma")]] void solve_avx2(const KernelView<Vec4>& k, const SolveJob<Vec4>& job)
{
    solve_blocks(k, job);
}
[[gnu::target("avx2,fma")]] void solve_avx2(const KernelView<Vec8f>& k,
                                            const SolveJob<Vec8f>& job)
{
    solve_blocks(k, job);
}
void solve_portable(const KernelView<Vec4>& k, const SolveJob<Vec4>& job) { solve_blocks(k, job); }
void solve_portable(const KernelView<Vec8f>& k, const SolveJob<Vec8f>& job)
{
    solve_blocks(k, job);
}
[[gnu::target("avx2,fma")]] void fold_avx2(const KernelView<Vec4>& k, const FoldJob& job)
{
    fold_blocks(k, job);
}
void fold_portable(const KernelView<Vec4>& k, const FoldJob& job) { fold_blocks(k, job); }

bool cpu_has_avx2_fma()
{
    static const bool has = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    }();
    return has;
}

template <class V>
double lane_sum(const V& v)
{
    double sum = 0.0;
    for (size_t l = 0; l < kLanes<V>; ++l)
        sum += v[l];
    return sum;
}

}  // namespace

bool FadeSimulation::kernel_available(Kernel kernel)
{
    return kernel == Kernel::portable || cpu_has_avx2_fma();
}

void FadeSimulation::set_kernel(Kernel kernel)
{
    if (!kernel_available(kernel))
        throw std::runtime_error("fade simulation: this CPU has no AVX2 + FMA");
    if (kernel != kernel_) {
        // Terms cached by the other build differ in rounding: recompute them all.
        std::fill(lanes64_.block_fresh.begin(), lanes64_.block_fresh.end(), 0);
        std::fill(lanes32_.block_fresh.begin(), lanes32_.block_fresh.end(), 0);
    }
    kernel_ = kernel;
}

FadeSimulation::FadeSimulation(const FadeMaterial& material, const WavelengthGrid& grid,
                               int sublayers)
    : grid_(grid), sublayers_(sublayers)
{
    material.validate();
    if (grid.nm.empty())
        throw std::runtime_error("fade simulation: empty wavelength grid");
    for (size_t w = 1; w < grid.nm.size(); ++w)
        if (!(grid.nm[w] > grid.nm[w - 1]))
            throw std::runtime_error("fade simulation: grid wavelengths must increase");
    if (sublayers < 1)
        throw std::runtime_error(fmt::format("fade simulation: sublayers = {} < 1", sublayers));
    kernel_ = cpu_has_avx2_fma() ? Kernel::avx2 : Kernel::portable;
    dz_ = material.thickness_m / sublayers;
    weights_ = grid.trapezoid_weights();
    const size_t W = grid.size();
    const size_t J = material.colorants.size();
    const size_t N = static_cast<size_t>(sublayers);
    const size_t Wp = padded_ = (W + kMaxBlock - 1) / kMaxBlock * kMaxBlock;
    absorption_.assign(J * Wp, 0.0);
    scattering_.assign(J * Wp, 0.0);
    product_.assign(J, -1);
    block_has_rate_.assign(Wp / (4 * kVecs), 0);
    auto add_rate = [&](size_t j, bool gain, const WavelengthRate& rate) {
        std::vector<double> spectrum(Wp, 0.0);
        for (size_t w = 0; w < W; ++w)
            // Eq. (14): the energy absorbed by colorant j, weighted by β_j(λ) (§3.1.2).
            spectrum[w] = 0.5 * (weights_[w] * rate.at(grid.nm[w]) * absorption_[j * Wp + w]);
        if (std::all_of(spectrum.begin(), spectrum.end(), [](double v) { return v == 0.0; }))
            return;  // this colorant never fades (or never breaks down): no work
        for (size_t w = 0; w < W; ++w)
            block_has_rate_[w / (4 * kVecs)] |= spectrum[w] != 0.0;
        rates_.insert(rates_.end(), spectrum.begin(), spectrum.end());
        rate_colorant_.push_back(j);
        rate_is_gain_.push_back(gain ? 1 : 0);
    };
    for (size_t j = 0; j < J; ++j) {
        const Colorant& c = material.colorants[j];
        colorant_names_.push_back(c.name);
        bool absorbs = false, scatters = false;
        for (size_t w = 0; w < W; ++w) {
            const double nm = grid.nm[w];
            absorption_[j * Wp + w] = c.absorption_per_m.at(nm);
            scattering_[j * Wp + w] = c.scattering_per_m.at(nm);
            absorbs |= absorption_[j * Wp + w] != 0.0;
            scatters |= scattering_[j * Wp + w] != 0.0;
        }
        // A colorant with a zero spectrum adds exactly 0 to Eqs. (12), (13): left out.
        if (absorbs)
            absorbers_.push_back(j);
        if (scatters)
            scatterers_.push_back(j);
    }
    for (size_t j = 0; j < J; ++j) {
        const Colorant& c = material.colorants[j];
        add_rate(j, false, c.fading);
        if (c.breakdown) {
            product_[j] = static_cast<int>(material.colorant_index(c.breakdown->product));
            add_rate(j, true, c.breakdown->rate);
        }
    }
    substrate_ = grid.sample(material.substrate_reflectance);
    substrate_.resize(Wp, 0.0);
    fractions_.resize(N * J);
    for (size_t i = 0; i < N; ++i)
        for (size_t j = 0; j < J; ++j)
            fractions_[i * J + j] = material.initial_fractions[j];
    init_lanes(lanes64_);
    init_lanes(lanes32_);
    loss_.assign(N * J, 0.0);
    gain_.assign(N * J, 0.0);
    start_.assign(J, 0.0);
}

template <class V>
void FadeSimulation::init_lanes(Lanes<V>& lanes) const
{
    using E = typename LaneTraits<V>::Elem;
    constexpr size_t L = kLanes<V>;
    const size_t N = static_cast<size_t>(sublayers_);
    lanes.vecs = padded_ / L;
    // Spectra of padded_ values each, one after the other, into vectors of L lanes.
    auto to_lanes = [&](const std::vector<double>& flat, typename Lanes<V>::Vector& out) {
        out.assign(flat.size() / L, splat<V>(0));
        for (size_t i = 0; i < flat.size(); ++i)
            out[i / L][i % L] = static_cast<E>(flat[i]);
    };
    to_lanes(absorption_, lanes.absorption);
    to_lanes(scattering_, lanes.scattering);
    to_lanes(rates_, lanes.rates);
    to_lanes(substrate_, lanes.substrate);
    lanes.work.assign(4 * (N + 1) * kVecs, splat<V>(0));
    lanes.acc.assign(N * rate_colorant_.size(), splat<V>(0));
    lanes.top.assign(lanes.vecs, splat<V>(0));
    lanes.bottom.assign(lanes.vecs, splat<V>(0));
    lanes.terms_cache.assign(sizeof(E) == sizeof(float) ? 3 * N * lanes.vecs : 0, splat<V>(0));
    lanes.row_same.assign(N, 0);
    lanes.block_fresh.assign(lanes.vecs / kVecs, 0);
    lanes.last_fractions.assign(fractions_.size(), 0);
}

void FadeSimulation::set_fractions(std::vector<double> fractions)
{
    if (fractions.size() != fractions_.size())
        throw std::runtime_error(fmt::format("fade simulation: {} fractions given, {} expected",
                                             fractions.size(), fractions_.size()));
    // The kernels rely on K, S >= 0 (row_terms).
    for (double f : fractions)
        if (!(f >= 0.0 && f <= 1.0))
            throw std::runtime_error(fmt::format("fade simulation: fraction {} not in [0, 1]", f));
    fractions_ = std::move(fractions);
}

void FadeSimulation::sublayer_optics_at(size_t w, std::span<double> rho,
                                        std::span<double> tau) const
{
    const std::vector<double> mu_a = absorption_profile(w), mu_s = scattering_profile(w);
    for (int i = 0; i < sublayers_; ++i) {
        const SublayerOptics o = sublayer_optics(mu_a[i], mu_s[i], dz_);
        rho[static_cast<size_t>(i)] = o.rho;
        tau[static_cast<size_t>(i)] = o.tau;
    }
}

void FadeSimulation::check_light(const Illumination& light) const
{
    const size_t W = grid_.size();
    if (light.top.size() != W || (!light.bottom.empty() && light.bottom.size() != W))
        throw std::runtime_error(fmt::format(
            "fade simulation: illumination has {} (top) and {} (bottom) values for {} "
            "wavelengths",
            light.top.size(), light.bottom.size(), W));
}

template <class V>
void FadeSimulation::solve(const Illumination& light, Lanes<V>& lanes, bool rates,
                           double* fluence) const
{
    using E = typename LaneTraits<V>::Elem;
    constexpr size_t L = kLanes<V>;
    const size_t N = static_cast<size_t>(sublayers_);
    const size_t J = colorants();
    for (size_t w = 0; w < padded_; ++w) {
        lanes.top[w / L][w % L] = w < light.top.size() ? static_cast<E>(light.top[w]) : E(0);
        lanes.bottom[w / L][w % L] =
            w < light.bottom.size() ? static_cast<E>(light.bottom[w]) : E(0);
    }
    const bool from_below =
        std::any_of(light.bottom.begin(), light.bottom.end(), [](double e) { return e != 0.0; });
    // The fractions in the kernel's precision; rows equal to the last solve's (in that
    // precision: float rows freeze sooner) keep their cached sublayer terms.
    lanes.fractions.assign(fractions_.begin(), fractions_.end());
    const E* fractions = lanes.fractions.data();
    for (size_t i = 0; i < N; ++i)
        lanes.row_same[i] = std::equal(&fractions[i * J], &fractions[(i + 1) * J],
                                       &lanes.last_fractions[i * J]);
    lanes.last_fractions = lanes.fractions;
    std::fill(lanes.acc.begin(), lanes.acc.end(), splat<V>(0));
    const KernelView<V> view{N,
                             J,
                             lanes.vecs,
                             static_cast<E>(dz_),
                             static_cast<E>(1.0 / dz_),
                             fractions,
                             lanes.absorption.data(),
                             lanes.scattering.data(),
                             absorbers_.data(),
                             absorbers_.size(),
                             scatterers_.data(),
                             scatterers_.size(),
                             lanes.substrate.data()};
    // Blocks are 16 (double) or 32 (float) wavelengths: block_has_rate_ is per 16.
    const char* block_has_rate = nullptr;
    if (rates && !fluence) {
        if constexpr (L == 4) {
            block_has_rate = block_has_rate_.data();
        } else {
            thread_local std::vector<char> pairs;
            pairs.assign(block_has_rate_.size() / 2, 0);
            for (size_t b = 0; b < block_has_rate_.size(); ++b)
                pairs[b / 2] |= block_has_rate_[b];
            block_has_rate = pairs.data();
        }
    }
    const SolveJob<V> job{lanes.top.data(),
                          from_below ? lanes.bottom.data() : nullptr,
                          lanes.rates.data(),
                          rates ? rate_colorant_.size() : 0,
                          block_has_rate,
                          lanes.work.data(),
                          lanes.acc.data(),
                          fluence,
                          // Double rows hardly ever freeze: the cache would cost more.
                          sizeof(E) == sizeof(float) ? lanes.terms_cache.data() : nullptr,
                          lanes.row_same.data(),
                          lanes.block_fresh.data()};
    if (kernel_ == Kernel::avx2)
        solve_avx2(view, job);
    else
        solve_portable(view, job);
}

void FadeSimulation::step(const Illumination& light, double dt_s)
{
    const size_t J = colorants();
    const size_t N = static_cast<size_t>(sublayers_);
    check_light(light);
    if (!(dt_s >= 0.0))
        throw std::runtime_error("fade simulation: negative time step");

    // Per sublayer and colorant: loss rate r = ∫ β a F dλ and gain rate ∫ γ a F dλ (1/s),
    // accumulated per lane by the kernel, the lanes summed here.
    std::fill(loss_.begin(), loss_.end(), 0.0);
    std::fill(gain_.begin(), gain_.end(), 0.0);
    const size_t n_rates = rate_colorant_.size();
    auto gather = [&](const auto& acc) {
        for (size_t i = 0; i < N; ++i)
            for (size_t n = 0; n < n_rates; ++n)
                (rate_is_gain_[n] ? gain_ : loss_)[i * J + rate_colorant_[n]] =
                    lane_sum(acc[i * n_rates + n]);
    };
    if (precision_ == Precision::float64) {
        solve(light, lanes64_, true, nullptr);
        gather(lanes64_.acc);
    } else {
        solve(light, lanes32_, true, nullptr);
        gather(lanes32_.acc);
    }

    // §4.2, Eq. (35) (first order: the exponent uses a = mu_a / f), and Eq. (15)'s
    // products, each integrated exactly over the step with the fluence held constant.
    for (size_t i = 0; i < N; ++i) {
        double* f = &fractions_[i * J];
        const double* r = &loss_[i * J];
        const double* g = &gain_[i * J];
        std::copy(f, f + J, start_.begin());
        for (size_t j = 0; j < J; ++j)
            if (r[j] != 0.0)  // exp(-0) = 1: nothing to do
                f[j] = start_[j] * std::exp(-r[j] * dt_s);
        for (size_t j = 0; j < J; ++j) {
            if (product_[j] < 0 || g[j] == 0.0 || start_[j] == 0.0)
                continue;
            const size_t k = static_cast<size_t>(product_[j]);
            f[k] += g[j] * start_[j] * chain_gain(r[j], r[k], dt_s);
        }
    }
}

std::vector<double> FadeSimulation::fluence_rates(const Illumination& light) const
{
    check_light(light);
    const size_t N = static_cast<size_t>(sublayers_);
    const size_t W = grid_.size();
    std::vector<double> padded(N * padded_, 0.0);
    if (precision_ == Precision::float64) {
        Lanes<Vec4> lanes = lanes64_;  // scratch of its own: this is const
        solve(light, lanes, false, padded.data());
    } else {
        Lanes<Vec8f> lanes = lanes32_;
        solve(light, lanes, false, padded.data());
    }
    std::vector<double> out(N * W);
    for (size_t i = 0; i < N; ++i)
        std::copy_n(&padded[i * padded_], W, &out[i * W]);
    return out;
}

void FadeSimulation::run(const Illumination& light, double duration_s, int steps)
{
    if (steps < 1)
        throw std::runtime_error("fade simulation: steps must be >= 1");
    for (int s = 0; s < steps; ++s)
        step(light, duration_s / steps);
}

LayerSpectra FadeSimulation::spectra() const
{
    const size_t W = grid_.size();
    std::vector<double> r_top(padded_), t(padded_), r_bottom(padded_);
    const KernelView<Vec4> view{static_cast<size_t>(sublayers_),
                                colorants(),
                                lanes64_.vecs,
                                dz_,
                                1.0 / dz_,
                                fractions_.data(),
                                lanes64_.absorption.data(),
                                lanes64_.scattering.data(),
                                absorbers_.data(),
                                absorbers_.size(),
                                scatterers_.data(),
                                scatterers_.size(),
                                lanes64_.substrate.data()};
    const FoldJob job{r_top.data(), t.data(), r_bottom.data()};
    if (kernel_ == Kernel::avx2)
        fold_avx2(view, job);
    else
        fold_portable(view, job);
    LayerSpectra out;
    out.r_top.assign(r_top.begin(), r_top.begin() + W);
    out.t.assign(t.begin(), t.begin() + W);
    out.r_bottom.assign(r_bottom.begin(), r_bottom.begin() + W);
    out.reflectance.resize(W);
    for (size_t w = 0; w < W; ++w)
        out.reflectance[w] = reflectance_over({r_top[w], t[w], r_bottom[w]}, substrate_[w]);
    return out;
}

std::vector<double> FadeSimulation::absorption_profile(size_t w) const
{
    const size_t J = colorants();
    std::vector<double> out(static_cast<size_t>(sublayers_), 0.0);
    for (size_t i = 0; i < out.size(); ++i)
        for (size_t j = 0; j < J; ++j)
            out[i] += fractions_[i * J + j] * absorption_[j * padded_ + w];
    return out;
}

std::vector<double> FadeSimulation::scattering_profile(size_t w) const
{
    const size_t J = colorants();
    std::vector<double> out(static_cast<size_t>(sublayers_), 0.0);
    for (size_t i = 0; i < out.size(); ++i)
        for (size_t j = 0; j < J; ++j)
            out[i] += fractions_[i * J + j] * scattering_[j * padded_ + w];
    return out;
}

std::vector<double> FadeSimulation::fluence_rate(const Illumination& light, size_t w) const
{
    const size_t N = static_cast<size_t>(sublayers_);
    std::vector<double> rho(N), tau(N), down(N + 1), up(N + 1), fluence(N);
    sublayer_optics_at(w, rho, tau);
    const double bottom = light.bottom.empty() ? 0.0 : light.bottom.at(w);
    solve_two_flux(rho, tau, {light.top.at(w), bottom, substrate_[w]}, down, up);
    sublayer_fluence_rate(down, up, fluence);
    return fluence;
}

}  // namespace patina::texgen::fade
