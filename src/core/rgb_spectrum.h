// RGB -> spectrum uplift (Jakob & Hanika 2019, "A Low-Dimensional Function Space for
// Efficient Spectral Upsampling"): a reflectance becomes scale * S(c0 l^2 + c1 l + c2),
// smooth and bounded in [0, 1]; a grey becomes a constant spectrum exactly.
//
// Colour is matched under CIE D65 for the CIE 1931 2° observer, integrating over 360-830 nm
// with an interpolatory rule on the 5 nm table nodes that agrees with the 1 nm integration
// of spectrum_to_xyz (core/spectrum.h) to ~5e-5.
//
// White: an emission colour (r, g, b) in the working space becomes
// scale * S(...) * D65(l) / Y(D65), with Y(D65) = ∫ D65 ȳ / ∫ ȳ (≈ 98.89 for the table scaled
// to 100 at 560 nm): RGB (1, 1, 1) is D65 with luminance exactly 1 (pbrt-v4's convention), so
// a unit white light renders as working-space (1, 1, 1).
// Objects are copyable and thread-safe; copies share the lazily built warm-start table.
#pragma once

#include "core/color_management.h"

#include <patina/abi.h>

#include <array>
#include <memory>

namespace patina {

class RgbToSpectrum {
public:
    /// `rgb_to_xyz` maps linear RGB of the working space to XYZ (D65 white at Y = 1); the
    /// fit matches the colour of the reflectance under CIE D65 seen by the CIE 1931 observer.
    /// The matrix's rows are rescaled so RGB (1, 1, 1) is exactly the XYZ of the perfect
    /// white under the embedded D65 table (a change of a few 1e-4 for D65 matrices).
    /// Throws std::invalid_argument if the matrix is singular.
    explicit RgbToSpectrum(const Matrix3& rgb_to_xyz);

    /// Uplift a reflectance (components clamped to [0, 1]) or, with `illuminant`, an
    /// unbounded emission colour (scaled, and multiplied by D65 when evaluated).
    PatinaRgbSpectrum uplift(const std::array<float, 3>& rgb, bool illuminant) const;

    /// Value of an uplifted spectrum at a wavelength (handles `illuminant`).
    static float eval(const PatinaRgbSpectrum& s, float lambda_nm);
    /// The white of emission colours: CIE D65 scaled to luminance Y = 1, that is
    /// d65(lambda_nm) * d65_to_unit_luminance(). eval() of an illuminant spectrum is its
    /// reflectance-like value times this.
    static float unit_d65(float lambda_nm);
    static float d65_to_unit_luminance();
    /// True when `s` is a grey: c0 = c1 = 0, so its reflectance-like value is the same at
    /// every wavelength (an illuminant grey is that value times unit_d65).
    static bool is_grey(const PatinaRgbSpectrum& s) { return s.c0 == 0.0f && s.c1 == 0.0f; }

    /// RGB of a reflectance spectrum under D65 (the inverse used for round-trip checks).
    /// For an illuminant spectrum: its emission colour, D65 of luminance 1 being (1, 1, 1),
    /// so rgb_of(uplift(rgb, true)) == rgb as well.
    std::array<float, 3> rgb_of(const PatinaRgbSpectrum& s) const;

private:
    /// Warm-start table and solver state shared by copies (defined in rgb_spectrum.cpp).
    struct Table;

    Matrix3 rgb_to_xyz_;
    Matrix3 xyz_to_rgb_;
    std::shared_ptr<Table> table_;
};

} // namespace patina
