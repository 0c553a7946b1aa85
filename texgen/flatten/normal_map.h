// A tangent-space normal map from a height field (D&H 1996 §4.3: the stack's total
// thickness "may be used to either perturb the normals or displace the surface").
#pragma once

#include <span>
#include <vector>

namespace patina::texgen {

/// Normals of the height field `height_um` (width x height texels, row 0 at the top, i.e.
/// v = 1, as every image file), texels `texel_size_um` apart, heights multiplied by
/// `scale` (1: true relief). Central differences, clamped at the borders. Tangent space in
/// the OpenGL convention: +X along +u, +Y along +v (up in the image: green up), +Z out of
/// the surface; n = normalize(-dh/du, -dh/dv, 1). Returned as three floats per texel,
/// encoded the usual way, n * 0.5 + 0.5 (a flat surface is (0.5, 0.5, 1)).
std::vector<float> normal_map_from_height(std::span<const float> height_um, int width,
                                          int height, double texel_size_um, double scale);

/// Decode one encoded component (2 c - 1).
inline float decode_normal_component(float encoded)
{
    return 2.0f * encoded - 1.0f;
}

}  // namespace patina::texgen
