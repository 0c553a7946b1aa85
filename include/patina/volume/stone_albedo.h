// The single-scattering albedo of weathered stone from a voxel's composition (Dorsey et al.
// 1999 §5.1: the stone's own albedo, darkened or tinted by its crust, iron oxide and salt):
// the weights of the four albedos, written once for the slab_volume medium (spectra) and for
// `patina-texgen export`'s OpenVDB colour grid (RGB).
#pragma once

#include <patina/volume/voxel_grid.h>

#include <algorithm>

namespace patina::volume {

/// The weights of the stone, crust, iron and salt albedos at a voxel whose crust, iron and
/// salt fractions are `fraction` (kCrust, kIron, kSalt), each first multiplied by its `gain`
/// and clamped to [0, 1]; fractions summing above 1 are scaled to sum to 1, and the stone
/// takes what they leave.
inline void albedo_weights(const float fraction[kCompositionCount],
                           const float gain[kCompositionCount], float weight[4])
{
    float q[kCompositionCount];
    float sum = 0.0f;
    for (int c = 0; c < kCompositionCount; ++c) {
        q[c] = std::clamp(fraction[c] * gain[c], 0.0f, 1.0f);
        sum += q[c];
    }
    if (sum > 1.0f) {
        for (float& f : q)
            f /= sum;
        sum = 1.0f;
    }
    weight[0] = 1.0f - sum;
    weight[1] = q[kCrust];
    weight[2] = q[kIron];
    weight[3] = q[kSalt];
}

}  // namespace patina::volume
