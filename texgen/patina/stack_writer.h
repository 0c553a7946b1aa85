// Writing a patina stack at one time step (D&H 1996 §3.3 "the layer structure is output as
// a series of material properties and texture maps"; DESIGN.md "texgen" output rules): the
// layer thicknesses as one multi-channel map and as one map per layer, the total thickness
// (for displacement or bump, §4.3), a `[patina]` table in stack.toml listing the layers
// bottom to top with their materials, and a KM preview PNG.
#pragma once

#include "core/color_management.h"
#include "texgen/patina/interpreter.h"
#include "texgen/stack/map_output.h"

#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen {

struct PatinaOutputOptions {
    MapOutputOptions maps;
    bool preview = true;
    std::string script;           ///< the script's file name, for the manifest
    Metadata parameters;          ///< recorded in every map's header and the manifest
};

/// The map name of layer `index` (1 = the lowest layer over the base): "layer01_tarnish".
std::string layer_map_name(size_t index, const PatinaMaterial& material);

/// The channel of layer `index` in thickness.exr: "layer01_tarnish", the number zero-padded
/// to the digits of `layer_count` (at least 2), so that the names sort in layer order (as
/// OpenEXR stores channels).
std::string layer_channel_name(size_t index, size_t layer_count, const PatinaMaterial& material);

/// Write `step` into `out_dir` (created if missing): thickness.exr (one channel per layer,
/// bottom to top, µm; what the layered shader reads with one lookup), layerNN_<material>.exr
/// per layer (the same thickness, channel "thickness", for tools that take one map per
/// layer), total_thickness.exr (channel "thickness", µm), preview.png (of the first tile,
/// every n-th texel so that it is at most 1024 wide) and stack.toml, whose [[patina.layers]]
/// name `map = "thickness"`, their `channel` and their `layer_map`. Maps of an earlier patina
/// run in the folder that this step does not have are dropped from its stack.toml (their
/// files are removed). Every file is written under a temporary name and renamed. Returns the
/// files written.
std::vector<std::filesystem::path> write_patina_step(const std::filesystem::path& out_dir,
                                                     const PatinaStep& step,
                                                     const PatinaDomain& domain,
                                                     const PatinaOutputOptions& options,
                                                     const ColorManager& colors);

}  // namespace patina::texgen
