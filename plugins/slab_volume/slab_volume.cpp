// The "slab_volume" plugin: the ABI entry points and the table of its shaders — the
// weathered-stone medium `slab_volume` and its boundary `stone_surface` (Dorsey et al. 1999
// §5). Each shader lives in its own source file, documented at its top; README.md lists
// their parameters with the same text as the metadata.
#include "slab_volume.h"

extern "C" {

PATINA_PLUGIN_DEFINE_VERSION;

PATINA_PLUGIN_EXPORT const PatinaPluginInfo* patina_plugin_entry(const PatinaHost* host);

} // extern "C"

const PatinaPluginInfo* patina_plugin_entry(const PatinaHost* /*host*/)
{
    // Static storage: the host keeps pointers into the table while the library is loaded
    static const PatinaShaderDesc shaders[] = {
        patina::slab_volume::slab_volume_shader(),
        patina::slab_volume::stone_surface_shader(),
    };
    static const PatinaPluginInfo info = {
        "slab_volume", "0.1.0", static_cast<int>(sizeof shaders / sizeof shaders[0]), shaders};
    return &info;
}
