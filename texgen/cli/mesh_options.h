// The options every command that reads a mesh shares: the file's up axis and unit (--up,
// --unit, --scale); texgen/meshes/mesh_input.h loads and records them.
#pragma once

#include "core/mesh_convention.h"

#include <CLI/CLI.hpp>

namespace patina::texgen {

/// Add --up, --unit, --scale (--unit and --scale exclude each other) and --uv-set to
/// `command`.
void add_mesh_convention_options(CLI::App& command, MeshConventionOptions& options);

} // namespace patina::texgen
