// Private declarations shared by the sources of the "basic" plugin: one descriptor
// function per shader (called once from patina_plugin_entry) and small helpers for create.
#pragma once

#include <patina/abi.h>
#include <patina/plugin_support.h>

namespace patina::basic {

PatinaShaderDesc lambert_shader();
PatinaShaderDesc conductor_shader();
PatinaShaderDesc dielectric_shader();
PatinaShaderDesc emitter_shader();
PatinaShaderDesc homogeneous_shader();

/// Roughness below which a BSDF becomes a delta lobe (documented in each shader).
inline constexpr float kSmoothRoughness = 1e-3f;

using plugin::describe;
using plugin::make_instance;
using plugin::report_error;

/// The transport mode of a shading point (radiance when the host gave no context).
inline PatinaTransportMode transport_mode(const PatinaShadingContext* ctx)
{
    return ctx ? ctx->mode : PATINA_TRANSPORT_RADIANCE;
}

} // namespace patina::basic
