// `patina-texgen export` of fade stacks (`patina-texgen fade`, formats/fade_stack/fade_stack.h): each
// stack's reflectance over its substrate (R_total of the dose table, looked up at every
// texel's dose as spectral_km looks it up) seen under D65 and converted by OCIO to linear
// Rec.709, as the base colour of a dielectric with roughness 1 (spectral_km is Lambertian);
// several stacks in order of age make a series, one variant per stack. The maps go through
// the writers every export shares (export_asset.h): glTF or the texture presets.
#pragma once

#include "core/color_management.h"
#include "texgen/export/export_patina.h"

#include <filesystem>
#include <vector>

namespace patina::texgen {

/// The mesh an exposure map was baked on and the up axis and unit it was read with, as the
/// stack.toml beside the map records them (an empty file when it records none).
struct BakedMesh {
    std::filesystem::path file;
    MeshConventionOptions convention;
    bool uv_wrap = false;  ///< its uvs outside the UDIM tiles were folded (texels/uv_wrap.h)
};
BakedMesh mesh_of_exposure_map(const std::filesystem::path& map);

/// True when `input` is a fade stack: a fade.toml, or a folder holding one.
bool is_fade_stack(const std::filesystem::path& input);

/// Exports the fade stacks `inputs` (in order of age; one stack, or a series) to `output`.
/// The geometry is `options.mesh`, else the mesh the stacks' exposure maps were baked on
/// (their stack.toml records it), else — for uniform doses — a square swatch of 10 cm.
/// Throws std::runtime_error naming the file or option for: a malformed stack or table,
/// stacks not in order of age, dose maps of different sizes, --resolution (a fade stack
/// exports at its dose map's resolution), a mesh that is not found or not on one UDIM tile.
ExportResult export_fade(const std::vector<std::filesystem::path>& inputs,
                         const std::filesystem::path& output, const ExportOptions& options,
                         const ColorManager& colors);

/// "0 d", "1 d", "2.5 d": an age in seconds named in `unit_s`'s unit (3600 h, 86400 d,
/// 365 d y), the unit of the series' oldest step.
std::string fade_age_name(double seconds, double unit_s);

}  // namespace patina::texgen
