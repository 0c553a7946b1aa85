// A quick look at a patina stack without a renderer: the Kubelka-Munk diffuse colour of
// every texel's layers over the base (Dorsey & Hanrahan 1996 §4.1-4.2), per linear Rec.709
// channel, written as a display PNG through OpenColorIO.
#pragma once

#include "core/color_management.h"
#include "texgen/patina/material_library.h"

#include <Imath/ImathVec.h>

#include <filesystem>
#include <span>
#include <vector>

namespace patina::texgen {

/// One layer of a stack as the preview sees it: its material and per-texel thickness (µm).
struct PreviewLayer {
    const PatinaMaterial* material = nullptr;
    std::span<const float> thickness_um;
};

/// Diffuse reflectance (linear Rec.709) of each of `texels` stacks: each layer's KM R and T
/// from its K, S and thickness (§4.1), composited over the opaque base of reflectance
/// base.color (§4.2, the base as a layer with T = 0). Layers bottom to top.
std::vector<Imath::V3f> stack_diffuse_color(const PatinaMaterial& base,
                                            std::span<const PreviewLayer> bottom_to_top,
                                            size_t texels);

/// Write `colors` (linear Rec.709, width x height, row 0 at the top; texels outside the
/// mesh given by `covered`, when not empty, are drawn mid grey) as an 8-bit sRGB PNG via
/// OCIO (lin_rec709 -> srgb_texture), atomically.
void write_preview_png(const std::filesystem::path& path, std::span<const Imath::V3f> colors,
                       int width, int height, std::span<const uint8_t> covered,
                       const ColorManager& color_manager);

}  // namespace patina::texgen
