// The sub-commands of patina-texgen; each adds itself to the application, with its options
// and a callback that does the work (errors are exceptions, reported by main).
#pragma once

#include <CLI/CLI.hpp>

namespace patina::texgen {

void register_mesh_command(CLI::App& app);
void register_uv_check_command(CLI::App& app);
void register_unwrap_command(CLI::App& app);
void register_ao_command(CLI::App& app);
void register_accessibility_command(CLI::App& app);
void register_sun_command(CLI::App& app);
void register_sky_command(CLI::App& app);
void register_exposure_command(CLI::App& app);
void register_wetness_command(CLI::App& app);
void register_deposit_command(CLI::App& app);
void register_patina_command(CLI::App& app);
void register_stone_command(CLI::App& app);
void register_flatten_command(CLI::App& app);
void register_fade_command(CLI::App& app);
void register_forecast_command(CLI::App& app);
void register_restore_command(CLI::App& app);
void register_export_command(CLI::App& app);
void register_view_command(CLI::App& app);

}  // namespace patina::texgen
