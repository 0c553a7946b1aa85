// The lighting-policy file of `patina-texgen forecast` (docs/forecast.md): one [[policy]]
// table per way of showing an object. The one reader of it.
//
//   [[policy]]
//   name = "LED 3000 K, 50 lx"
//   lamp = "LED-B2"              # a CIE lamp, or "spd.csv:COLUMN" (relative to this file)
//   lux = 50                     # at the object
//   hours_per_day = 8            # default 8
//   days_per_year = 365          # default 365
//   uv_filter = 400              # cut-off nm, "none" (default), or "filter.csv:COLUMN"
//
//   [[policy]]
//   name = "north window"
//   daylight = { epw = "site.epw", facing = "north", share = 0.1 }   # lamp D65, glazing
//                                # window_glass unless uv_filter says otherwise
//   [[policy]]
//   name = "as baked"
//   exposure = { map = "exposure.exr", scale = 0.58 }   # the map's mean texel
#pragma once

#include "texgen/forecast/lighting_policy.h"

#include <filesystem>
#include <vector>

namespace patina::texgen::forecast {

/// The file's policies, in order. Throws std::runtime_error "file:line:column: key: what"
/// for a TOML error, an unknown key, a missing or negative value, an unknown lamp, a lamp or
/// filter file that cannot be read, or a duplicate name.
std::vector<LightingPolicy> read_policy_file(const std::filesystem::path& file);

/// The glazing a daylight policy looks through unless it names a filter: data/filters/
/// window_glass.csv.
UvFilter window_glass();

}  // namespace patina::texgen::forecast
