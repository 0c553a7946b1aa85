// Running a patina script (Dorsey & Hanrahan 1996 §3): the statements applied in order to a
// layer stack over a domain (a flat strip or a mesh's texels), with thickness maps grown by
// the models of §3.3, baked maps and curves of time, at every time step of a series.
//
// Time. A script describes the surface at the end of the series, time T (years; the
// largest of the times asked for, 30 for the paper's strips): a texture(MODEL RATE STEP
// TOTAL) is the model grown to STEP of its TOTAL steps, normalised so that its largest
// value there is 1 (the coat's thickness is the layer's maximum, §3.2). At an earlier time t the same
// simulation is read at STEP * t / T, so a series starts from bare metal (t = 0) and shows
// the same patches growing; `t` and curves in expressions give any other dependence on time.
#pragma once

#include "texgen/patina/layer_stack.h"
#include "texgen/patina/material_library.h"
#include "texgen/patina/patina_domain.h"
#include "texgen/patina/script_ast.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace patina {
class Progress;
}

namespace patina::texgen {

struct InterpreterOptions {
    std::vector<double> times_years{30.0};  ///< the steps to compute, ascending
    double end_time_years = 0;              ///< T; 0: the last of times_years
    uint64_t seed = 1;
    /// Relative `map` paths are resolved against it (the script's folder).
    std::filesystem::path script_dir;
    /// OCIO config for reading baked maps (empty: the default).
    std::filesystem::path ocio_config;
    /// Voxels along the longest side of the mesh for `offset ... closing` on a mesh.
    int offset_voxels = 256;
    Progress* progress = nullptr;  ///< stepped once per grown map and per step
};

/// One layer of a result: its material, the statement that made it and its thickness per
/// domain node (µm).
struct ResultLayer {
    const PatinaMaterial* material = nullptr;
    std::string made_by;  ///< e.g. "coat at urban.patina:6:1"
    std::vector<float> thickness_um;
};

/// The stack at one time step.
struct PatinaStep {
    double time_years = 0;
    const PatinaMaterial* base = nullptr;
    std::vector<ResultLayer> layers;    ///< bottom to top
    std::vector<float> total_um;        ///< total thickness over the base, per node
};

/// Run `script` over `domain` at every time of `options`. Errors found while running (a
/// statement before `new`, a map that is missing or NaN, an unknown texture parameter) are
/// ScriptError at the statement's line and column; other failures std::runtime_error.
std::vector<PatinaStep> run_patina_script(const Script& script, const MaterialLibrary& library,
                                          const PatinaDomain& domain,
                                          const InterpreterOptions& options);

/// The number of grown maps and steps run_patina_script steps its progress by.
size_t patina_work_units(const Script& script, const InterpreterOptions& options);

}  // namespace patina::texgen
