// A small PatinaHost for the basic plugin's tests: it collects error messages, uplifts RGB
// to spectra (greys exactly, as the ABI requires; other colours by a simple fit that is
// good enough for these tests — the real uplift is src/core's and is tested there) and
// evaluates those spectra, multiplying emission colours by CIE D65 normalised at 560 nm.
// (The real host normalises D65 to luminance 1 instead; the emitter only scales whatever
// the host's eval_rgb_spectrum returns, which is what these tests check.)
#pragma once

#include <patina/abi.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

namespace patina::test {

/// CIE standard illuminant D65, relative SPD, 360-830 nm every 10 nm (100 at 560 nm):
/// CIE 15:2004, Table T.1 (every second entry of the 5 nm table).
// clang-format off
inline constexpr float kD65Every10Nm[48] = {
    46.6383f, 52.0891f, 49.9755f, 54.6482f, 82.7549f, 91.486f,  93.4318f, 86.6823f,
    104.865f, 117.008f, 117.812f, 114.861f, 115.923f, 108.811f, 109.354f, 107.802f,
    104.79f,  107.689f, 104.405f, 104.046f, 100.0f,   96.3342f, 95.788f,  88.6856f,
    90.0062f, 89.5991f, 87.6987f, 83.2886f, 83.6992f, 80.0268f, 80.2146f, 82.2778f,
    78.2842f, 69.7213f, 71.6091f, 74.349f,  61.604f,  69.8856f, 75.087f,  63.5927f,
    46.4182f, 66.8054f, 63.3828f, 64.304f,  59.4519f, 51.959f,  57.4406f, 60.3125f};
// clang-format on

/// D65 at a wavelength, normalised to 1 at 560 nm (linear interpolation, clamped ends).
inline float d65_normalised(float lambda_nm)
{
    const float x = std::clamp((lambda_nm - 360.0f) / 10.0f, 0.0f, 47.0f);
    const int i = std::min(static_cast<int>(x), 46);
    const float t = x - static_cast<float>(i);
    return (kD65Every10Nm[i] + t * (kD65Every10Nm[i + 1] - kD65Every10Nm[i])) / 100.0f;
}

struct TestHost : PatinaHost {
    mutable std::vector<std::string> errors;
    mutable std::vector<std::string> warnings;

    TestHost() : PatinaHost{}
    {
        size = sizeof(PatinaHost);
        abi_version = PATINA_ABI_VERSION;
        host_name = "patina basic plugin tests";
        working_space = "ACEScg";
        error = [](const PatinaHost* h, const char* shader, const char* message) {
            static_cast<const TestHost*>(h)->errors.push_back(std::string(shader ? shader : "?") +
                                                              ": " + (message ? message : ""));
        };
        warning = [](const PatinaHost* h, const char* shader, const char* message) {
            static_cast<const TestHost*>(h)->warnings.push_back(std::string(shader ? shader : "?") +
                                                                ": " + (message ? message : ""));
        };
        rgb_to_spectrum = uplift;
        eval_rgb_spectrum = [](const PatinaHost*, const PatinaRgbSpectrum* s,
                               const PatinaWavelengths* wl, float* out) {
            for (int i = 0; i < wl->count; ++i)
                out[i] = eval(*s, wl->lambda_nm[i]);
        };
    }
    TestHost(const TestHost&) = delete;
    TestHost& operator=(const TestHost&) = delete;

    /// Value of an uplifted spectrum, including the illuminant factor.
    static float eval(const PatinaRgbSpectrum& s, float lambda_nm)
    {
        const float v = patina_rgb_spectrum_eval(&s, lambda_nm);
        return s.illuminant ? v * d65_normalised(lambda_nm) : v;
    }

    /// Greys exactly (c = 0, scale = 2g); other colours: scale = 1 (reflectance) or
    /// 2·max (emission), and the quadratic through S⁻¹ of b, g, r at 450, 550, 650 nm.
    static void uplift(const PatinaHost*, const float rgb[3], int is_illuminant,
                       PatinaRgbSpectrum* out)
    {
        float c[3] = {rgb[0], rgb[1], rgb[2]};
        if (!is_illuminant)
            for (float& v : c)
                v = std::clamp(v, 0.0f, 1.0f);
        *out = PatinaRgbSpectrum{0.0f, 0.0f, 0.0f, 0.0f, is_illuminant ? 1 : 0};
        if (c[0] == c[1] && c[1] == c[2]) {
            out->scale = 2.0f * c[0];
            return;
        }
        const float m = std::max({c[0], c[1], c[2]});
        out->scale = is_illuminant ? 2.0f * m : 1.0f;
        // S⁻¹(y) = t / sqrt(1 − t²), t = 2y − 1
        auto inverse_sigmoid = [](double y) {
            const double t = 2.0 * std::clamp(y, 1e-4, 1.0 - 1e-4) - 1.0;
            return t / std::sqrt(1.0 - t * t);
        };
        const double x0 = inverse_sigmoid(c[2] / out->scale); // 450 nm: blue
        const double x1 = inverse_sigmoid(c[1] / out->scale); // 550 nm: green
        const double x2 = inverse_sigmoid(c[0] / out->scale); // 650 nm: red
        // Newton form of the quadratic through (450, x0), (550, x1), (650, x2)
        const double d1 = (x1 - x0) / 100.0, d2 = (x2 - x1) / 100.0;
        const double a = (d2 - d1) / 200.0;
        const double b = d1 - a * (450.0 + 550.0);
        const double c0 = x0 - b * 450.0 - a * 450.0 * 450.0;
        out->c0 = static_cast<float>(a);
        out->c1 = static_cast<float>(b);
        out->c2 = static_cast<float>(c0);
    }
};

} // namespace patina::test
