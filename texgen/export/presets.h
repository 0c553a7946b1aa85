// The packings of the flattened maps (texgen/flatten) for other programs: glTF 2.0, Unreal
// Engine, Unity HDRP and plain linear EXRs for Standard-Surface-like look files. Each preset
// names its maps and says what goes in each channel and in which encoding; docs/export.md
// has the tables.
#pragma once

#include "core/color_management.h"
#include "texgen/flatten/flatten_stack.h"

#include <string>
#include <vector>

namespace patina::texgen {

/// One map of a preset, for one step and tile: texels (row 0 at the top, channels
/// interleaved) ready to be written, in [0, 1] unless `linear_float`.
/// The gltf preset's clearcoat map (KHR_materials_clearcoat's texture), absent from a tile
/// whose coat is 0 everywhere.
inline constexpr const char* kGltfPresetCoat = "clearcoat";

struct PresetMap {
    std::string name;                    ///< $map of the file-name template
    std::vector<std::string> channels;   ///< R, G, B, A or named (EXR)
    std::vector<float> texels;
    bool srgb = false;                   ///< sRGB-encoded colour (else linear data or colour)
    int min_bits = 8;                    ///< 16 where 8 bits would band (height)
};

/// The presets: "gltf", "unreal", "unity-hdrp", "exr".
const std::vector<std::string>& preset_names();

/// Throws std::runtime_error naming --preset and the presets unless `preset` is one.
void check_preset(const std::string& preset);

/// True for the presets that write a folder of textures (not a glTF asset).
bool preset_writes_textures(const std::string& preset);

/// `flat`'s tile `tile` packed as `preset` packs it (colour encoded through `colors`). The
/// height of the PNG presets is stored as height / `height_range_um` (one range for every
/// step of a series, so that the steps compare); the exr preset stores metres. Throws
/// std::runtime_error naming --preset for an unknown preset.
std::vector<PresetMap> preset_maps(const std::string& preset, const FlattenedStack& flat,
                                   size_t tile, double height_range_um,
                                   const ColorManager& colors);

}  // namespace patina::texgen
