#include "farm/texgen_farm.h"

#include "farm/processes.h"

#include "core/file_fingerprint.h"
#include "core/image_io.h"
#include "formats/texture_stack/texture_stack.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cstdio>
#include <sstream>
#include <stdexcept>

namespace patina::farm {

namespace fs = std::filesystem;

namespace {

    fs::path record_of(const TexgenJob& job, size_t index)
    {
        return job.folder / "done" / fmt::format("task_{}.toml", index);
    }

    /// Written by the finishing job when it removed a chain's checkpoints: from then on the
    /// tasks' records leave the checkpoints out (they served the chain only).
    fs::path checkpoints_removed_marker(const TexgenJob& job)
    {
        return job.folder / "done" / "checkpoints_removed";
    }

    /// Whether the finishing job removed the chain's checkpoints (its marker is in place).
    bool checkpoints_removed(const TexgenJob& job)
    {
        std::error_code ec;
        return fs::exists(checkpoints_removed_marker(job), ec);
    }

    /// Whether `file` is one of the job's checkpoints, which a record leaves out when
    /// `gone` (the finishing job removed them).
    bool removed_checkpoint(const TexgenJob& job, const fs::path& file, bool gone)
    {
        if (!gone)
            return false;
        const fs::path checkpoints = (job.folder / "checkpoints").lexically_normal();
        const fs::path f = file.lexically_normal();
        const auto [end, _] = std::mismatch(checkpoints.begin(), checkpoints.end(), f.begin(), f.end());
        return end == checkpoints.end();
    }

    /// The task's command and the fingerprints of the files its arguments name (from the
    /// job's cwd), its outputs left out: what decides what it writes.
    std::string command_fingerprint(const TexgenJob& job, const TexgenTask& task, bool gone)
    {
        std::string text = job.texgen.string();
        for (const std::string& arg : task.args) {
            text += '\n' + arg;
            // "--opt=FILE" names a file too.
            const size_t eq = arg.starts_with("-") ? arg.find('=') : std::string::npos;
            const fs::path file = job.cwd / (eq == std::string::npos ? arg : arg.substr(eq + 1));
            std::error_code ec;
            const bool output = std::find(task.outputs.begin(), task.outputs.end(),
                                          file.lexically_normal()) != task.outputs.end();
            if (!output && !arg.empty() && !removed_checkpoint(job, file, gone) &&
                fs::is_regular_file(file, ec))
                text += ' ' + file_fingerprint(file);
        }
        return bytes_fingerprint(text);
    }

    /// Every file of the task's outputs (a folder's files recursively), sorted, with its
    /// fingerprint: "path fingerprint" lines. Throws when an output is missing.
    std::string outputs_fingerprint(const TexgenJob& job, const TexgenTask& task, bool gone)
    {
        std::vector<fs::path> files;
        for (const fs::path& out : task.outputs) {
            std::error_code ec;
            if (removed_checkpoint(job, out, gone))
                continue;
            if (fs::is_directory(out, ec)) {
                for (const auto& e : fs::recursive_directory_iterator(out))
                    if (e.is_regular_file())
                        files.push_back(e.path());
            } else if (fs::is_regular_file(out, ec)) {
                files.push_back(out);
            } else {
                throw std::runtime_error(fmt::format("'{}' was not written", out.string()));
            }
        }
        std::sort(files.begin(), files.end());
        std::string text;
        for (const fs::path& f : files)
            text += fmt::format("{} {}\n", f.string(), file_fingerprint(f));
        return text;
    }

    void write_record(const TexgenJob& job, size_t index, bool checkpoints_gone)
    {
        const TexgenTask& task = job.tasks[index];
        const toml::table t{{"label", task.label},
                            {"command", command_fingerprint(job, task, checkpoints_gone)},
                            {"outputs", outputs_fingerprint(job, task, checkpoints_gone)}};
        std::ostringstream text;
        text << "# Written by patina-farm task when the task succeeded: its command (with the\n"
                "# fingerprints of its input files) and the fingerprints of what it wrote.\n"
             << t << "\n";
        write_file_atomic(record_of(job, index), {text.str()}, "task record");
    }

    std::vector<bool> series_written(const TexgenJob& job)
    {
        if (job.command != "patina" || job.tasks.size() < 2)
            return {};
        std::error_code ec;
        return {fs::is_regular_file(job.output / formats::kSeriesManifest, ec)};
    }

}  // namespace

bool texgen_task_done(const TexgenJob& job, size_t index)
{
    std::error_code ec;
    const fs::path record = record_of(job, index);
    if (!fs::is_regular_file(record, ec))
        return false;
    try {
        const toml::table t = toml::parse_file(record.string());
        const TexgenTask& task = job.tasks[index];
        const bool gone = checkpoints_removed(job);
        return t["command"].value_or(std::string()) == command_fingerprint(job, task, gone) &&
               t["outputs"].value_or(std::string()) == outputs_fingerprint(job, task, gone);
    } catch (const std::exception&) {
        return false;  // a damaged record, an output gone or changed: not done
    }
}

Submitted submit_texgen_job(const TexgenJob& job, const SubmitOptions& options)
{
    return write_and_submit_job(texgen_job_shape(job), {"done", "checkpoints"},
                                texgen_job_text(job), options);
}

int run_texgen_task(const fs::path& folder, int index)
{
    const TexgenJob job = read_texgen_job(folder);
    if (index < 0 || static_cast<size_t>(index) >= job.tasks.size())
        throw std::runtime_error(fmt::format("task {}: the job in '{}' has tasks 0 to {}", index,
                                             folder.string(), job.tasks.size() - 1));
    const size_t i = static_cast<size_t>(index);
    const TexgenTask& task = job.tasks[i];
    if (texgen_task_done(job, i)) {
        std::fprintf(stderr, "task %d (%s): already done\n", index, task.label.c_str());
        return 0;
    }
    if (job.chained && i > 0 && !texgen_task_done(job, i - 1))
        throw std::runtime_error(fmt::format("task {} ({}) resumes task {}, which is not done",
                                             index, task.label, index - 1));
    std::fprintf(stderr, "task %d: patina-texgen %s (%s)\n", index, job.command.c_str(),
                 task.label.c_str());
    std::vector<std::string> argv = {job.texgen.string()};
    argv.insert(argv.end(), task.args.begin(), task.args.end());
    // The command's relative paths are from where it was submitted.
    fs::current_path(job.cwd);
    const int status = run_program(argv);
    if (status == 0)
        write_record(job, i, checkpoints_removed(job));
    return status;
}

void finish_texgen_job(const fs::path& folder)
{
    const TexgenJob job = read_texgen_job(folder);
    std::vector<std::string> missing;
    for (size_t i = 0; i < job.tasks.size(); ++i)
        if (!texgen_task_done(job, i))
            missing.push_back(fmt::format("{} ({})", i, job.tasks[i].label));
    if (!missing.empty())
        throw std::runtime_error(fmt::format("finish: task(s) {} of '{}' are not done",
                                             fmt::join(missing, ", "), folder.string()));
    if (job.command == "patina" && job.tasks.size() > 1) {
        // series.toml as `patina-texgen patina --times` writes it: the script's name and each
        // step's time and folder, from the stacks the tasks wrote.
        formats::StackSeries series;
        for (const TexgenTask& t : job.tasks) {
            const formats::TextureStack stack = formats::read_texture_stack(job.output / t.folder);
            const formats::PatinaTable& patina = formats::patina_of(stack);
            if (patina.time_years != t.time_years)
                throw std::runtime_error(fmt::format("finish: '{}' is the step at {} years, the "
                                                     "task's is {}",
                                                     stack.manifest.string(), patina.time_years,
                                                     t.time_years));
            series.script = patina.script;
            series.steps.push_back({t.time_years, t.folder});
        }
        write_file_atomic(job.output / formats::kSeriesManifest,
                          {formats::stack_series_text(series)}, "series manifest");
    }
    // What killed tasks left behind, in the job's folders and in the series' output folder
    // and its step folders (no other program should write there while the job runs).
    std::vector<fs::path> folders = {job.folder / "done", job.folder / "checkpoints", job.output};
    for (const TexgenTask& t : job.tasks)
        if (!t.folder.empty())
            folders.push_back(job.output / t.folder);
    for (const fs::path& f : folders)
        if (const size_t n = remove_staging_leftovers(f))
            std::fprintf(stderr, "finish: removed %zu staging folder(s) killed tasks left in %s\n",
                         n, f.string().c_str());
    // A chain's checkpoints served the steps, which are all written: gone, unless kept.
    // The tasks' records are written again without them first, so the tasks stay done.
    if (job.chained && !job.keep_checkpoints) {
        write_file_atomic(checkpoints_removed_marker(job),
                          {"# Written by patina-farm finish: the chain's checkpoints are removed; "
                           "the task records leave them out.\n"},
                          "marker");
        for (size_t i = 0; i < job.tasks.size(); ++i)
            write_record(job, i, true);
        std::error_code ec;
        size_t removed = 0;
        for (const fs::directory_entry& e : fs::directory_iterator(job.folder / "checkpoints", ec))
            removed += fs::remove_all(e.path(), ec) != static_cast<std::uintmax_t>(-1) ? 1 : 0;
        if (removed)
            std::fprintf(stderr, "finish: removed the chain's %zu checkpoint(s) (keep them with "
                                 "submit-texgen --keep-checkpoints)\n", removed);
    }
    std::fprintf(stderr, "finish: %zu task(s) of %s done -> %s\n", job.tasks.size(),
                 job.command.c_str(), job.output.string().c_str());
}

JobStatus texgen_job_status(const fs::path& folder)
{
    const TexgenJob job = read_texgen_job(folder);
    return job_status(texgen_job_shape(job),
                      [&](size_t i) { return std::string(texgen_task_done(job, i) ? "done" : "missing"); },
                      series_written(job));
}

Submitted resubmit_texgen_job(const fs::path& folder, const SubmitOptions& options)
{
    const TexgenJob job = read_texgen_job(folder);
    return resubmit_job(texgen_job_shape(job), texgen_job_status(folder), options);
}

}  // namespace patina::farm
