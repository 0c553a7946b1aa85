// The layered surface of Dorsey & Hanrahan 1996 §3.1: "a surface contains a stack of n
// layers. The '0'-th layer is assumed to be the base material with an essentially infinite
// thickness ... Each individual layer also has a thickness, although it may be zero at
// certain points." Every layer is one homogeneous material; only its thickness varies with
// position (per texel). Thicknesses and heights are in micrometres (µm).
//
// A "texel" here is any index 0..texel_count-1: the interpreter maps texel groups or lattice
// nodes to it. The operators that change a stack are in operators.h.
#pragma once

#include <cstddef>
#include <vector>

namespace patina::texgen {

/// One layer: a material (an id the caller's material table gives meaning to) and its
/// thickness at every texel (µm, >= 0; zero where the layer is absent).
struct Layer {
    int material = 0;
    std::vector<float> thickness_um;
};

/// A base material of infinite thickness under `layers`, listed bottom to top as the script
/// made them. A layer that is zero everywhere stays in the list (it still names a step of
/// the script; drop_empty_layers removes such layers when the caller wants).
/// Invariant (kept by the operators): every layer has texel_count thicknesses.
struct LayerStack {
    int base_material = 0;
    size_t texel_count = 0;
    std::vector<Layer> layers;

    /// Height of the top of the stack above the base at `texel` (µm): the sum of the layer
    /// thicknesses, added bottom to top in float. Every operator that aims at a height
    /// (fill, polish) measures with this same sum, so its guarantee holds bit for bit.
    float total_height(size_t texel) const;

    /// total_height of every texel (parallel, same bits as total_height).
    std::vector<float> total_heights() const;

    /// Index into `layers` of the layer seen from above at `texel` (the top layer whose
    /// thickness there is > 0), or -1 where every layer is absent and the base shows.
    int exposed_layer(size_t texel) const;

    /// Material seen from above at `texel`: that of exposed_layer, or the base material.
    int exposed_material(size_t texel) const;
};

/// Remove the layers whose thickness is zero at every texel (the stack's other layers and
/// their order are unchanged). Returns how many were removed.
size_t drop_empty_layers(LayerStack& stack);

}  // namespace patina::texgen
