// The particle deposition models of Dorsey & Hanrahan 1996 §3.3 (figure 5), after Barabási &
// Stanley 1995, "Fractal Concepts in Surface Growth": random deposition (RD, ch. 4), random
// deposition with surface relaxation (the Family model, ch. 5, Edwards-Wilkinson class) and
// ballistic deposition (BD, ch. 2, KPZ class). Heights are in monolayers (particles), on any
// Lattice; grow() turns them into thickness maps.
#pragma once

#include "texgen/growth/growth_model.h"
#include "texgen/growth/lattice.h"

#include <cstdint>
#include <span>
#include <vector>

namespace patina::texgen {

/// Drops particles one at a time on uniformly chosen nodes and returns the height of every
/// node after the first counts[k] particles, for each k (counts non-decreasing):
/// - RandomDeposition: h_i += 1.
/// - RandomDepositionRelaxed: the particle settles on the lowest node within
///   `parameters.relaxation_radius` (in lattice steps of cell_size; 0 -> one step, Family's
///   nearest neighbours) of where it landed; ties stay, then go to the nearest, then to a
///   random one of those.
/// - BallisticDeposition: h_i = max(h_i + 1, h_j over the neighbours j) (it sticks to the
///   first particle it touches, leaving voids below).
/// Deterministic for (lattice, model, parameters, seed) whatever the thread count; a
/// snapshot does not depend on the later counts asked for. Lattices of
/// more than 32768 nodes run in blocks in parallel (see BlockedDeposition in the .cpp: exact
/// for RD; for BD and RDR particles on either side of a block edge keep their order only at
/// the scale of a quarter monolayer); RDR with a reach over one step runs sequentially.
/// Throws std::invalid_argument for another model, decreasing counts, an empty lattice or a
/// relaxation radius over 16 steps.
std::vector<std::vector<int32_t>> deposit_heights(const Lattice& lattice, GrowthModelKind model,
                                                  const GrowthParameters& parameters,
                                                  uint64_t seed,
                                                  std::span<const uint64_t> counts);

/// True for RD, RDR and BD, the models deposit_heights runs.
bool is_deposition_model(GrowthModelKind model);

} // namespace patina::texgen
