// A render job's life on a farm (docs/farm.md): its folder written by `submit` (job.toml,
// the Slurm scripts, the OpenJD template and the plain shell loop), its tasks run by
// `patina-farm task` on the nodes, and its frames merged by `patina-farm finish`.
#pragma once

#include "farm/render_job.h"

#include <filesystem>
#include <string>
#include <vector>

namespace patina::farm {

struct SubmitOptions {
    int throttle = 0;        ///< at most this many tasks at once (sbatch --array %N); 0: no cap
    std::string partition;   ///< sbatch --partition, or the default
    bool dry_run = false;    ///< write the folder, submit nothing
};

/// What `submit` wrote and, unless a dry run, the Slurm job ids.
struct Submitted {
    std::vector<std::filesystem::path> files;
    std::string array_job, merge_job;
};

/// Writes `job`'s folder (job.toml, slurm_task.sh, slurm_merge.sh, run_local.sh,
/// job.openjd.yaml, parts/, frames/, logs/) and submits it: the tasks as one job array,
/// the merge as a job that runs after all of them succeeded (afterok). Throws
/// std::runtime_error naming the folder or sbatch's failure.
Submitted submit_render_job(const RenderJob& job, const SubmitOptions& options);

/// Task `index` of the job in `folder`: nothing when its output is already a valid part of
/// the task (a requeued or repeated task is idempotent), else patina-render with the task's
/// arguments. Returns the exit status.
int run_render_task(const std::filesystem::path& folder, int index);

/// True when `part` is a complete output of `task`: its header names the task's scene
/// (hash) and sample range.
bool valid_part(const RenderTask& task, const std::filesystem::path& part);

/// Merges every frame of the job in `folder` from its parts.
void finish_render_job(const std::filesystem::path& folder);

}  // namespace patina::farm
