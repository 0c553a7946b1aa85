// `patina-texgen export` of a per-texel forecast (`patina-texgen forecast --exposure`, the
// texture-stack map fade_forecast): the object's mesh with two material variants, the years
// to the threshold and the ΔE00 after N years in false colour (texgen/forecast/years_map.h),
// so a curator sees in any glTF viewer, or `patina-texgen view`, where the object fades first.
#pragma once

#include "core/color_management.h"
#include "texgen/export/export_patina.h"

#include <filesystem>

namespace patina::texgen {

/// True when `input` (a folder or its stack.toml) holds a fade_forecast map.
bool is_forecast_folder(const std::filesystem::path& input);

/// Exports the forecast folder `input` to `output`. The geometry is `options.mesh`, else the
/// mesh the forecast's exposure map was baked on (its stack.toml records it). Throws
/// std::runtime_error naming the file or option for a missing channel, a mesh that is not
/// found, or --resolution (the map exports at its own).
ExportResult export_forecast(const std::filesystem::path& input,
                             const std::filesystem::path& output, const ExportOptions& options,
                             const ColorManager& colors);

}  // namespace patina::texgen
