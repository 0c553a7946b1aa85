// The policy for uvs outside the UDIM tiles (docs/your-asset.md): UDIM tiles (0 <= u < 10,
// 0 <= v) stay as they are; a triangle elsewhere (u < 0, v < 0, u >= 10) is refused by the
// bakers unless --uv-wrap folds it into tile 1001 as texture wrapping would.
#pragma once

#include "core/mesh.h"

#include <cstddef>

namespace patina::texgen {

/// Move every triangle whose uv centroid lies outside the UDIM tiles by whole units so that
/// its centroid falls into [0, 1)^2, as a renderer's periodic (repeat) wrapping reads it:
/// the texels it is baked into are the ones such a lookup finds. Vertices shared with
/// triangles that do not move are duplicated (same position and normal). Returns the number
/// of triangles moved. A mesh without uvs is left alone.
size_t wrap_uvs_outside_udims(TriangleMesh& mesh);

} // namespace patina::texgen
