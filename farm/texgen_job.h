// A texgen series as a farm job: the steps of `patina-texgen patina --times` (one task per
// time, all at once: a job array), the stacks of `patina-texgen fade` for a list of
// durations or doses (a job array too), or the segments of a `patina-texgen stone --steps` run
// between its snapshots (one task per segment, each resuming the last one's checkpoint: a
// chain). Written to and read from the job folder's job.toml, kind "texgen" (docs/farm.md
// "Texgen series"), the one reader and writer of that kind.
#pragma once

#include "farm/job_folder.h"

#include <filesystem>
#include <string>
#include <vector>

namespace patina::farm {

struct TexgenTask {
    std::string label;                          ///< "t = 12 y", "cycles 0-4"
    std::vector<std::string> args;              ///< patina-texgen's arguments
    std::vector<std::filesystem::path> outputs; ///< the folders and files it writes (absolute)
    double time_years = 0.0;                    ///< a patina step's time
    std::string folder;                         ///< a patina or fade step's folder in the series
};

struct TexgenJob {
    std::filesystem::path folder;          ///< the job folder (absolute)
    std::string command;                   ///< "patina", "fade" or "stone"
    std::filesystem::path texgen, farm;    ///< the programs' absolute paths, as submitted
    std::filesystem::path cwd;             ///< where relative paths of `args` are from
    std::filesystem::path output;          ///< the series' folder (absolute)
    bool chained = false;                  ///< task i resumes task i - 1 (stone)
    /// Keep a chain's checkpoints after the finishing job (submit-texgen
    /// --keep-checkpoints); else it removes them once every step is written.
    bool keep_checkpoints = false;
    std::vector<TexgenTask> tasks;
};

/// The tasks of `args` (a patina-texgen command line without the program: "patina SCRIPT
/// --times ...", "fade ... --duration 0h,1d,7d -o OUT" or "stone --mesh ... --steps N") as
/// `texgen ARGS --plan` prints them (formats/texgen_plan/texgen_plan.h): patina-texgen plans its own
/// series. Throws std::invalid_argument with its message for what is missing or not
/// allowed (a patina run without --times, a fade run without a list, a stone run without
/// --steps or with the options the farm sets: --until, --resume, --checkpoint).
TexgenJob plan_texgen_job(const std::filesystem::path& folder, const std::vector<std::string>& args,
                          const std::filesystem::path& texgen, const std::filesystem::path& farm);

/// The job's shape for the scripts and Slurm.
JobShape texgen_job_shape(const TexgenJob& job);

/// job.toml's text, and the job read back from `folder`/job.toml (throws naming the file).
std::string texgen_job_text(const TexgenJob& job);
TexgenJob read_texgen_job(const std::filesystem::path& folder);

/// The kind of the job in `folder` ("render" or "texgen"); throws naming job.toml when it
/// has none.
std::string job_kind(const std::filesystem::path& folder);

}  // namespace patina::farm
