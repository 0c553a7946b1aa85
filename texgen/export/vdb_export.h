// `patina-texgen export` of stone volumes as OpenVDB (the sparse volume format Blender,
// Houdini and the production renderers read): one file per time step, frame-numbered, with
// world-space fog-volume grids named as renderers expect them — `density` (the extinction
// coefficient, 1/m), `color` (the single-scattering albedo, linear Rec.709) — and the
// simulation's own fields `crust`, `iron` and `salt` (fractions), `moisture` and `decay`
// (when the volume holds them). docs/export.md.
#pragma once

#include "core/color_management.h"

#include <filesystem>
#include <vector>

namespace patina::texgen {

struct VdbOptions {
    /// Extinction of solid stone (1/m) and the albedos of stone, crust, iron oxide and salt
    /// in the working space: the slab_volume medium's defaults, so that a renderer sees what
    /// patina-render's default stone shows.
    double sigma_t = 200.0;
    float albedo[4][3] = {{0.93f, 0.90f, 0.84f},
                          {0.06f, 0.05f, 0.05f},
                          {0.80f, 0.55f, 0.25f},
                          {0.97f, 0.97f, 0.96f}};
    /// The crust, iron and salt fractions that count as full cover (×).
    float gain[3] = {1.0f, 1.0f, 1.0f};
};

/// The VdbOptions of the slab_volume medium called `name` (empty: the scene's first
/// slab_volume) in the patina-render scene `scene`: its sigma_t, albedos (`[r, g, b]` in
/// the working space, a grey number, or `{ rgb = [...], colorspace = "..." }`) and gains;
/// the parameters it leaves out keep the medium's defaults. Throws std::runtime_error
/// naming the file (and line) for a scene without such a medium or a malformed value.
VdbOptions read_medium_options(const std::filesystem::path& scene, const std::string& name,
                               const ColorManager& colors);

/// The stone volumes of `input` (a `patina-texgen stone` output folder holding volume.exr,
/// or one holding cycle_NNNN step folders) as `output` (e.g. column.vdb): with steps, one
/// file per step, `<stem>.<frame>.vdb` with frame = the step's cycle (Blender's and
/// Houdini's sequence naming); else `output` itself. Where the step holds the run's
/// boundary mesh (eroded.obj), it is copied beside its volume as `<stem>[.<frame>].obj`.
/// Each file is written under a temporary name and renamed. Returns the files written (a
/// step's .vdb, then its .obj). Throws std::runtime_error naming the folder when it holds
/// no volume.
std::vector<std::filesystem::path> export_stone_vdb(const std::filesystem::path& input,
                                                    const std::filesystem::path& output,
                                                    const VdbOptions& options,
                                                    const ColorManager& colors);

}  // namespace patina::texgen
