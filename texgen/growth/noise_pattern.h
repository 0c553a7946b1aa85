// The procedural thickness patterns of Dorsey & Hanrahan 1996 §3.3's last paragraph ("noise
// and turbulence functions"): solid noise at each node's world position.
#pragma once

#include "texgen/growth/growth_model.h"
#include "texgen/growth/lattice.h"

#include <cstdint>
#include <vector>

namespace patina::texgen {

/// The pattern over the nodes at the end of the run, in [0, 1]: for `turbulence` false,
/// 0.5 + 0.5 noise(p / feature_size) (clamped); for true, the turbulence of `octaves`
/// octaves at p / feature_size. `resolved` must come from resolve_growth_parameters.
std::vector<float> noise_pattern(const Lattice& lattice, const GrowthParameters& resolved,
                                 uint64_t seed, bool turbulence);

} // namespace patina::texgen
