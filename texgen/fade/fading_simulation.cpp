// Comparisons here raise no floating-point exception anyone looks at: with that known, the
// selects of the sublayer optics (two_flux.h) become branch-free and the
// per-wavelength loops have no library call or branch and vectorise.
#pragma GCC optimize("no-trapping-math")

#include "texgen/fade/fading_simulation.h"

#include "texgen/fade/two_flux.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen::fade {

namespace {

// Wavelengths are processed in blocks of kBlock: every loop over a block is branch-free and
// vectorises (sublayer optics, the block Thomas sweeps, the fluence).
constexpr size_t kBlock = 16;

// (exp(-a T) - exp(-b T)) / (b - a) = exp(-a T) T phi((b - a) T), phi(x) = (1 - e^-x) / x:
// the product of a first-order chain parent -> product over one step, stable for a = b.
double chain_gain(double a, double b, double T)
{
    const double x = (b - a) * T;
    const double phi = std::abs(x) < 1e-8 ? 1.0 - 0.5 * x : -std::expm1(-x) / x;
    return std::exp(-a * T) * T * phi;
}

}  // namespace

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
    dz_ = material.thickness_m / sublayers;
    weights_ = grid.trapezoid_weights();
    const size_t W = grid.size();
    padded_ = (W + kBlock - 1) / kBlock * kBlock;
    const size_t Wp = padded_;
    const size_t J = material.colorants.size();
    absorption_.assign(J * Wp, 0.0);
    scattering_.assign(J * Wp, 0.0);
    fading_.assign(J * Wp, 0.0);
    production_.assign(J * Wp, 0.0);
    product_.assign(J, -1);
    for (size_t j = 0; j < J; ++j) {
        const Colorant& c = material.colorants[j];
        colorant_names_.push_back(c.name);
        if (c.breakdown)
            product_[j] = static_cast<int>(material.colorant_index(c.breakdown->product));
        for (size_t w = 0; w < W; ++w) {
            const double nm = grid.nm[w];
            const double a = c.absorption_per_m.at(nm);
            absorption_[j * Wp + w] = a;
            scattering_[j * Wp + w] = c.scattering_per_m.at(nm);
            // Eq. (14): the energy absorbed by colorant j, weighted by β_j(λ) (§3.1.2).
            fading_[j * Wp + w] = weights_[w] * c.fading.at(nm) * a;
            if (c.breakdown)
                production_[j * Wp + w] = weights_[w] * c.breakdown->rate.at(nm) * a;
        }
    }
    substrate_ = grid.sample(material.substrate_reflectance);
    fractions_.resize(static_cast<size_t>(sublayers) * J);
    for (int i = 0; i < sublayers; ++i)
        for (size_t j = 0; j < J; ++j)
            fractions_[static_cast<size_t>(i) * J + j] = material.initial_fractions[j];
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
    const size_t W = padded_;
    const size_t J = colorants();
    for (int i = 0; i < sublayers_; ++i) {
        // Eqs. (12), (13): the mixture's coefficients are the fraction-weighted sums.
        const double* f = &fractions_[static_cast<size_t>(i) * J];
        double mu_a = 0.0, mu_s = 0.0;
        for (size_t j = 0; j < J; ++j) {
            mu_a += f[j] * absorption_[j * W + w];
            mu_s += f[j] * scattering_[j * W + w];
        }
        const SublayerOptics o = sublayer_optics(mu_a, mu_s, dz_);
        rho[static_cast<size_t>(i)] = o.rho;
        tau[static_cast<size_t>(i)] = o.tau;
    }
}

void FadeSimulation::step(const Illumination& light, double dt_s)
{
    const size_t W = grid_.size();
    const size_t J = colorants();
    const size_t N = static_cast<size_t>(sublayers_);
    if (light.top.size() != W || (!light.bottom.empty() && light.bottom.size() != W))
        throw std::runtime_error(fmt::format(
            "fade simulation: illumination has {} (top) and {} (bottom) values for {} "
            "wavelengths",
            light.top.size(), light.bottom.size(), W));
    if (!(dt_s >= 0.0))
        throw std::runtime_error("fade simulation: negative time step");

    // Per sublayer and colorant: loss rate r = ∫ β a F dλ and gain rate ∫ γ a F dλ (1/s).
    std::vector<double> loss(N * J, 0.0), gain(N * J, 0.0);
    std::vector<char> fades(J), produces(J);
    for (size_t j = 0; j < J; ++j) {
        fades[j] = std::any_of(&fading_[j * padded_], &fading_[(j + 1) * padded_],
                               [](double v) { return v != 0.0; });
        produces[j] = std::any_of(&production_[j * padded_], &production_[(j + 1) * padded_],
                                  [](double v) { return v != 0.0; });
    }
    // Per block of wavelengths, [row * kBlock + b] with boundary (or sublayer) i in row
    // i + 1 and row 0 all zeros, so every row has a row above it and the loops over a
    // block are branch-free and vectorise: sublayer optics, then the block Thomas
    // elimination of two_flux.h (the same formulas, one wavelength per lane).
    const size_t rows = N + 2;
    thread_local std::vector<double> work;
    work.assign(8 * rows * kBlock, 0.0);
    double* rho = work.data();         // rows 1..N: sublayers, row N + 1: the ground
    double* tau = rho + rows * kBlock;
    double* c0 = tau + rows * kBlock;
    double* c1 = c0 + rows * kBlock;
    double* g0 = c1 + rows * kBlock;
    double* g1 = g0 + rows * kBlock;
    double* up = g1 + rows * kBlock;
    double* down = up + rows * kBlock;
    const double dz = dz_;
    for (size_t w0 = 0; w0 < padded_; w0 += kBlock) {
        double e_top[kBlock], e_bottom[kBlock];
        bool lit = false;
        for (size_t b = 0; b < kBlock; ++b) {
            const size_t w = w0 + b;
            e_top[b] = w < W ? light.top[w] : 0.0;
            e_bottom[b] = w < W && !light.bottom.empty() ? light.bottom[w] : 0.0;
            rho[(N + 1) * kBlock + b] = w < W ? substrate_[w] : 0.0;
            lit |= e_top[b] != 0.0 || e_bottom[b] != 0.0;
        }
        if (!lit)
            continue;
        // Eqs. (12), (13), (22), (23) per sublayer and wavelength.
        for (size_t i = 0; i < N; ++i) {
            double mu_a[kBlock] = {}, mu_s[kBlock] = {};
            const double* f = &fractions_[i * J];
            for (size_t j = 0; j < J; ++j) {
                const double* a = &absorption_[j * padded_ + w0];
                const double* s = &scattering_[j * padded_ + w0];
                for (size_t b = 0; b < kBlock; ++b) {
                    mu_a[b] += f[j] * a[b];
                    mu_s[b] += f[j] * s[b];
                }
            }
            sublayer_optics(mu_a, mu_s, dz, &rho[(i + 1) * kBlock], &tau[(i + 1) * kBlock],
                            kBlock);
        }
        // Forward sweep (see solve_two_flux): boundary i in row r, the one above in row p.
        for (size_t i = 0; i <= N; ++i) {
            const size_t r = (i + 1) * kBlock, p = i * kBlock;
            const double top_on = i == 0 ? 1.0 : 0.0;
            const double bottom_on = i == N ? 1.0 : 0.0;
            for (size_t b = 0; b < kBlock; ++b) {
                const double w01 = -rho[r + b];
                const double w10 = -rho[p + b] + tau[p + b] * c1[p + b];
                const double inv_det = 1.0 / (1.0 - w01 * w10);
                const double r0 = bottom_on * e_bottom[b];
                const double r1 = top_on * e_top[b] + tau[p + b] * g1[p + b];
                g0[r + b] = (r0 - w01 * r1) * inv_det;
                g1[r + b] = (r1 - w10 * r0) * inv_det;
                c0[r + b] = -tau[r + b] * inv_det;
                c1[r + b] = tau[r + b] * w10 * inv_det;
            }
        }
        // Back substitution.
        for (size_t b = 0; b < kBlock; ++b) {
            up[(N + 1) * kBlock + b] = g0[(N + 1) * kBlock + b];
            down[(N + 1) * kBlock + b] = g1[(N + 1) * kBlock + b];
        }
        for (size_t i = N; i-- > 0;) {
            const size_t r = (i + 1) * kBlock, n = (i + 2) * kBlock;
            for (size_t b = 0; b < kBlock; ++b) {
                up[r + b] = g0[r + b] - c0[r + b] * up[n + b];
                down[r + b] = g1[r + b] - c1[r + b] * up[n + b];
            }
        }
        // §4.1: the mean fluence rate of each sublayer; accumulate Eq. (14)'s integrals.
        for (size_t i = 0; i < N; ++i) {
            const size_t r = (i + 1) * kBlock, n = (i + 2) * kBlock;
            double fluence[kBlock];
            for (size_t b = 0; b < kBlock; ++b)
                fluence[b] = 0.5 * (down[r + b] + up[r + b] + down[n + b] + up[n + b]);
            for (size_t j = 0; j < J; ++j) {
                if (fades[j]) {
                    const double* fa = &fading_[j * padded_ + w0];
                    double sum = 0.0;
                    for (size_t b = 0; b < kBlock; ++b)
                        sum += fa[b] * fluence[b];
                    loss[i * J + j] += sum;
                }
                if (produces[j]) {
                    const double* pr = &production_[j * padded_ + w0];
                    double sum = 0.0;
                    for (size_t b = 0; b < kBlock; ++b)
                        sum += pr[b] * fluence[b];
                    gain[i * J + j] += sum;
                }
            }
        }
    }

    // §4.2, Eq. (35) (first order: the exponent uses a = mu_a / f), and Eq. (15)'s
    // products, each integrated exactly over the step with the fluence held constant.
    for (size_t i = 0; i < N; ++i) {
        double* f = &fractions_[i * J];
        const double* r = &loss[i * J];
        const double* g = &gain[i * J];
        std::vector<double> start(f, f + J);
        for (size_t j = 0; j < J; ++j)
            f[j] = start[j] * std::exp(-r[j] * dt_s);
        for (size_t j = 0; j < J; ++j) {
            if (product_[j] < 0 || g[j] == 0.0 || start[j] == 0.0)
                continue;
            const size_t k = static_cast<size_t>(product_[j]);
            f[k] += g[j] * start[j] * chain_gain(r[j], r[k], dt_s);
        }
    }
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
    const size_t N = static_cast<size_t>(sublayers_);
    LayerSpectra out;
    out.r_top.resize(W);
    out.t.resize(W);
    out.r_bottom.resize(W);
    out.reflectance.resize(W);
    std::vector<double> rho(N), tau(N);
    for (size_t w = 0; w < W; ++w) {
        sublayer_optics_at(w, rho, tau);
        const LayerOpticsValue v = fold_sublayers(rho, tau);
        out.r_top[w] = v.r_top;
        out.t[w] = v.t;
        out.r_bottom[w] = v.r_bottom;
        out.reflectance[w] = reflectance_over(v, substrate_[w]);
    }
    return out;
}

std::vector<double> FadeSimulation::absorption_profile(size_t w) const
{
    const size_t W = padded_;
    const size_t J = colorants();
    std::vector<double> out(static_cast<size_t>(sublayers_), 0.0);
    for (size_t i = 0; i < out.size(); ++i)
        for (size_t j = 0; j < J; ++j)
            out[i] += fractions_[i * J + j] * absorption_[j * W + w];
    return out;
}

std::vector<double> FadeSimulation::scattering_profile(size_t w) const
{
    const size_t W = padded_;
    const size_t J = colorants();
    std::vector<double> out(static_cast<size_t>(sublayers_), 0.0);
    for (size_t i = 0; i < out.size(); ++i)
        for (size_t j = 0; j < J; ++j)
            out[i] += fractions_[i * J + j] * scattering_[j * W + w];
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
