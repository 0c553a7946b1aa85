// What every export shares, whatever it exports (patina stacks, fade stacks): the steps as
// flattened maps (texgen/flatten's names: gltf_base_color, gltf_metallic_roughness,
// gltf_clearcoat, normal, height), the geometry they lie on, and the writers — a glTF 2.0
// asset with a material per step and UDIM tile (a series as KHR_materials_variants), or a
// folder of textures packed by a preset (texgen/export/presets.h).
#pragma once

#include "core/color_management.h"
#include "core/mesh.h"
#include "texgen/export/export_patina.h"
#include "texgen/flatten/flatten_stack.h"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace patina::texgen {

/// One step of an export: a stack at one age.
struct ExportStep {
    std::string label;    ///< $material of the file names: "t30", the step's folder
    std::string variant;  ///< the age, as the variant and the material are named: "30 y"
    std::filesystem::path manifest;  ///< the file the step was read from (for messages)
    nlohmann::json extras;           ///< the material's extras.patina
    FlattenedStack flat;             ///< for the gltf preset, its maps are dropped once encoded
    /// gltf: per tile, ($map, PNG)
    std::vector<std::vector<std::pair<std::string, std::vector<unsigned char>>>> pngs;
};

/// What the maps lie on: the mesh (with uvs), or, when it is empty, a plane of
/// width_m x height_m facing +Z.
struct ExportGeometry {
    TriangleMesh mesh;
    double width_m = 0.0, height_m = 0.0;
    /// Source materials of the mesh on which nothing grew (patina --keep-off): exported with
    /// their own base colour and base colour texture, the same at every age.
    std::vector<std::string> keep_off;
};

/// The maps of a rough dielectric with the base colour `base` (linear Rec.709, 3 floats per
/// texel, one UDIM tile 1001): roughness 1, metallic 0, no coat, a flat normal, no height.
/// What a Lambertian surface (spectral_km) or a false-colour picture exports as.
FlattenedStack rough_dielectric(int width, int height, std::vector<float> base,
                                const std::string& description);

/// Fills in `options`' defaults (bits) and refuses an unknown preset, bits the preset does
/// not take, or an output whose extension does not fit it, naming the option.
void check_export_options(ExportOptions& options, const std::filesystem::path& output);

/// Makes `count` steps in parallel, `make(k, step)` filling step k (and calling
/// encode_step), after a check for cancellation. The first failure in step order is
/// thrown, whatever the threads' order, so the message does not depend on the run.
std::vector<ExportStep> make_steps(size_t count,
                                   const std::function<void(size_t, ExportStep&)>& make);

/// Checks `step`'s maps (finite, UDIM tiles up to 1099) and, for the gltf preset, encodes
/// its PNGs and drops the maps. Thread-safe for distinct steps.
void encode_step(ExportStep& step, const ExportOptions& options, const ColorManager& colors);

/// Writes the steps (encoded by encode_step) to `output`: a glTF asset, or a folder of
/// textures for the texture presets. Throws, naming `input`, for steps of different sizes
/// or tiles; every file is written under a temporary name and renamed.
ExportResult write_export(std::vector<ExportStep>& steps, const ExportGeometry& geometry,
                          const std::filesystem::path& input,
                          const std::filesystem::path& output, const ExportOptions& options,
                          const ColorManager& colors);

}  // namespace patina::texgen
