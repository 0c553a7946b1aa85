// Private declarations shared by the sources of the "slab_volume" plugin: one descriptor
// function per shader (called once from patina_plugin_entry) and small helpers for create.
#pragma once

#include <patina/abi.h>
#include <patina/plugin_support.h>

namespace patina::slab_volume {

PatinaShaderDesc slab_volume_shader();
PatinaShaderDesc stone_surface_shader();

using plugin::describe;
using plugin::make_instance;
using plugin::report_error;

} // namespace patina::slab_volume
