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

// A block of kVecs Vec4 (16 wavelengths) goes through all sublayers at once: independent
// lanes for the recurrences of the adding method to overlap, and a block's rows (2-4
// arrays of N + 1 rows of 128 bytes) stay in the L1 cache.
constexpr size_t kVecs = 4;
constexpr size_t kBlock = 4 * kVecs;

Vec4 splat(double x) { return Vec4{x, x, x, x}; }

// (exp(-a T) - exp(-b T)) / (b - a) = exp(-a T) T phi((b - a) T), phi(x) = (1 - e^-x) / x:
// the product of a first-order chain parent -> product over one step, stable for a = b.
double chain_gain(double a, double b, double T)
{
    const double x = (b - a) * T;
    const double phi = std::abs(x) < 1e-8 ? 1.0 - 0.5 * x : -std::expm1(-x) / x;
    return std::exp(-a * T) * T * phi;
}

// What the kernels read of the simulation.
struct KernelView {
    size_t sublayers = 0, colorants = 0, vecs = 0;
    double dz = 0.0;
    const double* fractions = nullptr;  // [i * colorants + j]
    const Vec4* absorption = nullptr;   // [j * vecs + v]
    const Vec4* scattering = nullptr;
    const size_t* absorbers = nullptr;
    size_t n_absorbers = 0;
    const size_t* scatterers = nullptr;
    size_t n_scatterers = 0;
    const Vec4* substrate = nullptr;    // [v]
};

// One solve of the two-flux system at every wavelength (step(), fluence_rates()).
struct SolveJob {
    const Vec4* top = nullptr;        // [v]
    const Vec4* bottom = nullptr;     // [v], or nullptr: no light from below
    const Vec4* rates = nullptr;      // [k * vecs + v]
    size_t n_rates = 0;
    const char* block_has_rate = nullptr;  // skip blocks without (nullptr: none skipped)
    Vec4* work = nullptr;             // 4 (N + 1) kVecs
    Vec4* acc = nullptr;              // [i * n_rates + k]: lane sums of rate x fluence
    double* fluence = nullptr;        // optional: [i * 4 vecs + w]
};

// The layer's R_top, T, R_bottom at every wavelength (spectra()).
struct FoldJob {
    double* r_top = nullptr;  // [w], padded
    double* t = nullptr;
    double* r_bottom = nullptr;
};

// Eqs. (12), (13), (22), (23): sublayer i's terms for the block's kVecs vectors from v0.
[[gnu::always_inline]] inline void block_terms(const KernelView& k, size_t i, size_t v0,
                                               SublayerTerms<Vec4> (&out)[kVecs])
{
    Vec4 K[kVecs] = {}, S[kVecs] = {};
    const double* f = k.fractions + i * k.colorants;
    for (size_t n = 0; n < k.n_absorbers; ++n) {
        const size_t j = k.absorbers[n];
        const Vec4* a = k.absorption + j * k.vecs + v0;
        for (size_t v = 0; v < kVecs; ++v)
            K[v] += f[j] * a[v];
    }
    for (size_t n = 0; n < k.n_scatterers; ++n) {
        const size_t j = k.scatterers[n];
        const Vec4* s = k.scattering + j * k.vecs + v0;
        for (size_t v = 0; v < kVecs; ++v)
            S[v] += f[j] * s[v];
    }
    for (size_t v = 0; v < kVecs; ++v)
        out[v] = sublayer_terms(K[v], S[v], k.dz);
}

// The two-flux solve of one block (solve_two_flux's sweeps, four wavelengths per lane):
// the sublayer optics and the adding method from the ground up, then the irradiances from
// the top down, the fluence per sublayer and its products with the rate spectra.
template <bool kBottom>
[[gnu::always_inline]] inline void solve_block(const KernelView& k, const SolveJob& job,
                                               size_t block)
{
    const size_t N = k.sublayers;
    const size_t v0 = block * kVecs;
    Vec4* r = job.work;                  // R_i, rows 0..N
    Vec4* t_over_p = r + (N + 1) * kVecs;  // rows 0..N-1
    Vec4* a_over_p = t_over_p + (N + 1) * kVecs;
    Vec4* src = a_over_p + (N + 1) * kVecs;  // rows 0..N
    Vec4 r_below[kVecs], src_below[kVecs];
    for (size_t v = 0; v < kVecs; ++v) {
        r_below[v] = r[N * kVecs + v] = k.substrate[v0 + v];
        if constexpr (kBottom)
            src_below[v] = src[N * kVecs + v] = job.bottom[v0 + v];
    }
    for (size_t i = N; i-- > 0;) {
        SublayerTerms<Vec4> terms[kVecs];
        block_terms(k, i, v0, terms);
        for (size_t v = 0; v < kVecs; ++v) {
            const AddingStep<Vec4> s = adding_step(terms[v], r_below[v]);
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
    Vec4 down[kVecs], above[kVecs];  // E^d_i and E^d_i + E^u_i
    for (size_t v = 0; v < kVecs; ++v) {
        down[v] = job.top[v0 + v];
        Vec4 up = r[v] * down[v];
        if constexpr (kBottom)
            up += src[v];
        above[v] = down[v] + up;
    }
    for (size_t i = 0; i < N; ++i) {
        const size_t row = i * kVecs, next = (i + 1) * kVecs;
        Vec4 fluence[kVecs];
        for (size_t v = 0; v < kVecs; ++v) {
            Vec4 d = t_over_p[row + v] * down[v];
            if constexpr (kBottom)
                d += a_over_p[row + v] * src[next + v];
            Vec4 u = r[next + v] * d;
            if constexpr (kBottom)
                u += src[next + v];
            fluence[v] = above[v] + d + u;
            above[v] = d + u;
            down[v] = d;
        }
        for (size_t n = 0; n < job.n_rates; ++n) {
            const Vec4* rate = job.rates + n * k.vecs + v0;
            Vec4 sum = rate[0] * fluence[0];
            for (size_t v = 1; v < kVecs; ++v)
                sum += rate[v] * fluence[v];
            job.acc[i * job.n_rates + n] += sum;
        }
        if (job.fluence)
            for (size_t v = 0; v < kVecs; ++v)
                for (size_t l = 0; l < 4; ++l)
                    job.fluence[i * 4 * k.vecs + 4 * (v0 + v) + l] = 0.5 * fluence[v][l];
    }
}

[[gnu::always_inline]] inline void solve_blocks(const KernelView& k, const SolveJob& job)
{
    for (size_t b = 0; b < k.vecs / kVecs; ++b) {
        if (job.block_has_rate && !job.block_has_rate[b])
            continue;
        // Unlit blocks have zero fluence everywhere.
        bool lit = false;
        for (size_t v = 0; v < kVecs; ++v)
            for (size_t l = 0; l < 4; ++l)
                lit |= job.top[b * kVecs + v][l] != 0.0 ||
                       (job.bottom && job.bottom[b * kVecs + v][l] != 0.0);
        if (!lit && !job.fluence)
            continue;
        if (job.bottom)
            solve_block<true>(k, job, b);
        else
            solve_block<false>(k, job, b);
    }
}

[[gnu::always_inline]] inline void fold_blocks(const KernelView& k, const FoldJob& job)
{
    for (size_t b = 0; b < k.vecs / kVecs; ++b) {
        const size_t v0 = b * kVecs;
        Vec4 r_top[kVecs], t[kVecs], r_bottom[kVecs];
        for (size_t v = 0; v < kVecs; ++v) {
            r_top[v] = r_bottom[v] = splat(0.0);
            t[v] = splat(1.0);
        }
        for (size_t i = 0; i < k.sublayers; ++i) {
            SublayerTerms<Vec4> terms[kVecs];
            block_terms(k, i, v0, terms);
            for (size_t v = 0; v < kVecs; ++v)
                fold_sublayer(r_top[v], t[v], r_bottom[v], terms[v].a, terms[v].t,
                              terms[v].d);
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

// The kernels compiled twice: for AVX2 + FMA (4 doubles per instruction) and for the
// x86-64 baseline (SSE2, 2 per instruction); the caller picks by the CPU.
[[gnu::target("avx2,fma")]] void solve_avx2(const KernelView& k, const SolveJob& job)
{
    solve_blocks(k, job);
}
void solve_portable(const KernelView& k, const SolveJob& job) { solve_blocks(k, job); }
[[gnu::target("avx2,fma")]] void fold_avx2(const KernelView& k, const FoldJob& job)
{
    fold_blocks(k, job);
}
void fold_portable(const KernelView& k, const FoldJob& job) { fold_blocks(k, job); }

bool cpu_has_avx2_fma()
{
    static const bool has = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx2") && __builtin_cpu_supports("fma");
    }();
    return has;
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
    padded_ = (W + kBlock - 1) / kBlock * kBlock;
    vecs_ = padded_ / 4;
    const size_t blocks = padded_ / kBlock;
    absorption_.assign(J * vecs_, splat(0.0));
    scattering_.assign(J * vecs_, splat(0.0));
    product_.assign(J, -1);
    block_has_rate_.assign(blocks, 0);
    // Lane w % 4 of vector w / 4 of spectrum k.
    auto lane = [&](Vec4Vector& s, size_t k, size_t w) -> double& {
        return reinterpret_cast<double*>(&s[k * vecs_])[w];
    };
    auto add_rate = [&](size_t j, bool gain, const WavelengthRate& rate) {
        Vec4Vector spectrum(vecs_, splat(0.0));
        bool any = false;
        for (size_t w = 0; w < W; ++w) {
            // Eq. (14): the energy absorbed by colorant j, weighted by β_j(λ) (§3.1.2).
            const double a = lane(absorption_, j, w);
            const double value = 0.5 * (weights_[w] * rate.at(grid.nm[w]) * a);
            lane(spectrum, 0, w) = value;
            if (value != 0.0) {
                any = true;
                block_has_rate_[w / kBlock] = 1;
            }
        }
        if (!any)
            return;  // this colorant never fades (or never breaks down): no work
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
            lane(absorption_, j, w) = c.absorption_per_m.at(nm);
            lane(scattering_, j, w) = c.scattering_per_m.at(nm);
            absorbs |= lane(absorption_, j, w) != 0.0;
            scatters |= lane(scattering_, j, w) != 0.0;
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
    substrate_.assign(vecs_, splat(0.0));
    const std::vector<double> substrate = grid.sample(material.substrate_reflectance);
    for (size_t w = 0; w < W; ++w)
        lane(substrate_, 0, w) = substrate[w];
    fractions_.resize(N * J);
    for (size_t i = 0; i < N; ++i)
        for (size_t j = 0; j < J; ++j)
            fractions_[i * J + j] = material.initial_fractions[j];
    work_.assign(4 * (N + 1) * kVecs, splat(0.0));
    acc_.assign(N * rate_colorant_.size(), splat(0.0));
    top_.assign(vecs_, splat(0.0));
    bottom_.assign(vecs_, splat(0.0));
    loss_.assign(N * J, 0.0);
    gain_.assign(N * J, 0.0);
    start_.assign(J, 0.0);
}

void FadeSimulation::set_fractions(std::vector<double> fractions)
{
    if (fractions.size() != fractions_.size())
        throw std::runtime_error(fmt::format("fade simulation: {} fractions given, {} expected",
                                             fractions.size(), fractions_.size()));
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

void FadeSimulation::load_light(const Illumination& light, Vec4Vector& top,
                                Vec4Vector& bottom) const
{
    top.assign(vecs_, splat(0.0));
    bottom.assign(vecs_, splat(0.0));
    double* t = reinterpret_cast<double*>(top.data());
    double* b = reinterpret_cast<double*>(bottom.data());
    std::copy(light.top.begin(), light.top.end(), t);
    std::copy(light.bottom.begin(), light.bottom.end(), b);
}

void FadeSimulation::step(const Illumination& light, double dt_s)
{
    const size_t J = colorants();
    const size_t N = static_cast<size_t>(sublayers_);
    check_light(light);
    if (!(dt_s >= 0.0))
        throw std::runtime_error("fade simulation: negative time step");

    // Per sublayer and colorant: loss rate r = ∫ β a F dλ and gain rate ∫ γ a F dλ (1/s),
    // accumulated per lane by the kernel, the four lanes summed here.
    load_light(light, top_, bottom_);
    const bool from_below =
        std::any_of(light.bottom.begin(), light.bottom.end(), [](double e) { return e != 0.0; });
    std::fill(acc_.begin(), acc_.end(), splat(0.0));
    const KernelView view{N,
                          J,
                          vecs_,
                          dz_,
                          fractions_.data(),
                          absorption_.data(),
                          scattering_.data(),
                          absorbers_.data(),
                          absorbers_.size(),
                          scatterers_.data(),
                          scatterers_.size(),
                          substrate_.data()};
    const size_t n_rates = rate_colorant_.size();
    const SolveJob job{top_.data(),   from_below ? bottom_.data() : nullptr,
                       rates_.data(), n_rates,
                       block_has_rate_.data(), work_.data(),
                       acc_.data(),   nullptr};
    if (kernel_ == Kernel::avx2)
        solve_avx2(view, job);
    else
        solve_portable(view, job);
    std::fill(loss_.begin(), loss_.end(), 0.0);
    std::fill(gain_.begin(), gain_.end(), 0.0);
    for (size_t i = 0; i < N; ++i)
        for (size_t n = 0; n < n_rates; ++n) {
            const Vec4 a = acc_[i * n_rates + n];
            const double sum = (a[0] + a[1]) + (a[2] + a[3]);
            (rate_is_gain_[n] ? gain_ : loss_)[i * J + rate_colorant_[n]] = sum;
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
    Vec4Vector top, bottom, work(4 * (N + 1) * kVecs, splat(0.0));
    load_light(light, top, bottom);
    std::vector<double> padded(N * padded_, 0.0);
    const KernelView view{N,
                          colorants(),
                          vecs_,
                          dz_,
                          fractions_.data(),
                          absorption_.data(),
                          scattering_.data(),
                          absorbers_.data(),
                          absorbers_.size(),
                          scatterers_.data(),
                          scatterers_.size(),
                          substrate_.data()};
    const SolveJob job{top.data(), light.bottom.empty() ? nullptr : bottom.data(),
                       nullptr,    0,
                       nullptr,    work.data(),
                       nullptr,    padded.data()};
    if (kernel_ == Kernel::avx2)
        solve_avx2(view, job);
    else
        solve_portable(view, job);
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
    const KernelView view{static_cast<size_t>(sublayers_),
                          colorants(),
                          vecs_,
                          dz_,
                          fractions_.data(),
                          absorption_.data(),
                          scattering_.data(),
                          absorbers_.data(),
                          absorbers_.size(),
                          scatterers_.data(),
                          scatterers_.size(),
                          substrate_.data()};
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
        out.reflectance[w] =
            reflectance_over({r_top[w], t[w], r_bottom[w]}, substrate_[w / 4][w % 4]);
    return out;
}

std::vector<double> FadeSimulation::absorption_profile(size_t w) const
{
    const size_t J = colorants();
    std::vector<double> out(static_cast<size_t>(sublayers_), 0.0);
    for (size_t i = 0; i < out.size(); ++i)
        for (size_t j = 0; j < J; ++j)
            out[i] += fractions_[i * J + j] * absorption_[j * vecs_ + w / 4][w % 4];
    return out;
}

std::vector<double> FadeSimulation::scattering_profile(size_t w) const
{
    const size_t J = colorants();
    std::vector<double> out(static_cast<size_t>(sublayers_), 0.0);
    for (size_t i = 0; i < out.size(); ++i)
        for (size_t j = 0; j < J; ++j)
            out[i] += fractions_[i * J + j] * scattering_[j * vecs_ + w / 4][w % 4];
    return out;
}

std::vector<double> FadeSimulation::fluence_rate(const Illumination& light, size_t w) const
{
    const size_t N = static_cast<size_t>(sublayers_);
    std::vector<double> rho(N), tau(N), down(N + 1), up(N + 1), fluence(N);
    sublayer_optics_at(w, rho, tau);
    const double bottom = light.bottom.empty() ? 0.0 : light.bottom.at(w);
    solve_two_flux(rho, tau, {light.top.at(w), bottom, substrate_[w / 4][w % 4]}, down, up);
    sublayer_fluence_rate(down, up, fluence);
    return fluence;
}

}  // namespace patina::texgen::fade
