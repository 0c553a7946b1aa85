// The eroded surface as a triangle mesh: surface nets (Gibson 1998, "Constrained elastic
// surface nets") on the world grid's density at 1/2. One vertex per grid cell the surface
// crosses, at the mean of the crossings on its edges; one quad (two triangles) per grid edge
// the surface crosses, wound so the normals point out of the stone.
#pragma once

#include "core/mesh.h"
#include "texgen/stone_export/volume_export.h"

namespace patina::texgen::stone {

/// Throws std::runtime_error when the density never crosses 1/2 (no surface).
TriangleMesh extract_eroded_surface(const WorldVolume& volume, float iso = 0.5f);

} // namespace patina::texgen::stone
