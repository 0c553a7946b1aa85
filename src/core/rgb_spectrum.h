// RGB -> spectrum uplift (Jakob & Hanika 2019, "A Low-Dimensional Function Space for
// Efficient Spectral Upsampling"): a reflectance becomes scale * S(c0 l^2 + c1 l + c2),
// smooth and bounded in [0, 1]; a grey becomes a constant spectrum exactly.
#pragma once

#include "core/color_management.h"

#include <patina/abi.h>

#include <array>

namespace patina {

class RgbToSpectrum {
public:
    /// `rgb_to_xyz` maps linear RGB of the working space to XYZ (D65 white at Y = 1); the
    /// fit matches the colour of the reflectance under CIE D65 seen by the CIE 1931 observer.
    explicit RgbToSpectrum(const Matrix3& rgb_to_xyz);

    /// Uplift a reflectance (components clamped to [0, 1]) or, with `illuminant`, an
    /// unbounded emission colour (scaled, and multiplied by D65 when evaluated).
    PatinaRgbSpectrum uplift(const std::array<float, 3>& rgb, bool illuminant) const;

    /// Value of an uplifted spectrum at a wavelength (handles `illuminant`).
    static float eval(const PatinaRgbSpectrum& s, float lambda_nm);

    /// RGB of a reflectance spectrum under D65 (the inverse used for round-trip checks).
    std::array<float, 3> rgb_of(const PatinaRgbSpectrum& s) const;

private:
    Matrix3 rgb_to_xyz_;
    Matrix3 xyz_to_rgb_;
};

}  // namespace patina
