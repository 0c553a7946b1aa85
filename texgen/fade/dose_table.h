// A fading material's state tabulated over dose under one illuminant (issue 7, item 4):
// since the spectral irradiance is E(λ) = E s(λ), Eq. (35)'s exponent is
// dH ∫ β a F_λ/E dλ, and the state after any history of irradiance depends only on the
// dose H = ∫ E dt. The table holds, per dose, the layer's R_top, T, R_bottom and its
// reflectance over the substrate per wavelength, and the fractions by depth.
//
// Doses: entry k at H_k = H_0 (exp(k du) - 1), du = ln(1 + H_max/H_0) / (n - 1), so entry 0
// is the unexposed state, the spacing is linear near 0 (where the state changes linearly
// with H) and logarithmic beyond H_0. Interpolation: linear in u = ln(1 + H/H_0) between
// the two neighbouring entries; doses beyond H_max clamp to the last entry. Each interval
// is integrated with `substeps` exponential steps of equal dose.
#pragma once

#include "texgen/fade/fading_simulation.h"
#include "texgen/fade/illuminant.h"

#include <span>
#include <vector>

namespace patina::texgen::fade {

struct DoseTableOptions {
    double max_dose_j_m2 = 1e8;    ///< H_max
    double knee_dose_j_m2 = 1e4;   ///< H_0: spacing linear below, logarithmic above
    int entries = 64;              ///< n >= 2, entry 0 at H = 0
    int sublayers = 100;
    int substeps = 2;              ///< time steps per table interval
    bool both_sides = false;       ///< illuminate from below too (a free sheet)
};

class DoseTable {
public:
    /// Runs the simulation from H = 0 to H_max. Throws std::runtime_error for options out
    /// of range (naming the option) or an invalid material.
    static DoseTable build(const FadeMaterial& material, const Illuminant& illuminant,
                           const WavelengthGrid& grid, const DoseTableOptions& options);

    const WavelengthGrid& grid() const { return grid_; }
    const DoseTableOptions& options() const { return options_; }
    size_t colorants() const { return colorants_; }
    const std::vector<double>& doses() const { return doses_; }
    /// Entry k's spectra and fractions ([i * colorants() + j], as FadeSimulation).
    const LayerSpectra& spectra(size_t k) const { return spectra_[k]; }
    const std::vector<double>& fractions(size_t k) const { return fractions_[k]; }

    /// The two entries around `dose` and the weight of the upper one (the rule above).
    struct Bracket {
        size_t lower = 0;
        double upper_weight = 0.0;
    };
    Bracket locate(double dose_j_m2) const;
    /// Interpolated spectra and fractions at `dose` (every field, the same rule).
    LayerSpectra spectra_at(double dose_j_m2) const;
    std::vector<double> fractions_at(double dose_j_m2) const;

private:
    WavelengthGrid grid_;
    DoseTableOptions options_;
    size_t colorants_ = 0;
    double du_ = 0.0;
    std::vector<double> doses_;
    std::vector<LayerSpectra> spectra_;
    std::vector<std::vector<double>> fractions_;
};

}  // namespace patina::texgen::fade
