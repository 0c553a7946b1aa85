// `patina-texgen export` of patina stacks: one stack or a whole time series flattened
// (texgen/flatten: the maps `flatten` defines, one code path for both) and written as
// glTF 2.0 — the strip as a plane of its real size or the mesh the stack was grown on, a
// metallic-roughness material with KHR_materials_clearcoat per step (and per UDIM tile),
// and a series as one asset whose steps are KHR_materials_variants named by age.
// docs/export.md has the maps and their encodings.
#pragma once

#include "core/color_management.h"
#include "core/mesh_convention.h"

#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen {

struct ExportOptions {
    std::string preset = "gltf";  ///< the packing and naming of the maps (docs/export.md)
    int bits = 0;  ///< texture presets: 8 or 16 (PNG), 32 (float EXR); 0: 8, the exr preset 32
    bool separate = false;        ///< .gltf with .bin and PNGs beside it, not one .glb
    int resolution = 0;           ///< texels per tile side; 0: the stack's
    double normal_scale = 1.0;    ///< height exaggeration of the normal map
    /// The renderer the glTF material is fitted for: "khronos" (three.js, Babylon.js, the
    /// Khronos sample viewer) or "blender" (Blender 3.4's Principled BSDF); docs/export.md.
    std::string target = "khronos";
    /// File names of the maps with --separate: $mesh (the output's stem), $material (the
    /// step, e.g. "t30"), $map (base_color, ...), $udim (the tile).
    std::string name_template = "$mesh_$material_$map";
    /// The mesh a stack grown on a mesh was grown on; empty: the path the stack records.
    std::filesystem::path mesh;
    /// Its up axis and unit; what they leave open comes from the stack's record
    /// (texgen/meshes/mesh_input.h), then from the file.
    MeshConventionOptions convention;
};

/// What an export wrote and of what.
struct ExportResult {
    std::vector<std::filesystem::path> files;
    size_t steps = 0, textures = 0;
    int width = 0, height = 0;
};

/// Exports the patina stack or series at `input` (a stack folder or its stack.toml, or a
/// series folder holding series.toml) to `output`: a .glb (or .gltf with `separate`) for
/// the gltf preset, a folder of textures for the others.
/// Throws std::runtime_error naming the file or option for: an unknown preset, an output
/// whose extension does not match, a mesh stack whose mesh is not found (or does not fit
/// its tiles), a series whose steps differ in resolution, tiles or domain, a UDIM tile
/// beyond 1099, a NaN texel; the
/// output is written last, under a temporary name, so nothing is left half-written.
ExportResult export_patina(const std::filesystem::path& input,
                           const std::filesystem::path& output, const ExportOptions& options,
                           const ColorManager& colors);

/// "0 y", "6 y", "7.5 y": a step's variant name.
std::string age_name(double years);

/// `file` relative to `dir` with '/' separators, or `file` as given when it has no relative
/// form.
/// `input`/stack.toml for a folder, `input` itself otherwise.
std::filesystem::path stack_manifest_of(const std::filesystem::path& input);

std::string relative_to(const std::filesystem::path& file, const std::filesystem::path& dir);

}  // namespace patina::texgen
