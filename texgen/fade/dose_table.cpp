#include "texgen/fade/dose_table.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen::fade {

DoseTable DoseTable::build(const FadeMaterial& material, const Illuminant& illuminant,
                           const WavelengthGrid& grid, const DoseTableOptions& options)
{
    auto fail = [](const std::string& what) {
        throw std::runtime_error("dose table: " + what);
    };
    if (!(options.max_dose_j_m2 > 0.0))
        fail(fmt::format("max_dose_j_m2 = {} must be > 0", options.max_dose_j_m2));
    if (!(options.knee_dose_j_m2 > 0.0))
        fail(fmt::format("knee_dose_j_m2 = {} must be > 0", options.knee_dose_j_m2));
    if (options.entries < 2)
        fail(fmt::format("entries = {} must be >= 2", options.entries));
    if (options.substeps < 1)
        fail(fmt::format("substeps = {} must be >= 1", options.substeps));

    DoseTable t;
    t.grid_ = grid;
    t.options_ = options;
    t.colorants_ = material.colorants.size();
    t.du_ = std::log1p(options.max_dose_j_m2 / options.knee_dose_j_m2) / (options.entries - 1);

    FadeSimulation sim(material, grid, options.sublayers);
    // The fluence in single precision: within 1e-6 of double (fade_kernel_test), far below
    // the table's interpolation error, and 3-4x faster.
    sim.set_precision(FadeSimulation::Precision::float32);
    // Unit band irradiance: a step of dt seconds is a dose step of dt J/m^2.
    const Illumination light = illuminant.illumination(grid, 1.0, options.both_sides);
    double dose = 0.0;
    for (int k = 0; k < options.entries; ++k) {
        const double target =
            k == options.entries - 1 ? options.max_dose_j_m2
                                     : options.knee_dose_j_m2 * std::expm1(k * t.du_);
        if (k > 0)
            sim.run(light, target - dose, options.substeps);
        dose = target;
        t.doses_.push_back(dose);
        t.spectra_.push_back(sim.spectra());
        t.fractions_.push_back(sim.fractions());
    }
    return t;
}

DoseTable::Bracket DoseTable::locate(double dose_j_m2) const
{
    const double u = std::log1p(std::max(0.0, dose_j_m2) / options_.knee_dose_j_m2) / du_;
    const double last = static_cast<double>(doses_.size() - 1);
    if (!(u < last))
        return {doses_.size() - 2, 1.0};
    const double lower = std::floor(u);
    return {static_cast<size_t>(lower), u - lower};
}

namespace {

void lerp_into(const std::vector<double>& a, const std::vector<double>& b, double t,
               std::vector<double>& out)
{
    out.resize(a.size());
    for (size_t i = 0; i < a.size(); ++i)
        out[i] = a[i] + t * (b[i] - a[i]);
}

}  // namespace

LayerSpectra DoseTable::spectra_at(double dose_j_m2) const
{
    const Bracket b = locate(dose_j_m2);
    const LayerSpectra& lo = spectra_[b.lower];
    const LayerSpectra& hi = spectra_[b.lower + 1];
    LayerSpectra out;
    lerp_into(lo.r_top, hi.r_top, b.upper_weight, out.r_top);
    lerp_into(lo.t, hi.t, b.upper_weight, out.t);
    lerp_into(lo.r_bottom, hi.r_bottom, b.upper_weight, out.r_bottom);
    lerp_into(lo.reflectance, hi.reflectance, b.upper_weight, out.reflectance);
    return out;
}

std::vector<double> DoseTable::fractions_at(double dose_j_m2) const
{
    const Bracket b = locate(dose_j_m2);
    std::vector<double> out;
    lerp_into(fractions_[b.lower], fractions_[b.lower + 1], b.upper_weight, out);
    return out;
}

}  // namespace patina::texgen::fade
