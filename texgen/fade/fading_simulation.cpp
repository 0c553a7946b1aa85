#include "texgen/fade/fading_simulation.h"

#include "texgen/fade/two_flux.h"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace patina::texgen::fade {

namespace {

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
    const size_t J = material.colorants.size();
    absorption_.resize(J * W);
    scattering_.resize(J * W);
    fading_.resize(J * W);
    production_.assign(J * W, 0.0);
    product_.assign(J, -1);
    for (size_t j = 0; j < J; ++j) {
        const Colorant& c = material.colorants[j];
        colorant_names_.push_back(c.name);
        if (c.breakdown)
            product_[j] = static_cast<int>(material.colorant_index(c.breakdown->product));
        for (size_t w = 0; w < W; ++w) {
            const double nm = grid.nm[w];
            const double a = c.absorption_per_m.at(nm);
            absorption_[j * W + w] = a;
            scattering_[j * W + w] = c.scattering_per_m.at(nm);
            // Eq. (14): the energy absorbed by colorant j, weighted by β_j(λ) (§3.1.2).
            fading_[j * W + w] = weights_[w] * c.fading.at(nm) * a;
            if (c.breakdown)
                production_[j * W + w] = weights_[w] * c.breakdown->rate.at(nm) * a;
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
    const size_t W = grid_.size();
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

    std::vector<double> rho(N), tau(N), down(N + 1), up(N + 1), fluence(N);
    // Per sublayer and colorant: loss rate r = ∫ β a F dλ and gain rate ∫ γ a F dλ (1/s).
    std::vector<double> loss(N * J, 0.0), gain(N * J, 0.0);
    for (size_t w = 0; w < W; ++w) {
        const double top = light.top[w];
        const double bottom = light.bottom.empty() ? 0.0 : light.bottom[w];
        if (top == 0.0 && bottom == 0.0)
            continue;
        // §4.1: the fluence rate per sublayer at this wavelength.
        sublayer_optics_at(w, rho, tau);
        solve_two_flux(rho, tau, {top, bottom, substrate_[w]}, down, up);
        sublayer_fluence_rate(down, up, fluence);
        for (size_t j = 0; j < J; ++j) {
            const double fade = fading_[j * W + w];
            const double prod = production_[j * W + w];
            if (fade == 0.0 && prod == 0.0)
                continue;
            for (size_t i = 0; i < N; ++i) {
                loss[i * J + j] += fade * fluence[i];
                gain[i * J + j] += prod * fluence[i];
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
    const size_t W = grid_.size();
    const size_t J = colorants();
    std::vector<double> out(static_cast<size_t>(sublayers_), 0.0);
    for (size_t i = 0; i < out.size(); ++i)
        for (size_t j = 0; j < J; ++j)
            out[i] += fractions_[i * J + j] * absorption_[j * W + w];
    return out;
}

std::vector<double> FadeSimulation::scattering_profile(size_t w) const
{
    const size_t W = grid_.size();
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
