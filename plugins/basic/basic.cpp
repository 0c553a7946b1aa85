// The "basic" plugin: the ABI entry points and the table of its shaders (lambert,
// conductor, dielectric, emitter, homogeneous). Each shader lives in its own source file,
// documented at its top; docs/shaders.md lists their parameters from the metadata.
#include "basic.h"

// The host keeps pointers into the table while the library is loaded; it is built on the
// first call (thread-safe), so there is no static initialisation order across files.
PATINA_PLUGIN("basic", "0.1.0", patina::basic::lambert_shader(),
              patina::basic::conductor_shader(), patina::basic::dielectric_shader(),
              patina::basic::emitter_shader(), patina::basic::homogeneous_shader())
