// Option values the fading commands share (`fade`, `forecast`).
#pragma once

#include "texgen/fade/fade_material.h"
#include "texgen/fade/spectral_grid.h"
#include "texgen/forecast/lighting_policy.h"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace patina::texgen {

/// "7d", "6h", "30y", "90min", "3600s" or a bare number of seconds ("" = 0). Throws
/// std::runtime_error naming `what` (the option) for anything else.
double parse_duration(const std::string& text, const std::string& what = "--duration");

/// "FIRST:LAST:STEP" in nm -> the solver's grid. Throws std::runtime_error naming
/// --wavelengths for anything else or a grid over the limit.
fade::WavelengthGrid parse_grid(const std::string& text);

/// The fading material of `forecast` and `restore`: a library material (with a rate set), or
/// an ISO Blue Wool category (shaders/fade/blue_wool.toml).
struct FadeMaterialChoice {
    std::string material, rates;
    int blue_wool = 0;
    std::vector<std::filesystem::path> materials;  ///< more library files
};

/// --material, --rates, --blue-wool, --materials.
void add_material_options(CLI::App* cmd, FadeMaterialChoice& choice);

/// The chosen material from the library ($PATINA_SHADER_PATH and the shipped files, then
/// `materials`). Throws std::runtime_error naming the option for none or both of --material
/// and --blue-wool, a category outside 1-8, --rates with --blue-wool, an unknown name.
fade::FadeMaterial load_material(const FadeMaterialChoice& choice);

/// One lighting policy from options (forecast, restore): a lamp, its lux, hours and days,
/// a UV filter and a name.
struct LampPolicyChoice {
    std::string name, lamp, uv_filter;
    std::optional<double> lux;
    double hours_per_day = 8.0, days_per_year = 365.0;
};

/// --lamp, --lux, --hours-per-day, --days-per-year, --uv-filter, --name; `lamp_note` ends
/// --lamp's help (what else it means to the command).
void add_lamp_policy_options(CLI::App* cmd, LampPolicyChoice& choice, const std::string& lamp_note);

/// The policy the options describe (lamp D65 when none is named), named by --name or by its
/// lamp, lux and filter. Throws std::runtime_error naming the option for a missing --lux, a
/// negative or non-finite lux, an unknown lamp or filter.
forecast::LightingPolicy lamp_policy(const LampPolicyChoice& choice);

}  // namespace patina::texgen
