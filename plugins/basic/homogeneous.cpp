/*
 * homogeneous — Homogeneous participating medium (medium)
 * ========================================================
 *
 *  Parameter     Type      Default   Description
 *  ------------  --------  --------  ----------------------------------------------------
 *  sigma_a       spectrum  0.1       Absorption coefficient σa(λ), 1/m, in [0, 1e6].
 *  sigma_s       spectrum  1         Scattering coefficient σs(λ), 1/m, in [0, 1e6].
 *  g             float     0         Henyey-Greenstein asymmetry in [-0.99, 0.99].
 *  density       float     1         Scale of both coefficients, in [0, 1e6].
 *
 * A medium with the same coefficients everywhere: σa and σs (tabulated over wavelength in
 * nm, or constants) times `density`, extinction σt = σa + σs. Positions and directions are
 * world space; the medium ignores them (and the shading context) since nothing varies.
 *
 * Transmittance over a distance t is exact, Beer-Lambert per wavelength:
 *
 *     Tr(λ, t) = exp(−σt(λ) t).
 *
 * sample_distance — free-flight sampling from the mixture of the path's wavelengths
 * (one-sample MIS with the balance heuristic; pbrt-v4 §14.1.3, Wilkie et al. 2014):
 *
 *     j = ⌊u n⌋, u' = u n − j,  t = −ln(1 − u') / σt(λj)
 *     t < t_max (scatter, returns 1):  weight_i = Tr_i(t) σs_i / p̄,
 *                                      p̄ = (1/n) Σ_j σt_j Tr_j(t)
 *     t ≥ t_max (pass, returns 0):     weight_i = Tr_i(t_max) / P̄,
 *                                      P̄ = (1/n) Σ_j Tr_j(t_max), and *t = t_max
 *                                      (t_max < 0 or NaN counts as 0)
 *
 * p̄ and P̄ are exactly the densities of the mixture the distance was drawn from, so each
 * event's weight is its integrand over its own density and the product of weights along a
 * whole path is unbiased at every wavelength (a component with σt = 0 never interacts: the
 * ray passes). Weights are finite and at most n.
 *
 * Phase function: Henyey-Greenstein with one g for every wavelength (patina/shading/phase.h).
 * Both wo and wi point away from the scattering point: wo towards the previous vertex (the
 * camera side), wi towards the next (the light side), and p depends on cos θ = dot(wo, wi)
 * through 1 + g² + 2g cos θ (pbrt-v4 §11.3.1). So g > 0 (forward scattering) favours
 * wi ≈ −wo, g < 0 favours wi ≈ wo. phase_sample inverts the cdf exactly, so its pdf equals
 * p, and phase_eval returns p as the pdf.
 *
 * References: pbrt-v4 §11.1-11.3 (HomogeneousMedium, HGPhaseFunction), §14.1.3 (spectral
 * MIS of majorant sampling); A. Wilkie et al. 2014, "Hero Wavelength Spectral Sampling",
 * EGSR; L. G. Henyey and J. L. Greenstein 1941, Astrophys. J. 93, 70-83.
 */
#include "basic.h"

#include <patina/volume/medium_phase.h>

#include <patina/shading/phase.h>
#include <patina/shading/spectral.h>

#include <cmath>
#include <new>

namespace patina::basic {
namespace {

    using namespace patina::shading;

    constexpr const char* kName = "homogeneous";
    constexpr float kMaxCoefficient = 1e6f;
    constexpr float kMaxAsymmetry = 0.99f;

    // clang-format off
    const PatinaParamDecl kParams[] = {
        {"sigma_a", PATINA_PARAM_SPECTRUM, {0.1f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1e6f, "1/m",
         "Absorption coefficient sigma_a, tabulated over wavelength in nm or a constant; "
         "multiplied by density."},
        {"sigma_s", PATINA_PARAM_SPECTRUM, {1.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1e6f, "1/m",
         "Scattering coefficient sigma_s, tabulated over wavelength in nm or a constant; "
         "multiplied by density."},
        {"g", PATINA_PARAM_FLOAT, {0.0f, 0.0f, 0.0f}, nullptr, nullptr, -0.99f, 0.99f, "",
         "Henyey-Greenstein asymmetry: > 0 scatters forward, < 0 backward, 0 is isotropic."},
        {"density", PATINA_PARAM_FLOAT, {1.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1e6f, "",
         "Scale of both coefficients; sigma_t = density * (sigma_a + sigma_s)."},
    };
    // clang-format on

    struct Homogeneous {
        TabulatedSpectrum sigma_a;
        TabulatedSpectrum sigma_s;
        volume::HenyeyGreenstein phase;
        float density = 1.0f;
    };

    /// σs and σt = σa + σs at the path's wavelengths, density included, in double.
    struct Coefficients {
        double sigma_s[PATINA_MAX_WAVELENGTHS] = {};
        double sigma_t[PATINA_MAX_WAVELENGTHS] = {};
    };

    Coefficients coefficients(const Homogeneous& m, const PatinaWavelengths& wl)
    {
        Coefficients c;
        const double density = m.density;
        for_each_wavelength(wl, [&](int i, float lambda) {
            const double s = density * static_cast<double>(m.sigma_s.eval(lambda));
            c.sigma_s[i] = s;
            c.sigma_t[i] = density * static_cast<double>(m.sigma_a.eval(lambda)) + s;
        });
        return c;
    }

    /// Beer-Lambert exp(−σt t) for t >= 0 (possibly infinite); 1 when σt = 0.
    double beer_lambert(double sigma_t, double t)
    {
        return sigma_t > 0.0 ? std::exp(-sigma_t * t) : 1.0;
    }

    /// Checks a SPECTRUM parameter: usable table, values finite in [0, 1e6]; nullptr when fine.
    const char* check_coefficient(const PatinaParamValue& v)
    {
        if (v.type != PATINA_PARAM_SPECTRUM)
            return "expected a spectrum value";
        if (const char* why = check_tabulated(v.spectrum))
            return why;
        for (int i = 0; i < v.spectrum.count; ++i)
            if (!(v.spectrum.value[i] >= 0.0f && v.spectrum.value[i] <= kMaxCoefficient))
                return "values must lie in [0, 1e6] 1/m";
        return nullptr;
    }

    void* create(const PatinaHost* host, const PatinaParamValue* values)
    {
        const plugin::Parameters p(host, kName, kParams, values);
        const PatinaParamValue& sigma_a = p.value("sigma_a", PATINA_PARAM_SPECTRUM);
        const PatinaParamValue& sigma_s = p.value("sigma_s", PATINA_PARAM_SPECTRUM);
        const PatinaParamValue& g = p.value("g", PATINA_PARAM_FLOAT);
        const PatinaParamValue& density = p.value("density", PATINA_PARAM_FLOAT);
        if (!p.ok())
            return nullptr;
        if (const char* why = check_coefficient(sigma_a)) {
            report_error(host, kName, "sigma_a: %s", why);
            return nullptr;
        }
        if (const char* why = check_coefficient(sigma_s)) {
            report_error(host, kName, "sigma_s: %s", why);
            return nullptr;
        }
        if (g.type != PATINA_PARAM_FLOAT || !(g.f >= -kMaxAsymmetry && g.f <= kMaxAsymmetry)) {
            report_error(host, kName, "g %g must lie in [-0.99, 0.99]", g.f);
            return nullptr;
        }
        if (density.type != PATINA_PARAM_FLOAT ||
            !(density.f >= 0.0f && density.f <= kMaxCoefficient)) {
            report_error(host, kName, "density %g must lie in [0, 1e6]", density.f);
            return nullptr;
        }

        // Copy the tables: the host's arrays live only during create
        auto* m = make_instance<Homogeneous>(host, kName);
        if (!m)
            return nullptr;
        try {
            m->sigma_a = TabulatedSpectrum(sigma_a.spectrum);
            m->sigma_s = TabulatedSpectrum(sigma_s.spectrum);
        } catch (const std::bad_alloc&) {
            report_error(host, kName, "out of memory");
            delete m;
            return nullptr;
        }
        m->phase.g = g.f;
        m->density = density.f;
        return m;
    }

    void destroy(void* instance)
    {
        delete static_cast<Homogeneous*>(instance);
    }

    int sample_distance(const void* instance, const PatinaShadingContext*, PatinaVec3 /*origin*/,
                        PatinaVec3 /*dir*/, float t_max, float u, const PatinaWavelengths* wl,
                        float* t, float* weight)
    {
        const auto& m = *static_cast<const Homogeneous*>(instance);
        const int n = wavelength_count(*wl);
        const Coefficients c = coefficients(m, *wl);
        const double t_end = t_max > 0.0f ? static_cast<double>(t_max) : 0.0; // NaN -> 0

        // Free-flight distance from the mixture (1/n) Σ_j σt_j e^{−σt_j t} of the path's
        // wavelengths: u picks the component j, and its remainder the distance
        // t = −ln(1 − u')/σt_j (pbrt-v4 §11.2.2, SampleExponential). The density of the
        // event is then the mixture whatever the hero, so the weights below (integrand over
        // that density) stay unbiased multiplied along a whole path; a component with
        // σt_j = 0 never interacts and the ray passes.
        const double uc = std::isnan(u) ? 0.0 : std::clamp(static_cast<double>(u), 0.0, 1.0 - 0x1p-53);
        const double un = uc * n;
        const int j = std::clamp(static_cast<int>(un), 0, std::max(n - 1, 0));
        if (n > 0 && c.sigma_t[j] > 0.0) {
            const double ud = std::clamp(un - j, 0.0, 1.0 - 0x1p-53);
            const float ts = static_cast<float>(-std::log1p(-ud) / c.sigma_t[j]);
            if (ts < t_max) {
                // Scatter: Tr σs over the wavelength-averaged density σt Tr (balance
                // heuristic, one sample: pbrt-v4 §14.1.3; Wilkie et al. 2014 §4)
                const double tsd = ts;
                double tr[PATINA_MAX_WAVELENGTHS] = {};
                double p_mean = 0.0;
                for (int j = 0; j < n; ++j) {
                    tr[j] = beer_lambert(c.sigma_t[j], tsd);
                    p_mean += c.sigma_t[j] * tr[j];
                }
                p_mean /= n;
                for (int i = 0; i < n; ++i) {
                    const double w = p_mean > 0.0 ? tr[i] * c.sigma_s[i] / p_mean : 0.0;
                    weight[i] = std::isfinite(w) ? static_cast<float>(w) : 0.0f;
                }
                *t = ts;
                return 1;
            }
        }

        // Pass: Tr(t_max) over the wavelength-averaged probability of passing
        double tr[PATINA_MAX_WAVELENGTHS] = {};
        double p_mean = 0.0;
        for (int j = 0; j < n; ++j) {
            tr[j] = beer_lambert(c.sigma_t[j], t_end);
            p_mean += tr[j];
        }
        if (n > 0)
            p_mean /= n;
        for (int i = 0; i < n; ++i) {
            const double w = p_mean > 0.0 ? tr[i] / p_mean : 0.0;
            weight[i] = std::isfinite(w) ? static_cast<float>(w) : 0.0f;
        }
        *t = static_cast<float>(t_end);
        return 0;
    }

    void transmittance(const void* instance, const PatinaShadingContext*, PatinaVec3 /*origin*/,
                       PatinaVec3 /*dir*/, float t, float /*u*/, const PatinaWavelengths* wl,
                       float* tr)
    {
        const auto& m = *static_cast<const Homogeneous*>(instance);
        const Coefficients c = coefficients(m, *wl);
        const double td = t > 0.0f ? static_cast<double>(t) : 0.0; // NaN -> 0
        // Beer-Lambert, exact for constant σt: pbrt-v4 §11.2 Eq. 11.6
        for_each_wavelength(
            *wl, [&](int i, float) { tr[i] = static_cast<float>(beer_lambert(c.sigma_t[i], td)); });
    }

    const PatinaMediumFuncs kFuncs = {sample_distance, transmittance,
                                      volume::phase_eval<Homogeneous, &Homogeneous::phase>,
                                      volume::phase_sample<Homogeneous, &Homogeneous::phase>};

} // namespace

PatinaShaderDesc homogeneous_shader()
{
    return describe(kName,
                 "Homogeneous participating medium: constant absorption and "
                 "scattering coefficients with a Henyey-Greenstein phase function.",
                 kParams, create, destroy, kFuncs);
}

} // namespace patina::basic
