// The "slab_volume" plugin: the ABI entry points and the table of its shaders — the
// weathered-stone medium `slab_volume` and its boundary `stone_surface` (Dorsey et al. 1999
// §5). Each shader lives in its own source file, documented at its top; docs/shaders.md
// lists their parameters from the metadata.
#include "slab_volume.h"

PATINA_PLUGIN("slab_volume", "0.1.0", patina::slab_volume::slab_volume_shader(),
              patina::slab_volume::stone_surface_shader())
