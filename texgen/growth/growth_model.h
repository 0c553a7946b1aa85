// Thickness maps through time: the fractal surface growth models of Dorsey & Hanrahan 1996
// §3.3 (steady thickening, random deposition with and without surface relaxation, ballistic
// deposition, directed percolation depinning) and the procedural noise and turbulence of
// §3.3's last paragraph, each run on a Lattice (a flat grid, or the texels of a mesh joined
// across its uv seams) and paced by one of the classic oxidation rate laws.
//
// A script's `texture(MODEL RATE STEP TOTAL)` is grow(lattice, {MODEL, RATE, STEP, TOTAL},
// seed, {STEP / TOTAL}): the map the model has grown after STEP of its TOTAL steps. In a time
// series the interpreter scales that fraction by t / T (the step's time over the series'
// last time), so a time series shows the same patches growing, from one simulation.
#pragma once

#include "texgen/growth/lattice.h"

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

namespace patina::texgen {

enum class GrowthModelKind {
    SteadyThickening,             // "ST"
    RandomDeposition,             // "RD"
    RandomDepositionRelaxed,      // "RDR": RD with surface relaxation (the Family model)
    BallisticDeposition,          // "BD"
    DirectedPercolationDepinning, // "DPD"
    Noise,                        // "noise"
    Turbulence,                   // "turbulence"
};

enum class GrowthRate { Linear, Parabolic, Logarithmic, Cubic };

/// Script names, case-sensitive as the paper prints them: "ST", "RD", "RDR", "BD", "DPD",
/// "noise", "turbulence"; rates "linear", "parabolic", "logarithmic", "cubic". The name
/// lists serve "did you mean" messages.
std::optional<GrowthModelKind> growth_model_from_name(std::string_view name);
std::optional<GrowthRate> growth_rate_from_name(std::string_view name);
std::span<const std::string_view> growth_model_names();
std::span<const std::string_view> growth_rate_names();
std::string_view growth_model_name(GrowthModelKind model);
std::string_view growth_rate_name(GrowthRate rate);

/// The amount grown by fraction f in [0, 1] of a run, normalised so that g(0) = 0 and
/// g(1) = 1: the classic oxidation rate laws (Evans 1960, "The Corrosion and Oxidation of
/// Metals"; Kubaschewski & Hopkins 1962, "Oxidation of Metals and Alloys"):
/// linear x = k t -> f; parabolic x^2 = k t -> sqrt(f); cubic x^3 = k t -> cbrt(f);
/// logarithmic x = k1 ln(1 + k2 t) -> ln(1 + 20 f) / ln(21). Throws std::invalid_argument
/// for f outside [0, 1].
double growth_rate(GrowthRate rate, double f);

/// The logarithmic law's k2 in units of the run (how fast it flattens).
inline constexpr double kLogarithmicRateConstant = 20.0;

/// Every size in metres (world units), so that a pattern does not depend on the resolution
/// of the lattice it is grown on. A size of 0 means a default given in lattice cells (of the
/// lattice's mean cell size), noted beside it.
struct GrowthParameters {
    // RD, RDR, BD
    double layers = 16;            ///< monolayers deposited per node over the whole run
    double relaxation_radius = 0;  ///< RDR: how far a particle may move to settle (m); 0 -> 1 cell

    // DPD (D&H 1996 §3.3, figure 6)
    double patch_size = 0;         ///< edge of a square seed patch (m); 0 -> 10 cells (the paper's)
    double blocked_fraction = 0.5; ///< share of blocked lattice cells
    double seed_density = 0;       ///< seed patches at the start, per m^2; 0 -> one per 6x6 patches
    double new_seed_ratio = 1;     ///< seeds appearing over the run, per m^2 of then unoccupied
                                   ///< area, as a multiple of seed_density (0: none)
    double spread_distance = 0;    ///< length of the run: its sweeps times the cell size (m);
                                   ///< a front advances a fraction of it; 0 -> 10 patch sizes
    double advance_unblocked = 0.6; ///< chance per sweep that a patch advances onto an
                                    ///< unblocked neighbour
    double advance_blocked = 0.1;   ///< ... onto a blocked neighbour
    int levels = 8;                ///< thickness levels (1..255)

    // ST
    double st_spacing = 0;         ///< spacing of its sample points (m); 0 -> 16 cells
    double noise_amplitude = 0.1;  ///< ST's "small amount of noise", relative to its thickness

    // noise, turbulence
    double feature_size = 0;       ///< size of a noise feature (m); 0 -> 32 cells
    int octaves = 5;               ///< turbulence octaves (1..16)
};

struct GrowthSpec {
    GrowthModelKind model = GrowthModelKind::RandomDeposition;
    GrowthRate rate = GrowthRate::Linear;
    int step = 1;  ///< the script's STEP: 0 <= step <= total
    int total = 1; ///< the script's TOTAL: > 0
    GrowthParameters parameters;
};

/// STEP / TOTAL of a spec, after checking 0 <= step <= total and total > 0 (throws
/// std::invalid_argument naming the bad one).
double growth_fraction(const GrowthSpec& spec);

/// The model's thickness map at each requested fraction of its run (each in [0, 1]; the run
/// is `total` steps and fraction f corresponds to step f * total, the amount grown by then
/// being growth_rate(rate, f) of the whole run). One simulation serves every fraction
/// (snapshots), so a time series shows the same patches growing. Each map has one value per
/// lattice node, normalised by the maximum over the nodes at f = 1, so values lie in [0, 1]
/// and grow monotonically in f at every node. Deterministic for (lattice, spec, seed)
/// whatever the thread count. Throws std::invalid_argument naming the bad parameter.
std::vector<std::vector<float>> grow(const Lattice& lattice, const GrowthSpec& spec,
                                     uint64_t seed, std::span<const double> fractions);

/// The parameters with every default (0) size resolved to metres for this lattice, after
/// checking them (std::invalid_argument naming the parameter). grow() runs on these.
GrowthParameters resolve_growth_parameters(const Lattice& lattice,
                                           const GrowthParameters& parameters);

/// Mean lattice step (m) over the nodes: the "cell" that defaults are given in.
double mean_cell_size(const Lattice& lattice);

} // namespace patina::texgen
