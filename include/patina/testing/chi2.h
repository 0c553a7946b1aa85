// Pearson's chi-square test of a direction sampler against its claimed density, as in
// pbrt-v3's tests/bsdfs.cpp and Mitsuba's chi2 module (Jakob's "chi2" tests):
//
//  1. draw N directions from the sampler and histogram them on a (θ, φ) grid over the
//     whole sphere (failed samples are drawn but land in no cell);
//  2. integrate the pdf over each cell, ∫∫ pdf(θ, φ) sin θ dθ dφ, with adaptive Simpson
//     quadrature in both dimensions, and multiply by N: the expected counts;
//  3. pool cells whose expected count is below 5 (sorted by expected count, pooled until
//     the pool reaches 5) and compute X² = Σ (observed − expected)² / expected;
//  4. p-value = Q((dof)/2, X²/2), the chi-square tail probability; the test fails when it is
//     below the per-test significance α' = 1 − (1 − α)^(1/K) (Šidák correction for K tests).
//
// A sample in a cell whose expected count is 0 fails at once (beyond 1e-5·N, to forgive
// rounding at cell borders), and so does a non-finite or non-unit direction.
//
// Installed with the plugin headers (include/patina/testing/): every BSDF and phase function
// of Patina's plugins is tested with it, and an out-of-tree plugin's should be too. Header-
// only, standard C++ and <patina/shading/vec.h>; no test framework needed.
#pragma once

#include <patina/shading/vec.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <string>
#include <vector>

namespace patina::test::chi2 {

using shading::Vec3;

// ---------------------------------------------------------------------------------------
// Chi-square distribution
// ---------------------------------------------------------------------------------------

/// Regularised upper incomplete gamma function Q(a, x) = Γ(a, x) / Γ(a).
inline double gamma_q(double a, double x)
{
    if (x <= 0.0)
        return 1.0;
    const double log_prefactor = -x + a * std::log(x) - std::lgamma(a);
    if (x < a + 1.0) {
        // Series for P(a, x): Numerical Recipes, 3rd ed., §6.2, Eq. 6.2.5
        double ap = a, term = 1.0 / a, sum = term;
        for (int n = 0; n < 100000; ++n) {
            ap += 1.0;
            term *= x / ap;
            sum += term;
            if (std::abs(term) < std::abs(sum) * 1e-15)
                break;
        }
        return std::max(0.0, 1.0 - sum * std::exp(log_prefactor));
    }
    // Continued fraction for Q(a, x), modified Lentz: Numerical Recipes, 3rd ed., §6.2, Eq. 6.2.7
    constexpr double kTiny = 1e-300;
    double b = x + 1.0 - a, c = 1.0 / kTiny, d = 1.0 / b, h = d;
    for (int i = 1; i < 100000; ++i) {
        const double an = -i * (i - a);
        b += 2.0;
        d = an * d + b;
        if (std::abs(d) < kTiny)
            d = kTiny;
        c = b + an / c;
        if (std::abs(c) < kTiny)
            c = kTiny;
        d = 1.0 / d;
        const double delta = d * c;
        h *= delta;
        if (std::abs(delta - 1.0) < 1e-15)
            break;
    }
    return std::exp(log_prefactor) * h;
}

/// P(X² >= statistic) for a chi-square distribution with `dof` degrees of freedom.
inline double p_value(double statistic, int dof)
{
    return gamma_q(0.5 * dof, 0.5 * statistic);
}

/// Per-test significance for an overall level alpha over `tests` tests (Šidák 1967).
inline double sidak(double alpha, int tests)
{
    return 1.0 - std::pow(1.0 - alpha, 1.0 / tests);
}

// ---------------------------------------------------------------------------------------
// Adaptive Simpson quadrature
// ---------------------------------------------------------------------------------------

template <typename F>
double simpson_recurse(const F& f, double a, double b, double c, double fa, double fb, double fc,
                       double whole, double eps, int depth)
{
    // Simpson's rule on both halves; stop by Lyness's criterion |S2 − S1| < 15 ε
    // (J. N. Lyness 1969, "Notes on the adaptive Simpson quadrature routine", JACM 16(3))
    const double d = 0.5 * (a + b), e = 0.5 * (b + c);
    const double fd = f(d), fe = f(e);
    const double h = c - a;
    const double left = h / 12.0 * (fa + 4.0 * fd + fb);
    const double right = h / 12.0 * (fb + 4.0 * fe + fc);
    const double both = left + right;
    if (depth <= 0 || std::abs(both - whole) < 15.0 * eps)
        return both + (both - whole) / 15.0; // Richardson extrapolation
    return simpson_recurse(f, a, d, b, fa, fd, fb, left, 0.5 * eps, depth - 1) +
           simpson_recurse(f, b, e, c, fb, fe, fc, right, 0.5 * eps, depth - 1);
}

/// ∫_{x0}^{x1} f(x) dx by adaptive Simpson with absolute tolerance eps.
template <typename F>
double adaptive_simpson(const F& f, double x0, double x1, double eps, int max_depth)
{
    const double b = 0.5 * (x0 + x1);
    const double fa = f(x0), fb = f(b), fc = f(x1);
    const double whole = (x1 - x0) / 6.0 * (fa + 4.0 * fb + fc);
    return simpson_recurse(f, x0, b, x1, fa, fb, fc, whole, eps, max_depth);
}

/// ∫∫ f(x, y) over [x0, x1] × [y0, y1], nested adaptive Simpson.
template <typename F>
double adaptive_simpson_2d(const F& f, double x0, double y0, double x1, double y1, double eps,
                           int max_depth)
{
    auto inner = [&](double y) {
        return adaptive_simpson([&](double x) { return f(x, y); }, x0, x1, eps, max_depth);
    };
    return adaptive_simpson(inner, y0, y1, eps, max_depth);
}

// ---------------------------------------------------------------------------------------
// The test
// ---------------------------------------------------------------------------------------

inline double sqr_diff(double a, double b)
{
    return (a - b) * (a - b);
}

struct Result {
    bool passed = false;
    double p_value = 0.0;
    double statistic = 0.0;
    int dof = 0;
    double pdf_integral = 0.0;     // ∫ pdf over the sphere (1 unless sampling can fail)
    double sampled_fraction = 0.0; // fraction of samples that produced a direction
    std::string message;
};

struct Options {
    int theta_res = 16;
    int phi_res = 32;
    int sample_count = 400000;
    double min_expected = 5.0;
    double significance = 0.01; // overall level before the Šidák correction
    int test_count = 1;         // K, for the Šidák correction
    unsigned seed = 1;
};

/// Runs the test. `sample(Vec3* w)` draws one direction (false when sampling fails);
/// `pdf(Vec3 w)` is the claimed solid-angle density.
template <typename Sample, typename Pdf> Result run(const Options& opt, Sample&& sample, Pdf&& pdf)
{
    Result r;
    const int cells = opt.theta_res * opt.phi_res;
    const double dtheta = M_PI / opt.theta_res, dphi = 2.0 * M_PI / opt.phi_res;

    // Histogram of sampled directions
    std::vector<double> observed(cells, 0.0);
    int produced = 0;
    for (int i = 0; i < opt.sample_count; ++i) {
        Vec3 w;
        if (!sample(&w))
            continue;
        const float len = shading::length(w);
        if (!shading::is_finite(w) || std::abs(len - 1.0f) > 1e-3f) {
            r.message = "sampler returned a non-finite or non-unit direction";
            return r;
        }
        ++produced;
        const double theta = std::acos(std::clamp(static_cast<double>(w.z), -1.0, 1.0));
        double phi = std::atan2(static_cast<double>(w.y), static_cast<double>(w.x));
        if (phi < 0.0)
            phi += 2.0 * M_PI;
        const int ti = std::min(static_cast<int>(theta / dtheta), opt.theta_res - 1);
        const int pi = std::min(static_cast<int>(phi / dphi), opt.phi_res - 1);
        observed[ti * opt.phi_res + pi] += 1.0;
    }
    r.sampled_fraction = static_cast<double>(produced) / opt.sample_count;

    // Expected counts: the pdf integrated over each cell
    std::vector<double> expected(cells, 0.0);
    auto integrand = [&](double theta, double phi) {
        const double st = std::sin(theta);
        const Vec3 w(static_cast<float>(st * std::cos(phi)), static_cast<float>(st * std::sin(phi)),
                     static_cast<float>(std::cos(theta)));
        return static_cast<double>(pdf(w)) * st;
    };
    for (int ti = 0; ti < opt.theta_res; ++ti) {
        for (int pi = 0; pi < opt.phi_res; ++pi) {
            // Cells shrink by 1e-9 rad so that a pdf discontinuous at a cell border (the
            // horizon) is not sampled exactly on it
            constexpr double kInset = 1e-9;
            const double integral =
                adaptive_simpson_2d(integrand, ti * dtheta + kInset, pi * dphi + kInset,
                                    (ti + 1) * dtheta - kInset, (pi + 1) * dphi - kInset, 1e-6, 6);
            r.pdf_integral += integral;
            expected[ti * opt.phi_res + pi] = integral * opt.sample_count;
        }
    }

    // Pool low-expectation cells, from the smallest expected count up
    std::vector<int> order(cells);
    std::iota(order.begin(), order.end(), 0);
    std::sort(order.begin(), order.end(), [&](int a, int b) { return expected[a] < expected[b]; });
    double pooled_obs = 0.0, pooled_exp = 0.0, chi2 = 0.0;
    int dof = 0;
    for (int c : order) {
        if (expected[c] <= 0.0) {
            if (observed[c] > opt.sample_count * 1e-5) {
                char buf[160];
                std::snprintf(buf, sizeof buf,
                              "%g samples in a cell (θ %d, φ %d) where the pdf is 0", observed[c],
                              c / opt.phi_res, c % opt.phi_res);
                r.message = buf;
                return r;
            }
            pooled_obs += observed[c]; // a few stray samples: let them weigh in the pool
        } else if (expected[c] < opt.min_expected ||
                   (pooled_exp > 0.0 && pooled_exp < opt.min_expected)) {
            pooled_obs += observed[c];
            pooled_exp += expected[c];
        } else {
            chi2 += sqr_diff(observed[c], expected[c]) / expected[c];
            ++dof;
        }
    }
    if (pooled_exp > 0.0) {
        chi2 += sqr_diff(pooled_obs, pooled_exp) / pooled_exp;
        ++dof;
    }
    dof -= 1; // the counts sum to N: one constraint
    r.statistic = chi2;
    r.dof = dof;
    if (dof <= 0) {
        r.message = "too few degrees of freedom";
        return r;
    }
    r.p_value = p_value(chi2, dof);
    const double alpha = sidak(opt.significance, opt.test_count);
    r.passed = std::isfinite(r.p_value) && r.p_value >= alpha;
    char buf[200];
    std::snprintf(buf, sizeof buf,
                  "X2 = %.1f, dof = %d, p = %.4f (alpha' = %.2e), ∫pdf = %.5f, sampled %.5f", chi2,
                  dof, r.p_value, alpha, r.pdf_integral, r.sampled_fraction);
    r.message = buf;
    return r;
}

} // namespace patina::test::chi2
