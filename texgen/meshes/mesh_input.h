// A mesh a user brings, loaded in Patina's world with the convention its file declares or
// the options give (core/mesh_convention.h), with warnings a user should see; and how a
// stack records that convention so that every later step (patina, export, render) agrees.
#pragma once

#include "core/image_io.h"
#include "core/mesh.h"
#include "core/mesh_convention.h"

#include <toml++/toml.h>

#include <filesystem>
#include <string>

namespace patina::texgen {

/// load_merged_mesh(file, convention), printing on stderr what a user should know: an option
/// that contradicts the file, a size that suggests a wrong unit (implausible_size_warning).
/// `applied`, when given, receives the convention used.
TriangleMesh load_mesh_with_warnings(const std::filesystem::path& file,
                                     const MeshConventionOptions& convention,
                                     MeshConvention* applied = nullptr);

/// The map parameters that record the convention a bake or a growth applied
/// (`mesh_up = "+z"`, `mesh_metres_per_unit = 0.01`), after the mesh's path.
void record_convention(Metadata& parameters, const MeshConvention& applied);

/// Record the uv set baked into (`uv_set`, when not the first).
void record_uv_set(Metadata& parameters, int uv_set);

/// Record that the mesh's uvs outside the UDIM tiles were folded into tile 1001
/// (`uv_wrap = 1`; texels/uv_wrap.h), and read it back.
void record_uv_wrap(Metadata& parameters);
bool recorded_uv_wrap(const toml::table& parameters);

/// The convention recorded in a stack map's `parameters` (record_convention), as options that
/// reproduce it; empty options when nothing is recorded.
MeshConventionOptions recorded_convention(const toml::table& parameters);

/// The options to load a stack's mesh with: the user's where given, else what the stack
/// recorded. Throws naming `what` (the stack) when the user's disagree with the recorded
/// ones: the maps were baked on the mesh placed otherwise.
MeshConventionOptions convention_for_stack(const MeshConventionOptions& user,
                                           const MeshConventionOptions& recorded,
                                           const std::string& what);

} // namespace patina::texgen
