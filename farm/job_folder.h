// What every farm job's folder has, whatever its tasks run (a render's parts, a texgen
// series' steps, a stone run's segments): the scripts (Slurm, OpenJD, a shell loop), the
// submission to Slurm (a job array, or a chain of jobs that each wait for the one before,
// then a finishing job), the ids in submitted.toml, and where the tasks stand in the queue.
// docs/farm.md "The job folder".
#pragma once

#include <toml++/toml.h>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace patina::farm {

/// The shape of a job, as the scripts and Slurm see it.
struct JobShape {
    std::filesystem::path folder;  ///< absolute
    std::filesystem::path farm;    ///< the patina-farm the nodes run (absolute)
    std::string title;             ///< e.g. "render shot", "patina series urban"
    size_t tasks = 0;
    /// Task i needs task i - 1's output (a stone run's segments): a chain of jobs, each
    /// after the one before (afterok), instead of an array.
    bool chained = false;
};

struct SubmitOptions {
    int throttle = 0;        ///< at most this many tasks at once (sbatch --array %N); 0: no cap
    std::string partition;   ///< sbatch --partition, or the default
    int cpus_per_task = 0;   ///< sbatch --cpus-per-task for the tasks; 0: the cluster's default
    bool dry_run = false;    ///< write the folder, submit nothing
};

/// What `submit` wrote and, unless a dry run, the Slurm job ids.
struct Submitted {
    std::vector<std::filesystem::path> files;
    std::string array_job;  ///< the array's id; for a chain, the ids joined by ','
    std::string merge_job;
};

/// Makes the folder's logs/ and the folders `subfolders`, then writes slurm_task.sh,
/// slurm_merge.sh, run_local.sh and job.openjd.yaml (each whole at once: the jobs may start
/// as soon as sbatch has them). Returns the files written.
std::vector<std::filesystem::path> write_job_scripts(const JobShape& job,
                                                     const std::vector<std::string>& subfolders);

/// Writes the scripts and `subfolders` (write_job_scripts), then job.toml (`job_toml`),
/// then, unless a dry run, submits every task and the finishing job (submit_job).
Submitted write_and_submit_job(const JobShape& job, const std::vector<std::string>& subfolders,
                               const std::string& job_toml, const SubmitOptions& options);

/// `folder`/job.toml parsed; throws std::runtime_error "file:line:column: what".
toml::table parse_job_file(const std::filesystem::path& folder);

/// Submits `tasks` (indices; none: the finishing job alone) as an array or a chain, then the
/// finishing job after them (afterok, --kill-on-invalid-dep), and appends the ids to
/// submitted.toml. Throws std::runtime_error with sbatch's failure.
Submitted submit_job(const JobShape& job, const std::vector<size_t>& tasks,
                     const SubmitOptions& options);

/// Where a job stands (docs/farm.md "status and resubmit").
struct JobStatus {
    /// per task: done, running, pending, broken (its output is there but not whole or not
    /// the task's) or missing
    std::vector<std::string> tasks;
    std::vector<std::string> failures;  ///< per task: what its log says when broken or missing
    std::vector<bool> merged;           ///< per output of the finishing job: written
    bool merge_queued = false;
    /// What became of the finishing job when its outputs are not all written: "queued",
    /// "held" (in the queue, held by a user or an administrator), "waiting on a task that
    /// failed" (in the queue, its dependency never satisfiable), "failed" (it ran: see
    /// merge_error), "not run: a task it waits for failed" (Slurm dropped it), or empty.
    std::string merge_state;
    std::string merge_error;            ///< "logs/merge.log: <its first error line>"
    bool queue_known = true;            ///< false when squeue could not be asked
    std::string queue_error;            ///< why not
    size_t count(const std::string& state) const;
};

/// The status from Slurm's queue (squeue over submitted.toml's ids), `output_state(i)`
/// ("done", "broken" or "missing") for a task not in it, its log for a task neither queued
/// nor done, and `merged`.
JobStatus job_status(const JobShape& job,
                     const std::function<std::string(size_t)>& output_state,
                     std::vector<bool> merged);

/// Submits the broken and missing tasks of `st` and the finishing job after them (or the finishing job
/// alone when only it is missing). Refuses while a task or finishing job of the job is still
/// queued. Returns empty ids when the job is complete.
Submitted resubmit_job(const JobShape& job, const JobStatus& st, const SubmitOptions& options);

/// Removes the staging folders (`.patina-staging-*`, core/output_transaction.h) a killed
/// task left directly in `folder` (a task killed with SIGKILL, or with its node, cannot
/// remove its own). Called by the finishing job, after every task of the job has ended, on
/// the folders only the job writes. Returns how many it removed.
size_t remove_staging_leftovers(const std::filesystem::path& folder);

}  // namespace patina::farm
