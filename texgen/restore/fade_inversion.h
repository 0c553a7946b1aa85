// The colours before the fade (Kimmel et al. 2013, §6 names it as future work): given the
// colour a texel shows now and the dose it has had, the original amounts of the material's
// fading colorants such that fading them by that dose gives what is seen, and the colour
// they had unexposed.
//
// The forward model is the fading simulation, tabulated: a grid of original amounts (a
// multiplier of the material's fraction per fading colorant, denser near 0 where
// Kubelka-Munk colour changes fastest) with one dose table per node, reduced to CIE XYZ per
// dose (XYZ is linear in reflectance, so interpolating it in the dose follows the table's own
// rule). Per texel, a Gauss-Newton fit in CIELAB over the multilinear interpolation of the
// nodes, pulled weakly towards the material's own amounts.
//
// When the answer is not unique. A colorant faded to nothing leaves no trace in the colour:
// any original amount of it fades to the same thing. The fit reports, per texel, how far the
// restored colour can move per unit the observed colour moves (its `amplification`: an
// error of 0.2 in what is seen becomes up to 0.2 × amplification in the restoration), and
// how far the fit is from what is seen (`residual`, ΔE00). A texel is `unique` when the
// first is at most InversionOptions::max_amplification and the second at most
// max_residual; elsewhere the restored colour keeps the material's own amounts in the
// undetermined directions and the confidence map says so.
#pragma once

#include "texgen/fade/dose_table.h"
#include "texgen/forecast/fade_forecast.h"

#include <Imath/ImathVec.h>

#include <array>
#include <string>
#include <vector>

namespace patina::texgen::restore {

struct InversionOptions {
    double max_amount = 2.0;      ///< multipliers searched in [0, max_amount]
    int levels = 0;               ///< grid levels per colorant (0: 33, 17, 12 for 1, 2, 3)
    int sublayers = 50;
    int entries = 64;             ///< dose table entries (one rule for every node)
    double max_dose_j_m2 = 0.0;   ///< largest dose to invert (> 0)
    double max_amplification = 1.5; ///< restored colour change per observed change, for `unique`
    double max_residual = 1.0;    ///< ΔE00 between the fit and the observed colour
    double prior_weight = 0.02;   ///< pull towards the material's amounts (CIELAB per unit)
    /// The colorants to solve for (empty: every fading colorant the material starts with);
    /// the others keep the material's amounts.
    std::vector<std::string> colorants;
};

struct Inversion {
    std::array<double, 3> amounts{1.0, 1.0, 1.0};  ///< multipliers, per free colorant
    Imath::V3d unfaded_xyz{0.0};   ///< the colour at dose 0 (D65, white Y = 1)
    Imath::V3d faded_xyz{0.0};     ///< the model's colour at the dose, for those amounts
    /// How far the restored colour can move (CIELAB) per unit the observed colour moves:
    /// the largest ratio over changes of the amounts. Infinite where a colorant is faded
    /// to nothing (its amount changes the restored colour, not the faded one).
    double amplification = 0.0;
    double residual = 0.0;         ///< ΔE00, model against observed
    bool unique = false;
};

class FadeInversion {
public:
    /// Builds the node tables (in parallel). Throws std::runtime_error naming the material
    /// when no colorant fades or more than three do (an RGB colour fixes at most three
    /// amounts; name up to three in options.colorants), when a named colorant is not one
    /// of its fading colorants, or for options out of range.
    FadeInversion(const fade::FadeMaterial& material, const fade::Illuminant& light,
                  const fade::WavelengthGrid& grid, const forecast::ColourMeter& meter,
                  const InversionOptions& options);

    /// The colorants whose original amounts are solved for.
    const std::vector<std::string>& free_colorants() const { return free_names_; }
    size_t dimensions() const { return free_.size(); }
    const InversionOptions& options() const { return options_; }

    /// The model's XYZ for `amounts` (multipliers, dimensions() of them) after `dose`.
    Imath::V3d xyz(const std::array<double, 3>& amounts, double dose_j_m2) const;
    /// The fit for one texel: observed XYZ (D65, white Y = 1) after `dose`.
    Inversion invert(const Imath::V3d& observed_xyz, double dose_j_m2) const;

private:
    struct Row {
        size_t lower = 0;
        double weight = 0.0;
    };
    Row row(double dose_j_m2) const;
    Imath::V3d xyz_at(const std::array<double, 3>& amounts, const Row& r) const;
    double level_coordinate(double amount) const;

    InversionOptions options_;
    const forecast::ColourMeter* meter_ = nullptr;
    std::vector<size_t> free_;
    std::vector<std::string> free_names_;
    int levels_ = 0;
    size_t entries_ = 0;
    double knee_ = 1.0, inv_du_ = 0.0;
    /// Per node (level-major, first colorant slowest) and table entry: XYZ.
    std::vector<Imath::V3d> node_xyz_;
};

}  // namespace patina::texgen::restore
