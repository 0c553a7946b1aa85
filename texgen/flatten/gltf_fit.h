// The glTF material of a texel fitted to Patina's: given the directional albedo of the
// texel's layered BRDF (layered_km's, flat_texel.h) at the Gauss cosines, split into its
// diffuse lobe's and its glossy lobes', the base colour and the coat weight with which the
// target renderer's glTF BRDF (gltf_albedo.h) reflects as much light in each part at each
// cosine: least squares weighted as the hemisphere is seen (2 μ dμ). Matching the parts
// and not only their sum keeps a texel's look under a sun, whose light the glossy lobes send
// elsewhere, as under a uniform sky. The base colour is solved in closed form per channel,
// the coat weight (shared by the channels) in closed form given the colour, twice. The
// lobes' widths (roughness, coat roughness) and the metallic share come from the two-lobe
// reduction (flat_texel.h).
#pragma once

#include "texgen/flatten/gltf_albedo.h"

#include <patina/shading/lanes.h>

#include <Imath/ImathVec.h>

#include <array>

namespace patina::texgen {

struct TwoLobe;

/// A texel's directional albedo at the Gauss cosines, its diffuse lobe's and its glossy
/// lobes' parts (R, G, B in lanes 0-2).
struct AlbedoParts {
    std::array<shading::simd::V4, shading::kGaussNodes> diffuse{}, glossy{};
};

/// The reduction `start` with its base colour and coat weight fitted to `albedo`.
TwoLobe fit_gltf(const GltfAlbedo& model, GltfTarget target, const AlbedoParts& albedo,
                 const TwoLobe& start);

/// The target's directional albedo of a two-lobe material at the Gauss cosines.
std::array<Imath::V3f, shading::kGaussNodes> gltf_albedo_of(const GltfAlbedo& model,
                                                            GltfTarget target,
                                                            const TwoLobe& material);

}  // namespace patina::texgen
