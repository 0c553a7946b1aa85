// The layered fading simulation (Kimmel et al. 2013, §3-§4): a material's layer split into
// N sublayers (§4.1), per wavelength the two-flux system for the fluence rate per sublayer,
// then per time step (§4.2, Eq. 35) every colorant's volume fraction multiplied by
//   exp(-dt sum_λ w_λ β_j(λ) a_j(λ) F_i(λ))
// with a_j = mu_a / f its absorption per unit volume fraction (first order in f; see
// colorant.h) and w_λ trapezoid weights; breakdown products (Eq. 15) gain what their
// parent loses times γ/β, integrated exactly over the step with F held constant.
// Absorption and scattering of a sublayer are the fraction-weighted sums over colorants
// (Eqs. 12, 13): only absorbers fade (§3.1.1), so a colorant with a = 0 keeps its fraction.
//
// The per wavelength x sublayer work runs in vector kernels, a block of 16 wavelengths at
// a time: AVX2 + FMA where the CPU has them, SSE2 elsewhere (the same formulas, rounded
// differently where FMA fuses a multiply and an add; tested to agree to 1e-12). Double
// precision by default (the reference); single precision on request, twice as many
// wavelengths per instruction (tested against double on Table IV: reflectance and
// fractions within 1e-6), reusing the sublayer optics of rows whose fractions (in float)
// did not change since the last step (bitwise the same result).
#pragma once

#include "texgen/fade/fade_material.h"
#include "texgen/fade/layer_optics.h"
#include "texgen/fade/spectral_grid.h"
#include "texgen/fade/two_flux.h"

#include <span>
#include <vector>

namespace patina::texgen::fade {

/// Spectral irradiance (W m^-2 nm^-1) at every grid wavelength, entering from the top and,
/// optionally, from below (illumination from both sides; empty: none). Light from below
/// enters through the substrate, so it only makes sense over a transparent ground
/// (substrate reflectance 0, a free sheet).
struct Illumination {
    std::vector<double> top;
    std::vector<double> bottom;
};

/// R_top, T, R_bottom of the layer (see layer_optics.h) and its reflectance over the
/// material's substrate, per grid wavelength.
struct LayerSpectra {
    std::vector<double> r_top, t, r_bottom;
    std::vector<double> reflectance;  ///< over the substrate: reflectance_over(...)
};

class FadeSimulation {
public:
    /// The instruction set of the vector kernels.
    enum class Kernel { portable, avx2 };
    /// Whether this CPU can run `kernel` (portable: always).
    static bool kernel_available(Kernel kernel);
    /// The precision of the per wavelength x sublayer work of step() (the fluence and the
    /// rates of Eq. 35); the fractions, their update and spectra() stay double.
    enum class Precision { float64, float32 };

    /// Samples the material on `grid`; throws std::runtime_error for an invalid material,
    /// an empty grid or sublayers < 1.
    FadeSimulation(const FadeMaterial& material, const WavelengthGrid& grid, int sublayers);

    /// One time step of dt seconds under `light` (Eq. 35 with the fluence of the state at
    /// the start of the step). Throws std::runtime_error if the spectra do not match the grid.
    void step(const Illumination& light, double dt_s);
    /// `steps` equal steps over `duration_s`.
    void run(const Illumination& light, double duration_s, int steps);

    int sublayers() const { return sublayers_; }
    size_t colorants() const { return colorant_names_.size(); }
    const WavelengthGrid& grid() const { return grid_; }
    /// Volume fraction of colorant j in sublayer i (0 = top).
    double fraction(int sublayer, size_t colorant) const
    {
        return fractions_[static_cast<size_t>(sublayer) * colorants() + colorant];
    }
    /// All fractions, sublayer-major: [i * colorants() + j].
    const std::vector<double>& fractions() const { return fractions_; }
    /// Replace the state (e.g. a profile read back from a fade stack); same layout, every
    /// fraction in [0, 1] (else std::runtime_error).
    void set_fractions(std::vector<double> fractions);

    /// The layer's spectra for the current fractions.
    LayerSpectra spectra() const;
    /// Top reflectance over the substrate, per wavelength (LayerSpectra::reflectance).
    std::vector<double> reflectance() const { return spectra().reflectance; }
    /// Absorption and scattering coefficients (1/m) of every sublayer at grid wavelength w.
    std::vector<double> absorption_profile(size_t w) const;
    std::vector<double> scattering_profile(size_t w) const;
    /// The mean fluence rate per sublayer at grid wavelength w under `light` (W m^-2 nm^-1),
    /// by the scalar solve_two_flux.
    std::vector<double> fluence_rate(const Illumination& light, size_t w) const;
    /// The same for every sublayer i and wavelength w at [i * grid().size() + w], by the
    /// vector kernel that step() uses.
    std::vector<double> fluence_rates(const Illumination& light) const;

    /// The kernels' instruction set: the best available by default. Throws
    /// std::runtime_error if this CPU cannot run `kernel`.
    void set_kernel(Kernel kernel);
    Kernel kernel() const { return kernel_; }
    /// float64 (default) or float32 for step() and fluence_rates().
    void set_precision(Precision precision) { precision_ = precision; }
    Precision precision() const { return precision_; }

private:
    // The kernels' copy of the spectra in one precision (V: Vec4 or Vec8f), and scratch.
    template <class V>
    struct Lanes {
        using Vector = std::vector<V, Align32Allocator<V>>;
        size_t vecs = 0;  // vectors per spectrum
        Vector absorption, scattering, rates, substrate;  // [j * vecs + v], [v]
        Vector work, acc, top, bottom;
        std::vector<typename LaneTraits<V>::Elem> fractions, last_fractions;  // this solve's
        // Sublayer terms of the last solve per block and row, reused for unchanged rows.
        Vector terms_cache;
        std::vector<char> row_same, block_fresh;
    };
    template <class V>
    void init_lanes(Lanes<V>& lanes) const;
    template <class V>
    void solve(const Illumination& light, Lanes<V>& lanes, bool rates, double* fluence) const;
    void sublayer_optics_at(size_t w, std::span<double> rho, std::span<double> tau) const;
    void check_light(const Illumination& light) const;

    WavelengthGrid grid_;
    size_t padded_ = 0;                 // wavelengths padded to whole blocks (zeros)
    int sublayers_ = 0;
    double dz_ = 0.0;
    Kernel kernel_ = Kernel::portable;
    Precision precision_ = Precision::float64;
    std::vector<std::string> colorant_names_;
    std::vector<double> weights_;       // trapezoid weights, nm
    // Per colorant j and padded wavelength w, at [j * padded_ + w]:
    std::vector<double> absorption_;    // a_j = mu_a / f, 1/m
    std::vector<double> scattering_;    // mu_s / f, 1/m
    std::vector<size_t> absorbers_;     // colorants with some absorption
    std::vector<size_t> scatterers_;    // colorants with some scattering
    // The non-zero rate spectra of Eq. (14) at [k * padded_ + w]: 0.5 w_λ β_j a_j (loss of
    // colorant j) or 0.5 w_λ γ_j a_j (gain of its product), trapezoid weight w_λ in nm, the
    // 0.5 of the fluence's mean over a sublayer's two boundaries folded in.
    std::vector<double> rates_;
    std::vector<size_t> rate_colorant_;
    std::vector<char> rate_is_gain_;
    std::vector<char> block_has_rate_;  // per block of 16 wavelengths: some rate non-zero
    std::vector<int> product_;          // breakdown product of colorant j, or -1
    std::vector<double> substrate_;     // rho*, [w]
    std::vector<double> fractions_;     // [i * J + j]
    // The kernels' data and step()'s scratch, sized once: no allocation per step.
    Lanes<Vec4> lanes64_;
    Lanes<Vec8f> lanes32_;
    std::vector<double> loss_, gain_, start_;
};

}  // namespace patina::texgen::fade
