// `patina-texgen stone` as a library call: build the slab shell of a mesh, fill it from the
// quarry, run wet/dry cycles driven by a wetness map, and write the volumes, the eroded mesh
// and the surface maps (one folder per snapshot of a time series).
#pragma once

#include "texgen/stone/quarry.h"
#include "texgen/stone/stone_state.h"

#include <filesystem>
#include "core/mesh_convention.h"

#include <optional>
#include <string>
#include <vector>

namespace patina::texgen::stone {

struct StoneJobOptions {
    std::filesystem::path mesh;         ///< the closed stone mesh (world space, metres)
    std::filesystem::path slab_mesh;    ///< coarser base for the slabs (empty: `mesh`)
    MeshConventionOptions convention;   ///< --up, --unit, --scale of both meshes
    std::filesystem::path out_dir = "stone";
    QuarryOptions quarry;
    StoneParameters params;
    double depth = 0.0;                 ///< shell depth (m); 0: 15% of the largest extent
    int tangential_res = 16;
    int depth_res = 16;
    int cycles = 100;
    int snapshots = 0;                  ///< 0: the final state only, in out_dir itself
    // Wetness: a texgen wetness map, else rain from a direction, else a constant.
    std::filesystem::path wetness_map;
    std::optional<Imath::V3d> rain_direction;  ///< wetness = max(0, -N . dir) (normalised)
    float wetness_value = 1.0f;
    std::filesystem::path deposit_map;
    float deposit_value = 0.0f;
    int grid_resolution = 128;          ///< world grid voxels along the longest side
    int map_resolution = 512;           ///< surface maps (0: none; needs uvs)
    bool write_mesh = true;
    bool quiet = false;
    // Checkpoints (stone_checkpoint.h): a run continued from one is bitwise the run that
    // was never stopped.
    std::filesystem::path checkpoint;   ///< where to write them (empty: none)
    int checkpoint_every = 0;           ///< cycles between them (0: only at the stop)
    std::filesystem::path resume;       ///< continue from this checkpoint
    int until = -1;                     ///< stop after this cycle (< 0: --cycles)
};

/// The fingerprint of everything that decides a run's states (the meshes' and maps' bytes,
/// the quarry, the lattice, the parameters; not the cycles, snapshots or outputs): a
/// checkpoint resumes only a run with the same.
std::string stone_setup_fingerprint(const StoneJobOptions& options);

/// Run the job; progress on stderr unless quiet. Throws std::runtime_error naming the input
/// or option at fault.
void run_stone_job(const StoneJobOptions& options);

/// The cycles a run of `cycles` cycles writes snapshots at: with `steps` > 0 the fresh stone
/// and `steps` more evenly over the run (cycles * k / steps, rounded down, each once);
/// with 0 only the end.
std::vector<int> snapshot_cycles(int cycles, int steps);

/// The snapshot folder name of cycle `c` in a series ending at `last`: "cycle_0050".
std::string snapshot_folder(int cycle, int last);

/// Write every output of the current state into `dir` (volume.exr, slabs.exr, eroded.obj,
/// maps).
void write_stone_outputs(const std::filesystem::path& dir, const StoneState& st,
                         const TriangleMesh& mesh, const StoneJobOptions& options);

} // namespace patina::texgen::stone
