// A quick look at a patina stack without a renderer: the Kubelka-Munk diffuse colour of
// every texel's layers over the base (Dorsey & Hanrahan 1996 §4.1-4.2), the stack model of
// flatten (texgen/flatten/flat_texel.h) on the optics the stack records, written as a
// display PNG through OpenColorIO.
#pragma once

#include "core/color_management.h"
#include "texgen/flatten/band_optics.h"

#include <Imath/ImathVec.h>

#include <filesystem>
#include <span>
#include <vector>

namespace patina::texgen {

/// Reflectance (linear Rec.709 under D65) of each of `texels` stacks: flatten's diffuse
/// albedo (flat_texel.h), over a metal base with the metal's once-through reflection kept:
/// the whole reflectance, what the surface looks like. `thickness_um[l]` holds layer l's
/// thickness (µm) at every texel, bottom to top.
std::vector<Imath::V3f> stack_diffuse_color(const BandStack& stack,
                                            std::span<const std::vector<float>> thickness_um,
                                            size_t texels, const BandsToRgb& to_rgb);

/// Write `colors` (linear Rec.709, width x height, row 0 at the top; texels outside the
/// mesh given by `covered`, when not empty, are drawn mid grey) as an 8-bit sRGB PNG via
/// OCIO (lin_rec709 -> srgb_texture), atomically.
void write_preview_png(const std::filesystem::path& path, std::span<const Imath::V3f> colors,
                       int width, int height, std::span<const uint8_t> covered,
                       const ColorManager& color_manager);

}  // namespace patina::texgen
