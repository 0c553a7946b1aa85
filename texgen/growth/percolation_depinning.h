// Directed percolation depinning (DPD), Dorsey & Hanrahan 1996 §3.3 and figure 6: square
// seed patches spread over a lattice of blocked and unblocked cells, much more readily onto
// unblocked ones (moisture on the surface), new seeds appear on unoccupied cells over time,
// and upper thickness levels fill in where the level below supports them.
//
// Each sweep of the paper's process gives an unoccupied node a chance to be taken from each
// occupied neighbour. With an independent geometric waiting time per neighbour, the sweep at
// which a node is taken is a first-passage time, min over neighbours u of T(u) + delay(u, v)
// (first-passage percolation; Eden 1961), so one Dijkstra pass with a bucket queue (Dial
// 1969) gives the whole history at once: every snapshot of a time series comes from one run,
// in O(nodes) work. The level l + 1 clocks likewise start at the supporting level-l nodes,
// so a node with more support climbs sooner ("probability proportional to the number of
// cells in level l that support it").
#pragma once

#include "texgen/growth/growth_model.h"
#include "texgen/growth/lattice.h"

#include <cstdint>
#include <span>
#include <vector>

namespace patina::texgen {

/// Whether each node is blocked: a share `blocked_fraction` of the nodes, independently.
std::vector<uint8_t> dpd_blocked_nodes(const Lattice& lattice, double blocked_fraction,
                                       uint64_t seed);

/// The nodes of a square seed patch of about `side` lattice steps centred on `centre`: the
/// straight walks along the node's first neighbour pair, and from each node of that line
/// the straight walks along the other pair (so on a grid exactly a side x side square; on a
/// surface lattice the walks go straight on across seams). Nodes may repeat.
void dpd_patch_nodes(const Lattice& lattice, int32_t centre, int side,
                     std::vector<int32_t>& out);

/// The run's length in sweeps for these parameters (spread_distance / mean cell size).
int dpd_sweeps(const Lattice& lattice, const GrowthParameters& resolved);

/// The number of levels (0 = void .. parameters.levels) each node has reached at each time,
/// given as fractions of the run in [0, 1] (time t is sweep t * dpd_sweeps; the first seed
/// patches appear in sweep 1, so at time 0 the surface is bare). `resolved` must come from
/// resolve_growth_parameters. Deterministic for (lattice, parameters, seed) whatever the
/// thread count.
std::vector<std::vector<uint8_t>> percolation_depinning_levels(const Lattice& lattice,
                                                               const GrowthParameters& resolved,
                                                               uint64_t seed,
                                                               std::span<const double> times);

} // namespace patina::texgen
