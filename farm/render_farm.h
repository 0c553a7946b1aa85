// A render job's life on a farm (docs/farm.md): its folder written by `submit` (job.toml,
// the Slurm scripts, the OpenJD template and the plain shell loop), its tasks run by
// `patina-farm task` on the nodes, and its frames merged by `patina-farm finish`.
#pragma once

#include "farm/job_folder.h"
#include "farm/render_job.h"

#include <filesystem>
#include <string>
#include <vector>

namespace patina::farm {

/// Writes `job`'s folder (job.toml, slurm_task.sh, slurm_merge.sh, run_local.sh,
/// job.openjd.yaml, parts/, frames/, logs/) and submits it: the tasks as one job array,
/// the merge as a job that runs after all of them succeeded (afterok). Throws
/// std::runtime_error naming the folder or sbatch's failure.
Submitted submit_render_job(const RenderJob& job, const SubmitOptions& options);

/// The job's shape for the scripts and Slurm: an array of its tasks.
JobShape render_job_shape(const RenderJob& job);

/// Task `index` of the job in `folder`: nothing when its output is already a valid part of
/// the task (a requeued or repeated task is idempotent), else patina-render with the task's
/// arguments. Returns the exit status.
int run_render_task(const std::filesystem::path& folder, int index);

/// "done" when `part` is a complete output of `task`: its header names the task's scene
/// (hash), sample range (or the job's spp) and the job's plugins, it holds the task's band
/// of the frame, and its pixels read whole (a file cut short after its header is not);
/// "broken" when the file is there but is not that; "missing" when there is none.
std::string part_state(const RenderJob& job, const RenderTask& task,
                       const std::filesystem::path& part);
inline bool valid_part(const RenderJob& job, const RenderTask& task,
                       const std::filesystem::path& part)
{
    return part_state(job, task, part) == "done";
}

/// The plugin set (render/plugin_setup.h scene_plugin_set) `scene` renders with here: the
/// plugins patina-render would load (bundled, $PATINA_PLUGIN_PATH, the scene's trusted
/// [plugins] path), those of its shaders.
std::string plugin_set_of(const std::filesystem::path& scene);

/// Merges every frame of the job in `folder` from its parts, after checking that each was
/// rendered with the job's plugins (naming the part and both sets otherwise).
void finish_render_job(const std::filesystem::path& folder);

/// The status of the job in `folder`, from its parts, its frames and (when it was
/// submitted) Slurm's queue.
JobStatus render_job_status(const std::filesystem::path& folder);

/// Submits again what is left of the job in `folder`: its missing tasks as a job array
/// and a merge after them (or the merge alone when only it is missing). Refuses while any
/// of its tasks or merges is still queued. Returns the new ids (empty when the job is
/// complete: nothing is submitted).
Submitted resubmit_render_job(const std::filesystem::path& folder, const SubmitOptions& options);

}  // namespace patina::farm
