// Steady thickening (ST), Dorsey & Hanrahan 1996 §3.3: "sample a surface evenly with a small
// number of points", give each an initial thickness, interpolate between them, thicken every
// point by the growth rate and add "a small amount of noise": a relatively uniform layer.
#pragma once

#include "texgen/growth/growth_model.h"
#include "texgen/growth/lattice.h"

#include <cstdint>
#include <vector>

namespace patina::texgen {

/// ST's pattern over the nodes at the end of its run, before normalisation: the sample
/// points sit on a cubic grid of spacing st_spacing in world space, each with a thickness
/// in [1 - kSteadyThickeningSpread, 1 + kSteadyThickeningSpread], interpolated smoothly
/// (a cubic B-spline over the grid, C2) at each node's position, plus
/// noise_amplitude times gradient noise of a quarter of that spacing; never negative. Its
/// value at fraction f of the run is growth_rate(f) times this. `resolved` must come from
/// resolve_growth_parameters.
std::vector<float> steady_thickening_pattern(const Lattice& lattice,
                                             const GrowthParameters& resolved, uint64_t seed);

/// How far the sample points' thicknesses spread about their mean (relative).
inline constexpr double kSteadyThickeningSpread = 0.4;

} // namespace patina::texgen
