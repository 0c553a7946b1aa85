// Spectra on a wavelength grid for the spectral fading model (Kimmel et al. 2013, §3.1.2,
// §4.2): a piecewise-linear tabulated spectrum (the form material files give theirs in)
// and the set of wavelengths the solver runs on, with trapezoid weights for the integral
// of Eqs. (14) and (35).
#pragma once

#include <string>
#include <vector>

namespace patina::texgen::fade {

/// A spectrum given at knots (nm strictly increasing), linearly interpolated between them
/// and held constant beyond the first and last knot. One knot: a constant.
struct TabulatedSpectrum {
    std::vector<double> nm;
    std::vector<double> value;

    static TabulatedSpectrum constant(double v) { return {{550.0}, {v}}; }
    /// Value at `lambda_nm`.
    double at(double lambda_nm) const;
    bool empty() const { return nm.empty(); }
};

/// The wavelengths the solver runs on (any set, strictly increasing), in nm.
struct WavelengthGrid {
    std::vector<double> nm;

    /// first, first + step, ... up to last (inclusive when it falls on the grid).
    /// Most wavelengths a grid may have (0.13 nm steps over 300-830 nm).
    static constexpr double kMaxWavelengths = 4096;

    /// The paper's grid is uniform(330, 700, 1): 371 wavelengths (Table IV). Throws when
    /// the grid would have more than kMaxWavelengths.
    static WavelengthGrid uniform(double first_nm, double last_nm, double step_nm);
    size_t size() const { return nm.size(); }
    /// Trapezoid weights in nm: sum_i w_i g(nm_i) approximates the integral of g over
    /// [nm.front(), nm.back()]. One wavelength: weight 1 nm (a 1 nm band).
    std::vector<double> trapezoid_weights() const;
    /// Sample a spectrum at every grid wavelength.
    std::vector<double> sample(const TabulatedSpectrum& s) const;
};

}  // namespace patina::texgen::fade
