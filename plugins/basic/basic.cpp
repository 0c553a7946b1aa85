// The "basic" plugin: the ABI entry points and the table of its shaders (lambert,
// conductor, dielectric, emitter, homogeneous). Each shader lives in its own source file,
// documented at its top; README.md lists their parameters with the same text as the metadata.
#include "basic.h"

extern "C" {

PATINA_PLUGIN_DEFINE_VERSION;

PATINA_PLUGIN_EXPORT const PatinaPluginInfo* patina_plugin_entry(const PatinaHost* host);

} // extern "C"

const PatinaPluginInfo* patina_plugin_entry(const PatinaHost* /*host*/)
{
    // Static storage: the host keeps pointers into the table while the library is loaded.
    // Built on first call (thread-safe), so no static initialisation order across files.
    static const PatinaShaderDesc shaders[] = {
        patina::basic::lambert_shader(),
        patina::basic::conductor_shader(),
        patina::basic::dielectric_shader(),
        patina::basic::emitter_shader(),
        patina::basic::homogeneous_shader(),
    };
    static const PatinaPluginInfo info = {
        "basic", "0.1.0", static_cast<int>(sizeof shaders / sizeof shaders[0]), shaders};
    return &info;
}
