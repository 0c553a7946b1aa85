// Option values the fading commands share (`fade`, `forecast`).
#pragma once

#include "texgen/fade/spectral_grid.h"

#include <string>

namespace patina::texgen {

/// "7d", "6h", "30y", "90min", "3600s" or a bare number of seconds ("" = 0). Throws
/// std::runtime_error naming `what` (the option) for anything else.
double parse_duration(const std::string& text, const std::string& what = "--duration");

/// "FIRST:LAST:STEP" in nm -> the solver's grid. Throws std::runtime_error naming
/// --wavelengths for anything else or a grid over the limit.
fade::WavelengthGrid parse_grid(const std::string& text);

}  // namespace patina::texgen
