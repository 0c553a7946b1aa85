// The ground under a baked mesh: a plane placed at its lowest point (--ground), and the check
// that an occluder does not cut through the mesh it shades.
#pragma once

#include "core/mesh.h"

#include <string>
#include <vector>

namespace patina::texgen {

/// A horizontal square facing +y, centred under `mesh`'s bounds at its lowest y, 20 times
/// the widest horizontal extent of the bounds across (at least 1 m): wide enough that the sky
/// it hides from the mesh is the sky a real ground hides (an obstruction 10 half-widths away
/// subtends under 6 degrees above the horizon).
TriangleMesh ground_under(const TriangleMesh& mesh);

/// Where `occluder` cuts through `target`: a description of how many of the target's
/// triangle edges cross an occluder triangle, with the first crossing point and, for a
/// horizontal occluder, the heights involved; empty when none does. An edge that only
/// touches an occluder at its ends (a statue standing on the ground) does not count.
std::string occluder_crossing(const TriangleMesh& target,
                              const std::vector<TriangleMesh>& occluder);

} // namespace patina::texgen
