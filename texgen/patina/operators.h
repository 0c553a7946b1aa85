// The operators on layers of Dorsey & Hanrahan 1996 §3.2: "The development of a patina is
// implemented as a series of operators on layers." Each works per texel on a LayerStack
// (layer_stack.h); thicknesses and heights are in µm above the base material.
//
// Maps: an operator's amount is `value * map[i]` at texel i; an empty map means 1
// everywhere. A map value below 0 counts as 0 (a noise map may dip below zero; no operator
// turns into its opposite). Every texel is independent, so the operators run in parallel
// (TBB) and give the same bits for any thread count.
//
// Errors: std::invalid_argument whose message starts with the operator's name ("coat: ..."),
// for a negative or non-finite value, a non-finite map value, a map whose size is not the
// stack's texel count, or a negative material id. Zero is a valid amount (see each operator).
#pragma once

#include "texgen/patina/layer_stack.h"

#include <span>

namespace patina::texgen {

/// Most layers a stack may hold above its base (coat, fill and offset each add one); the
/// layered_km shader renders up to 16 of them.
inline constexpr size_t kMaxStackLayers = 256;

/// `new material`: a stack whose base ("the '0'-th layer ... with an essentially infinite
/// thickness", §3.1) is `material`, with no layers, over `texel_count` texels.
LayerStack new_stack(int material, size_t texel_count);

/// `coat material thickness thickness-map`: "adds a new layer of material to a surface. The
/// new layer has a specified maximum thickness that is modulated by the thickness map."
/// The layer is thickness_um * map[i] thick. A zero thickness adds a layer that is absent
/// everywhere (it stays in the stack, as the script made it).
void coat(LayerStack& stack, int material, float thickness_um, std::span<const float> map = {});

/// `erode thickness thickness-map`: "proceeds through the stack of layers decreasing the
/// thickness of each layer until the desired amount of material has been removed. This
/// provides a means to cut into a material and expose underlying layers." Removes
/// thickness_um * map[i] from the top down, through as many layers as it takes. The base is
/// infinitely thick (§3.1) and is never cut: where the amount exceeds the total height, the
/// erosion stops at the base (every layer there becomes 0). Layers keep their place in the
/// stack even where eroded to 0. Zero removes nothing.
/// Eroding exactly what a coat added (same thickness, same map) restores every texel of the
/// stack bit for bit: the same float product t * map[i] is removed from the top layer it
/// made, and x - x == 0 exactly; the layers below are not touched.
void erode(LayerStack& stack, float thickness_um, std::span<const float> map = {});

/// `fill material height height-map`: "deposits material up to a given absolute height above
/// the base material ... akin to filling all the valleys with water until it reaches a
/// given height." Adds a layer of max(0, h_i - total_i) with h_i = height_um * map[i]:
/// afterwards total_height(i) >= h_i at every texel (guaranteed for the float sum of
/// LayerStack::total_height: the new thickness is rounded up by an ulp where the sum would
/// fall short), and texels already at or above h_i are unchanged. Zero adds an empty layer.
void fill(LayerStack& stack, int material, float height_um, std::span<const float> map = {});

/// `polish height height-map`: "removes material until a given absolute height above the
/// base material is reached. The result is a smoothing effect across a surface." Cuts every
/// layer at h_i = height_um * map[i]: afterwards total_height(i) <= h_i (exactly, for the
/// float sum of LayerStack::total_height), and texels at or below h_i are unchanged. Zero
/// removes every layer's material, exposing the base everywhere.
void polish(LayerStack& stack, float height_um, std::span<const float> map = {});

/// The height at which a horizontal cut through `heights` meets `fraction` of the area: the
/// bearing-area (Abbott-Firestone) curve of the surface (Thomas, "Rough Surfaces", 1982, the
/// paper's ref. [29]) read backwards. With the texels sorted by height, highest first
/// (ties by index), it is the height of the first texel at which the cumulative weight
/// reaches fraction * (total weight): the texels at or above it hold at least `fraction` of
/// the weight and those strictly above it less. Texels of weight 0 do not count. `weights`
/// (one per texel, >= 0; empty = uniform) is the area each texel stands for, e.g. coverage
/// times world area. Throws std::invalid_argument ("polish until exposed: ...") when
/// fraction is outside [0, 1], a weight is negative or not finite, or all weights are 0.
float bearing_height(std::span<const float> heights, float fraction,
                     std::span<const float> weights = {});

/// The variant of polish that "removes material until a given area of surface is exposed"
/// (§3.2, "motivated by observing profiles and statistics of rough surfaces after they have
/// been polished [29]"): polish to bearing_height(total heights, fraction, weights), so that
/// the polished plateau covers `fraction` of the area (to within the share of one texel).
/// Fraction 0 polishes nothing (the height is the highest texel's); 1 polishes everything
/// down to the lowest texel. Returns the height used (µm).
float polish_until_exposed(LayerStack& stack, float fraction, std::span<const float> weights = {});

/// `offset radius`: "applies a material to a surface by first applying a thick coat and then
/// removing the part accessible to a sphere of a given radius" (§3.2, after Miller 1994).
/// What the sphere cannot reach is computed elsewhere (heightfield_offset.h on a flat strip;
/// the accessibility bakers on a mesh); this adds it as a layer of `material` whose
/// thickness at texel i is fill_thickness_um[i] (>= 0, finite, one per texel).
void offset(LayerStack& stack, int material, std::span<const float> fill_thickness_um);

}  // namespace patina::texgen
