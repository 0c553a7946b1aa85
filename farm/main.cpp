// patina-farm: Patina's renders, bakes and simulations on a render farm (docs/farm.md).
#include "farm/frame_merge.h"
#include "farm/render_farm.h"
#include "farm/texgen_farm.h"

#include "core/cancel.h"
#include "core/cli_errors.h"
#include "core/manual_page.h"
#include "core/progress.h"

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <memory>
#include <stdexcept>
#include <vector>

namespace {

namespace fs = std::filesystem;

struct MergeOptions {
    std::vector<fs::path> parts;
    fs::path output;
    bool quiet = false;
};

void register_merge(CLI::App& app)
{
    auto o = std::make_shared<MergeOptions>();
    CLI::App* cmd = app.add_subcommand(
        "merge", "merge the parts of a frame a farm rendered — tiles or crops, and sample "
                 "ranges (--samples) — into one EXR, checking that they belong together");
    cmd->add_option("parts", o->parts, "the parts: EXRs written by patina-render")
        ->required()
        ->check(CLI::ExistingFile);
    cmd->add_option("-o,--out", o->output, "the merged EXR")->required();
    cmd->add_flag("-q,--quiet", o->quiet, "no summary line");
    cmd->callback([o] {
        const patina::farm::MergeResult r = patina::farm::merge_render_parts(o->parts, o->output);
        if (!o->quiet)
            std::fprintf(stderr, "merge: %zu part(s), samples %d-%d, pixels [%d, %d) x [%d, %d) "
                                 "-> %s\n",
                         r.parts, r.sample_begin, r.sample_end, r.x, r.x + r.width, r.y,
                         r.y + r.height, o->output.string().c_str());
    });
}

/// The options of Slurm's side of a submission (submit, submit-texgen, resubmit).
void add_submit_options(CLI::App* cmd, patina::farm::SubmitOptions& o, bool dry_run)
{
    cmd->add_option("--throttle", o.throttle, "at most this many tasks at once (sbatch --array %N)");
    cmd->add_option("--partition", o.partition, "the Slurm partition");
    cmd->add_option("--cpus-per-task", o.cpus_per_task, "CPUs per task (sbatch --cpus-per-task)")
        ->check(CLI::PositiveNumber);
    if (dry_run)
        cmd->add_flag("--dry-run", o.dry_run, "write the job folder, submit nothing");
}

struct SubmitCommand {
    patina::farm::RenderJobOptions job;
    patina::farm::SubmitOptions submit;
};

void register_submit(CLI::App& app)
{
    auto o = std::make_shared<SubmitCommand>();
    CLI::App* cmd = app.add_subcommand(
        "submit", "submit a render to Slurm as a job array (a task per frame, tile and sample "
                  "range) and a merge job that runs after it; writes the job folder (job.toml, "
                  "the scripts, an OpenJD template, a plain shell loop)");
    cmd->add_option("scene", o->job.scene, "the scene; with --frames, a run of '#' in its name "
                                           "is the frame number")
        ->required();
    cmd->add_option("--job", o->job.folder, "the job folder to write")->required();
    cmd->add_option("--frames", o->job.frames, "A-B: the frames to render");
    cmd->add_option("--tiles", o->job.tiles, "bands of rows per frame, a task each")
        ->capture_default_str();
    cmd->add_option("--sample-splits", o->job.sample_splits,
                    "sample ranges per pixel, a task each (needs --spp)")
        ->capture_default_str();
    cmd->add_option("--spp", o->job.spp, "samples per pixel (default: the scene's)");
    add_submit_options(cmd, o->submit, true);
    cmd->callback([o] {
        // The programs the nodes run: this one and patina-render beside it.
        const fs::path self = fs::read_symlink("/proc/self/exe");
        const fs::path render = self.parent_path() / "patina-render";
        patina::farm::RenderJob job = patina::farm::plan_render_job(o->job, render, self);
        job.plugins = patina::farm::plugin_set_of(job.tasks.front().scene);
        const patina::farm::Submitted s = patina::farm::submit_render_job(job, o->submit);
        if (o->submit.dry_run)
            std::printf("wrote %s (%zu tasks, %zu frame(s)); not submitted\n",
                        job.folder.string().c_str(), job.tasks.size(), job.merges.size());
        else
            std::printf("%s %s\n", s.array_job.c_str(), s.merge_job.c_str());
    });
}

struct SubmitTexgenCommand {
    fs::path folder;
    std::vector<std::string> args;
    patina::farm::SubmitOptions submit;
    bool keep_checkpoints = false;
};

void register_submit_texgen(CLI::App& app)
{
    auto o = std::make_shared<SubmitTexgenCommand>();
    CLI::App* cmd = app.add_subcommand(
        "submit-texgen",
        "submit a texgen series to Slurm: the steps of `patina-texgen patina --times` as a job "
        "array, or the segments of `patina-texgen stone --steps` between its snapshots as a "
        "chain of jobs each resuming the last one's checkpoint; then a finishing job");
    cmd->add_option("--job", o->folder, "the job folder to write")->required();
    add_submit_options(cmd, o->submit, true);
    cmd->add_flag("--keep-checkpoints", o->keep_checkpoints,
                  "stone: keep the chain's checkpoints after the finishing job (by default it "
                  "removes them once every step is written)");
    cmd->add_option("command", o->args,
                    "after '--': the patina-texgen command line, e.g. -- patina urban.patina "
                    "--times 0,6,12 -o urban")
        ->required();
    cmd->callback([o] {
        const fs::path self = fs::read_symlink("/proc/self/exe");
        patina::farm::TexgenJob job = patina::farm::plan_texgen_job(
            o->folder, o->args, self.parent_path() / "patina-texgen", self);
        job.keep_checkpoints = o->keep_checkpoints;
        const patina::farm::Submitted s = patina::farm::submit_texgen_job(job, o->submit);
        if (o->submit.dry_run)
            std::printf("wrote %s (%zu tasks); not submitted\n", job.folder.string().c_str(),
                        job.tasks.size());
        else
            std::printf("%s %s\n", s.array_job.c_str(), s.merge_job.c_str());
    });
}

void register_task(CLI::App& app)
{
    auto folder = std::make_shared<fs::path>();
    auto index = std::make_shared<int>(0);
    CLI::App* cmd = app.add_subcommand(
        "task", "run one task of a job (what a farm node runs); nothing when its output is "
                "already there and valid");
    cmd->add_option("job", *folder, "the job folder")->required()->check(CLI::ExistingDirectory);
    cmd->add_option("index", *index, "the task (SLURM_ARRAY_TASK_ID)")->required();
    cmd->callback([folder, index] {
        const bool render = patina::farm::job_kind(*folder) == "render";
        const int status = render ? patina::farm::run_render_task(*folder, *index)
                                  : patina::farm::run_texgen_task(*folder, *index);
        if (status != 0)
            throw std::runtime_error(fmt::format("task {}: {} failed (exit status {})", *index,
                                                 render ? "patina-render" : "patina-texgen",
                                                 status));
    });
}

void register_finish(CLI::App& app)
{
    auto folder = std::make_shared<fs::path>();
    CLI::App* cmd = app.add_subcommand(
        "finish", "merge every frame of a render job from its parts; write a texgen series' "
                  "manifest once every step is done");
    cmd->add_option("job", *folder, "the job folder")->required()->check(CLI::ExistingDirectory);
    cmd->callback([folder] {
        if (patina::farm::job_kind(*folder) == "render")
            patina::farm::finish_render_job(*folder);
        else
            patina::farm::finish_texgen_job(*folder);
    });
}

void register_status(CLI::App& app)
{
    auto folder = std::make_shared<fs::path>();
    CLI::App* cmd = app.add_subcommand(
        "status", "where a job stands: each task done, running, pending, broken (its output "
                  "there but cut short or not the task's) or missing, with the error line of "
                  "its log (else its last line), and the frames merged");
    cmd->add_option("job", *folder, "the job folder")->required()->check(CLI::ExistingDirectory);
    cmd->callback([folder] {
        // Each task's description, and what the finishing job writes.
        std::vector<std::string> labels;
        patina::farm::JobStatus st;
        std::string finished;
        if (patina::farm::job_kind(*folder) == "render") {
            for (const patina::farm::RenderTask& t : patina::farm::read_render_job(*folder).tasks)
                labels.push_back(fmt::format("frame {}, tile {}{}", t.frame, t.tile,
                                             t.sample_end > 0 ? fmt::format(", samples {}-{}",
                                                                            t.sample_begin,
                                                                            t.sample_end)
                                                              : ""));
            st = patina::farm::render_job_status(*folder);
            finished = fmt::format("{} of {} frame(s) merged",
                                   std::count(st.merged.begin(), st.merged.end(), true),
                                   st.merged.size());
        } else {
            for (const patina::farm::TexgenTask& t : patina::farm::read_texgen_job(*folder).tasks)
                labels.push_back(t.label);
            st = patina::farm::texgen_job_status(*folder);
            finished = st.merged.empty() ? "nothing to finish"
                       : st.merged.front() ? "the series manifest written"
                                           : "the series manifest not written";
        }
        if (!st.queue_known)
            throw std::runtime_error(fmt::format(
                "status of '{}': Slurm's queue could not be asked ({}), so which tasks are "
                "queued is not known", folder->string(), st.queue_error));
        for (size_t i = 0; i < st.tasks.size(); ++i)
            std::printf("task %zu (%s): %s%s%s\n", i, labels[i].c_str(), st.tasks[i].c_str(),
                        st.failures[i].empty() ? "" : ": ", st.failures[i].c_str());
        if (!st.merge_error.empty())
            std::printf("merge: failed: %s\n", st.merge_error.c_str());
        std::printf("%zu task(s): %zu done, %zu running, %zu pending, %zu broken, %zu missing; "
                    "%s%s%s\n",
                    st.tasks.size(), st.count("done"), st.count("running"), st.count("pending"),
                    st.count("broken"), st.count("missing"), finished.c_str(),
                    st.merge_state.empty() ? "" : "; the merge ",
                    st.merge_state == "queued" ? "is queued"
                    : st.merge_state == "held" ? "is held"
                    : st.merge_state == "waiting on a task that failed"
                        ? "is queued but can never run: a task it waits for failed"
                    : st.merge_state == "failed" ? "failed (see above)"
                    : st.merge_state.empty() ? ""
                                             : "did not run: a task it waits for failed");
    });
}

void register_resubmit(CLI::App& app)
{
    auto folder = std::make_shared<fs::path>();
    auto options = std::make_shared<patina::farm::SubmitOptions>();
    CLI::App* cmd = app.add_subcommand(
        "resubmit", "submit again the tasks of a job whose outputs are missing or invalid, and "
                    "its merge");
    cmd->add_option("job", *folder, "the job folder")->required()->check(CLI::ExistingDirectory);
    add_submit_options(cmd, *options, false);
    cmd->callback([folder, options] {
        const patina::farm::Submitted s =
            patina::farm::job_kind(*folder) == "render"
                ? patina::farm::resubmit_render_job(*folder, *options)
                : patina::farm::resubmit_texgen_job(*folder, *options);
        // Labelled, one job a line: the tasks run again (when any), then what follows them.
        if (s.merge_job.empty()) {
            std::printf("nothing to resubmit: every task is done and every frame merged\n");
            return;
        }
        if (!s.array_job.empty())
            std::printf("array job %s\n", s.array_job.c_str());
        std::printf("merge job %s\n", s.merge_job.c_str());
    });
}

}  // namespace

int main(int argc, char** argv)
{
    // First of all: a SIGINT or SIGTERM that arrives while the options are read or the
    // plugins load must cancel the run (exit 130, nothing written), not kill it untidily.
    patina::install_cancel_handler();
    CLI::App app{"patina-farm: Patina's renders, bakes and simulations on a render farm"};
    app.set_version_flag("--version", std::string("patina-farm ") + PATINA_VERSION_STRING);
    app.require_subcommand(1);
    register_submit(app);
    register_submit_texgen(app);
    register_task(app);
    register_finish(app);
    register_status(app);
    register_resubmit(app);
    register_merge(app);
    app.footer(patina::manual_footer("farm.md"));
    for (CLI::App* command : app.get_subcommands({}))
        command->footer(patina::manual_footer("farm.md"));

    patina::refuse_non_finite_numbers(app);  // NaN and infinities, for every option
    try {
        // Each file is written under a temporary name and renamed at once: a job's scripts
        // must be in place before sbatch starts them.
        app.parse(argc, argv);
        return 0;
    } catch (const CLI::ParseError& e) {
        return patina::report_parse_error(app, e, "patina-farm", argc, argv);
    } catch (const patina::Cancelled& e) {
        std::fprintf(stderr, "\npatina-farm: %s; no output was written\n", e.what());
        return 130;
    } catch (const std::exception& e) {
        patina::end_progress_line();  // the message on a line of its own
        std::fprintf(stderr, "patina-farm: error: %s\n", patina::one_line(e.what()).c_str());
        return 1;
    }
}
