// A texgen series' life on a farm (docs/farm.md "Texgen series"): its folder written by
// `submit-texgen`, its tasks run by `patina-farm task` (patina-texgen with the task's
// arguments), each leaving a record of what it read and wrote, and the series finished by
// `patina-farm finish` (a patina series' series.toml).
#pragma once

#include "farm/job_folder.h"
#include "farm/texgen_job.h"

#include <filesystem>

namespace patina::farm {

/// Writes the job's folder (job.toml, the scripts, logs/, done/, checkpoints/) and, unless
/// a dry run, submits it: an array (patina) or a chain (stone) and the finishing job.
Submitted submit_texgen_job(const TexgenJob& job, const SubmitOptions& options);

/// True when task `index` is done: its record (done/task_<index>.toml) names the task's
/// command and the same fingerprints of its input files (the arguments that name files) and
/// of every file it wrote, as they are now.
bool texgen_task_done(const TexgenJob& job, size_t index);

/// Task `index` of the job in `folder`: nothing when it is done, else patina-texgen with
/// its arguments (from the job's cwd), then its record. Returns the exit status.
int run_texgen_task(const std::filesystem::path& folder, int index);

/// Finishes the series in `folder` after checking that every task is done (naming those
/// that are not): a patina series gets its series.toml, as the one-process run writes it.
void finish_texgen_job(const std::filesystem::path& folder);

JobStatus texgen_job_status(const std::filesystem::path& folder);
Submitted resubmit_texgen_job(const std::filesystem::path& folder, const SubmitOptions& options);

}  // namespace patina::farm
