/*
 * emitter — Diffuse area light (emitter)
 * ======================================
 *
 *  Parameter     Type    Default          Description
 *  ------------  ------  ---------------  -----------------------------------------------
 *  color         color   (1, 1, 1)        Emission colour, scene-linear, >= 0, unbounded.
 *  intensity     float   1                Scale of the emitted radiance, >= 0.
 *  two_sided     bool    false            Emit from both sides of the surface.
 *
 * A Lambertian emitter: the radiance leaving the surface is the same in every direction,
 *
 *     L(λ) = intensity · E(λ),
 *
 * where E is the host's illuminant uplift of `color` (abi.h, PatinaRgbSpectrum with
 * illuminant = 1): the working space's white illuminant normalised to luminance Y = 1,
 * times a smooth reflectance-like factor. A white colour (1, 1, 1) therefore emits the
 * white illuminant itself (D65 for the usual working spaces) with luminance `intensity`,
 * and renders as (intensity, intensity, intensity) in the working space.
 * Units: W/(m² sr nm) when intensity is read in those units.
 *
 * Only the side the shading normal points to (+z) emits, unless `two_sided` is set; the
 * back side is black. The spectrum is evaluated by the host (eval_rgb_spectrum).
 */
#include "basic.h"

#include <patina/shading/spectral.h>

namespace patina::basic {
namespace {

    using namespace patina::shading;

    constexpr const char* kName = "emitter";

    // clang-format off
    const PatinaParamDecl kParams[] = {
        {"color", PATINA_PARAM_COLOR, {1.0f, 1.0f, 1.0f}, nullptr, nullptr, 0.0f, 1e30f,
         "scene_linear",
         "Emission colour, uplifted as an illuminant; white emits the working space's white "
         "with luminance 1."},
        {"intensity", PATINA_PARAM_FLOAT, {1.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1e30f, "",
         "Scale of the emitted radiance."},
        {"two_sided", PATINA_PARAM_BOOL, {0.0f, 0.0f, 0.0f}, nullptr, nullptr, 0.0f, 1.0f, "",
         "Emit from both sides of the surface; otherwise only on the side the normal points to."},
    };
    // clang-format on

    struct Emitter {
        const PatinaHost* host = nullptr;
        PatinaRgbSpectrum color{};
        float intensity = 1.0f;
        bool two_sided = false;
    };

    void* create(const PatinaHost* host, const PatinaParamValue* values)
    {
        const plugin::Parameters p(host, kName, kParams, values);
        const PatinaParamValue& color = p.value("color", PATINA_PARAM_COLOR);
        const PatinaParamValue& intensity = p.value("intensity", PATINA_PARAM_FLOAT);
        const PatinaParamValue& two_sided = p.value("two_sided", PATINA_PARAM_BOOL);
        if (!p.ok())
            return nullptr;
        if (!host || !host->eval_rgb_spectrum) {
            report_error(host, kName,
                         "the host offers no eval_rgb_spectrum service, which the "
                         "emitter needs to evaluate its colour");
            return nullptr;
        }
        if (color.type != PATINA_PARAM_COLOR) {
            report_error(host, kName, "color: expected a colour value");
            return nullptr;
        }
        for (int c = 0; c < 3; ++c) {
            if (!(color.rgb[c] >= 0.0f && is_finite(color.rgb[c]))) {
                report_error(host, kName, "color (%g, %g, %g) must be finite and >= 0",
                             color.rgb[0], color.rgb[1], color.rgb[2]);
                return nullptr;
            }
        }
        const PatinaRgbSpectrum& s = color.color;
        if (!is_finite(s.c0) || !is_finite(s.c1) || !is_finite(s.c2) || !is_finite(s.scale) ||
            s.scale < 0.0f) {
            report_error(host, kName, "color spectrum has non-finite or negative coefficients");
            return nullptr;
        }
        if (intensity.type != PATINA_PARAM_FLOAT ||
            !(intensity.f >= 0.0f && is_finite(intensity.f))) {
            report_error(host, kName, "intensity %g must be finite and >= 0", intensity.f);
            return nullptr;
        }
        if (two_sided.type != PATINA_PARAM_BOOL) {
            report_error(host, kName, "two_sided: expected a bool value");
            return nullptr;
        }
        return make_instance<Emitter>(host, kName, host, s, intensity.f, two_sided.i != 0);
    }

    void destroy(void* instance)
    {
        delete static_cast<Emitter*>(instance);
    }

    void emit(const void* instance, const PatinaShadingContext*, PatinaVec3 wo,
              const PatinaWavelengths* wl, float* radiance)
    {
        const auto& e = *static_cast<const Emitter*>(instance);
        // Black on the back side of a one-sided emitter, and exactly in the tangent plane
        if (wo.z == 0.0f || (wo.z < 0.0f && !e.two_sided)) {
            fill(0.0f, *wl, radiance);
            return;
        }
        // L(λ) = intensity · E(λ), E evaluated by the host (illuminant uplift)
        float value[PATINA_MAX_WAVELENGTHS] = {};
        e.host->eval_rgb_spectrum(e.host, &e.color, wl, value);
        for_each_wavelength(*wl, [&](int i, float) {
            const float l = e.intensity * value[i];
            radiance[i] = is_finite(l) && l > 0.0f ? l : 0.0f;
        });
    }

    const PatinaEmitterFuncs kFuncs = {emit};

} // namespace

PatinaShaderDesc emitter_shader()
{
    return describe(kName,
                 "Diffuse area light: uniform radiance intensity x colour (an illuminant "
                 "spectrum), from the front side or both sides.",
                 kParams, create, destroy, kFuncs);
}

} // namespace patina::basic
