#include "farm/job_folder.h"

#include "formats/toml_location.h"

#include "farm/processes.h"

#include "core/image_io.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace patina::farm {

namespace fs = std::filesystem;

namespace {

    /// `text` in single quotes for a shell script.
    std::string quoted(const std::string& text)
    {
        std::string out = "'";
        for (char c : text)
            out += c == '\'' ? std::string("'\\''") : std::string(1, c);
        return out + "'";
    }

    /// `text` as a YAML double-quoted scalar: backslash, double quote and every control
    /// character escaped (a newline as \n), so that any path survives as it is.
    std::string yaml_quoted(const std::string& text)
    {
        std::string out = "\"";
        for (const char c : text) {
            const auto u = static_cast<unsigned char>(c);
            if (c == '"' || c == '\\')
                out += {'\\', c};
            else if (c == '\n')
                out += "\\n";
            else if (c == '\t')
                out += "\\t";
            else if (u < 0x20 || u == 0x7f)
                out += fmt::format("\\x{:02x}", u);
            else
                out += c;
        }
        return out + "\"";
    }

    std::string trimmed(std::string s)
    {
        while (!s.empty() && (s.back() == '\n' || s.back() == '\r' || s.back() == ' '))
            s.pop_back();
        // sbatch --parsable prints "id" or "id;cluster".
        return s.substr(0, s.find(';'));
    }

    /// "0-7" or "1,4,5": the --array index list of `tasks` (the array task id is the
    /// task's index in job.toml, whichever submission runs it).
    std::string index_list(const std::vector<size_t>& tasks)
    {
        const bool contiguous = tasks.back() - tasks.front() + 1 == tasks.size();
        return contiguous ? fmt::format("{}-{}", tasks.front(), tasks.back())
                          : fmt::format("{}", fmt::join(tasks, ","));
    }

    /// The job ids of the submissions so far (submitted.toml), oldest first: arrays,
    /// finishing jobs, and the jobs of chains with their tasks.
    struct SubmittedIds {
        std::vector<std::string> arrays, merges, chain_jobs;
        std::vector<int64_t> chain_tasks;
    };

    SubmittedIds read_submitted(const fs::path& dir)
    {
        SubmittedIds ids;
        const fs::path file = dir / "submitted.toml";
        std::error_code ec;
        if (!fs::exists(file, ec))
            return ids;
        try {
            const toml::table t = toml::parse_file(file.string());
            for (auto [key, out] : {std::pair{"array_jobs", &ids.arrays},
                                    std::pair{"merge_jobs", &ids.merges},
                                    std::pair{"chain_jobs", &ids.chain_jobs}})
                if (const toml::array* a = t[key].as_array())
                    for (const toml::node& id : *a)
                        out->push_back(id.value_or(std::string()));
            if (const toml::array* a = t["chain_tasks"].as_array())
                for (const toml::node& i : *a)
                    ids.chain_tasks.push_back(i.value_or(int64_t(-1)));
        } catch (const toml::parse_error& e) {
            throw std::runtime_error(fmt::format("{}:{}: {}", file.string(), e.source().begin.line,
                                                 e.description()));
        }
        if (ids.chain_tasks.size() != ids.chain_jobs.size())
            throw std::runtime_error(fmt::format("{}: chain_jobs and chain_tasks differ in length",
                                                 file.string()));
        return ids;
    }

    void write_submitted(const fs::path& dir, const SubmittedIds& ids)
    {
        auto strings = [](const std::vector<std::string>& v) {
            toml::array a;
            for (const std::string& s : v)
                a.push_back(s);
            return a;
        };
        toml::table t{{"array_jobs", strings(ids.arrays)}, {"merge_jobs", strings(ids.merges)}};
        if (!ids.chain_jobs.empty()) {
            toml::array tasks;
            for (int64_t i : ids.chain_tasks)
                tasks.push_back(i);
            t.insert_or_assign("chain_jobs", strings(ids.chain_jobs));
            t.insert_or_assign("chain_tasks", std::move(tasks));
        }
        std::ostringstream text;
        text << "# Slurm job ids of this job, oldest first (patina-farm submit, resubmit).\n"
             << t << "\n";
        write_file_atomic(dir / "submitted.toml", {text.str()}, "job file");
    }

    /// The OpenJD template: the tasks as one step with an INT parameter (an array), or one
    /// step per task each depending on the one before (a chain); then the Merge step. The
    /// job folder, the patina-farm program and the plugin path are job parameters (their
    /// defaults this machine's), so that the template runs from wherever the folder is
    /// mounted on another farm; the plugin path reaches every step through a job
    /// environment's PATINA_PLUGIN_PATH.
    std::string openjd_template(const JobShape& job)
    {
        const char* plugin_path = std::getenv("PATINA_PLUGIN_PATH");
        auto run = [&](const std::string& args) {
            return fmt::format("  script:\n    actions:\n      onRun:\n        command: "
                               "'{{{{Param.PatinaFarm}}}}'\n        args: [{}]\n",
                               args);
        };
        std::string text = fmt::format(
            "specificationVersion: 'jobtemplate-2023-09'\nname: {}\n"
            "parameterDefinitions:\n"
            "- name: JobRoot\n  type: PATH\n  objectType: DIRECTORY\n  dataFlow: INOUT\n"
            "  default: {}\n"
            "  description: 'the job folder: job.toml, parts, frames, logs'\n"
            "- name: PatinaFarm\n  type: STRING\n  default: {}\n"
            "  description: 'the patina-farm program'\n"
            "- name: PluginPath\n  type: STRING\n  default: {}\n"
            "  description: 'PATINA_PLUGIN_PATH for every task (colon-separated folders)'\n"
            "jobEnvironments:\n- name: Patina\n  variables:\n"
            "    PATINA_PLUGIN_PATH: '{{{{Param.PluginPath}}}}'\nsteps:\n",
            yaml_quoted("patina " + job.title), yaml_quoted(job.folder.string()), yaml_quoted(job.farm.string()),
            yaml_quoted(plugin_path ? plugin_path : ""));
        std::string last;
        if (job.chained) {
            for (size_t i = 0; i < job.tasks; ++i) {
                const std::string name = fmt::format("Task{}", i);
                text += fmt::format("- name: {}\n", name);
                if (!last.empty())
                    text += fmt::format("  dependencies:\n  - dependsOn: {}\n", last);
                text += run(fmt::format("'task', '{{{{Param.JobRoot}}}}', '{}'", i));
                last = name;
            }
        } else {
            text += fmt::format("- name: Tasks\n  parameterSpace:\n    taskParameterDefinitions:\n"
                                "    - name: Task\n      type: INT\n      range: '0-{}'\n",
                                job.tasks - 1);
            text += run("'task', '{{Param.JobRoot}}', '{{Task.Param.Task}}'");
            last = "Tasks";
        }
        text += fmt::format("- name: Merge\n  dependencies:\n  - dependsOn: {}\n", last);
        text += run("'finish', '{{Param.JobRoot}}'");
        return text;
    }

}  // namespace

std::vector<fs::path> write_job_scripts(const JobShape& job, const std::vector<std::string>& subfolders)
{
    const fs::path& dir = job.folder;
    std::error_code ec;
    std::vector<std::string> folders = subfolders;
    folders.emplace_back("logs");
    for (const std::string& sub : folders)
        if (!fs::create_directories(dir / sub, ec) && ec)
            throw std::runtime_error(fmt::format("submit: cannot make '{}': {}",
                                                 (dir / sub).string(), ec.message()));
    const std::string farm = quoted(job.farm.string()), folder = quoted(dir.string());
    std::vector<fs::path> files;
    auto write = [&](const char* name, const std::string& text) {
        const fs::path file = dir / name;
        write_file_atomic(file, {text}, "job file");
        files.push_back(file);
    };
    // An array task's index is SLURM_ARRAY_TASK_ID; a chain's job passes it as $1. Each
    // attempt (a requeue, a resubmit) writes a log of its own, task_<i>.<attempt>.log, so
    // that the first failure's message is kept; Slurm's own lines go to
    // slurm_task_<i>.log.
    write("slurm_task.sh",
          fmt::format("#!/bin/bash\n# Written by patina-farm submit: one task of the job "
                      "(job.toml lists them), $1 or SLURM_ARRAY_TASK_ID.\n"
                      "i=\"${{1:-$SLURM_ARRAY_TASK_ID}}\"\nn=1\n"
                      "while [ -e {}/logs/task_$i.$n.log ]; do n=$((n + 1)); done\n"
                      "exec > {}/logs/task_$i.$n.log 2>&1\nexec {} task {} \"$i\"\n",
                      folder, folder, farm, folder));
    write("slurm_merge.sh",
          fmt::format("#!/bin/bash\n# Written by patina-farm submit: the finishing job, after "
                      "every task succeeded.\nexec {} finish {}\n",
                      farm, folder));
    write("run_local.sh",
          fmt::format("#!/bin/bash\n# Written by patina-farm submit: the job without a "
                      "scheduler, one task after the other.\nset -e\nfor i in $(seq 0 {}); do\n"
                      "  {} task {} \"$i\"\ndone\nexec {} finish {}\n",
                      job.tasks - 1, farm, folder, farm, folder));
    write("job.openjd.yaml", openjd_template(job));
    for (const char* name : {"slurm_task.sh", "slurm_merge.sh", "run_local.sh"})
        fs::permissions(dir / name, fs::perms::owner_exec | fs::perms::group_exec,
                        fs::perm_options::add, ec);
    return files;
}

Submitted write_and_submit_job(const JobShape& job, const std::vector<std::string>& subfolders,
                               const std::string& job_toml, const SubmitOptions& options)
{
    std::vector<fs::path> files = write_job_scripts(job, subfolders);
    write_file_atomic(job.folder / "job.toml", {job_toml}, "job file");
    files.push_back(job.folder / "job.toml");
    Submitted out;
    if (!options.dry_run) {
        std::vector<size_t> all(job.tasks);
        for (size_t i = 0; i < all.size(); ++i)
            all[i] = i;
        out = submit_job(job, all, options);
    }
    out.files = std::move(files);
    return out;
}

toml::table parse_job_file(const fs::path& folder)
{
    return formats::parse_toml_file(folder / "job.toml");
}

Submitted submit_job(const JobShape& job, const std::vector<size_t>& tasks,
                     const SubmitOptions& options)
{
    const fs::path& dir = job.folder;
    auto base = [&](const std::string& name, const fs::path& log) {
        std::vector<std::string> a = {"sbatch", "--parsable", "--job-name", name,
                                      "--output", log.string(), "--open-mode=append",
                                      "--chdir", dir.string()};
        if (!options.partition.empty())
            a.insert(a.end(), {"--partition", options.partition});
        return a;
    };
    auto cpus = [&](std::vector<std::string>& a) {
        if (options.cpus_per_task > 0)
            a.push_back(fmt::format("--cpus-per-task={}", options.cpus_per_task));
    };
    auto after = [](std::vector<std::string>& a, const std::string& id) {
        a.insert(a.end(), {"--dependency=afterok:" + id, "--kill-on-invalid-dep=yes"});
    };
    const std::string name = "patina-" + dir.filename().string();
    SubmittedIds ids = read_submitted(dir);
    Submitted out;
    std::string last;  // the job the finishing job waits for
    if (!tasks.empty() && job.chained) {
        std::vector<std::string> chain;
        for (size_t i : tasks) {
            std::vector<std::string> a = base(fmt::format("{}-{}", name, i),
                                              dir / "logs" / fmt::format("slurm_task_{}.log", i));
            if (!last.empty())
                after(a, last);
            cpus(a);
            a.push_back((dir / "slurm_task.sh").string());
            a.push_back(std::to_string(i));
            last = trimmed(run_and_capture(a));
            chain.push_back(last);
            ids.chain_jobs.push_back(last);
            ids.chain_tasks.push_back(static_cast<int64_t>(i));
        }
        out.array_job = fmt::format("{}", fmt::join(chain, ","));
    } else if (!tasks.empty()) {
        std::vector<std::string> a = base(name, dir / "logs" / "slurm_task_%a.log");
        a.push_back("--array=" + index_list(tasks) +
                    (options.throttle > 0 ? fmt::format("%{}", options.throttle) : ""));
        cpus(a);
        a.push_back((dir / "slurm_task.sh").string());
        last = out.array_job = trimmed(run_and_capture(a));
        ids.arrays.push_back(last);
    }
    std::vector<std::string> merge = base(name + "-merge", dir / "logs" / "merge.log");
    if (!last.empty())
        after(merge, last);
    merge.push_back((dir / "slurm_merge.sh").string());
    out.merge_job = trimmed(run_and_capture(merge));
    ids.merges.push_back(out.merge_job);
    write_submitted(dir, ids);
    return out;
}

size_t JobStatus::count(const std::string& state) const
{
    return static_cast<size_t>(std::count(tasks.begin(), tasks.end(), state));
}

JobStatus job_status(const JobShape& job,
                     const std::function<std::string(size_t)>& output_state,
                     std::vector<bool> merged)
{
    JobStatus st;
    st.tasks.assign(job.tasks, "missing");
    st.failures.assign(job.tasks, "");
    st.merged = std::move(merged);
    const SubmittedIds ids = read_submitted(job.folder);
    std::vector<std::string> queued(job.tasks);
    std::vector<std::string> all = ids.arrays;
    all.insert(all.end(), ids.merges.begin(), ids.merges.end());
    all.insert(all.end(), ids.chain_jobs.begin(), ids.chain_jobs.end());
    if (!all.empty()) {
        try {
            // One line per job or array task: its job id (the array's for an array task),
            // array task id (N/A for a plain job) and state; -r lists pending array tasks
            // one by one.
            const std::string out = run_and_capture(
                {"squeue", "-h", "-r", "-j", fmt::format("{}", fmt::join(all, ",")), "-o",
                 "%F %K %t %r"});
            std::istringstream lines(out);
            std::string line;
            while (std::getline(lines, line)) {
                std::istringstream fields(line);
                std::string id, task, state, reason;
                if (!(fields >> id >> task >> state))
                    continue;
                fields >> reason;
                const std::string s = state == "PD" ? "pending" : "running";
                if (std::find(ids.merges.begin(), ids.merges.end(), id) != ids.merges.end()) {
                    st.merge_queued = true;
                    st.merge_state = reason.rfind("JobHeld", 0) == 0 ? "held"
                                     : reason == "DependencyNeverSatisfied"
                                         ? "waiting on a task that failed"
                                         : "queued";
                    continue;
                }
                if (auto c = std::find(ids.chain_jobs.begin(), ids.chain_jobs.end(), id);
                    c != ids.chain_jobs.end()) {
                    const int64_t index = ids.chain_tasks[size_t(c - ids.chain_jobs.begin())];
                    if (index >= 0 && size_t(index) < queued.size())
                        queued[size_t(index)] = s;
                    continue;
                }
                size_t index = 0;
                if (std::from_chars(task.data(), task.data() + task.size(), index).ec ==
                        std::errc() &&
                    index < queued.size())
                    queued[index] = s;
            }
        } catch (const std::exception& e) {
            st.queue_known = false;  // squeue failed: a queued task cannot be told apart
            st.queue_error = e.what();
        }
    }
    for (size_t i = 0; i < job.tasks; ++i) {
        if (!queued[i].empty()) {
            st.tasks[i] = queued[i];
        } else if (st.tasks[i] = output_state(i); st.tasks[i] != "done") {
            // Its latest attempt's log says why: the first error line (the program's,
            // before the task's own), else the last line; else what Slurm wrote of it (a
            // cancellation, a lost node).
            int attempt = 0;
            std::error_code ec;
            while (fs::exists(job.folder / "logs" / fmt::format("task_{}.{}.log", i, attempt + 1), ec))
                ++attempt;
            auto read_log = [](const fs::path& file) {
                std::ifstream log(file);
                std::string line, last, error;
                while (std::getline(log, line)) {
                    if (!line.empty())
                        last = line;
                    if (error.empty() && line.find("error:") != std::string::npos)
                        error = line;
                }
                return error.empty() ? last : error;
            };
            if (attempt > 0)
                st.failures[i] = read_log(job.folder / "logs" / fmt::format("task_{}.{}.log", i, attempt));
            if (st.failures[i].empty())
                st.failures[i] = read_log(job.folder / "logs" / fmt::format("slurm_task_{}.log", i));
        }
    }
    // The finishing job out of the queue with its outputs not all written: it ran and
    // failed (its log says why), or Slurm dropped it because a task it waited for failed.
    const bool finished = std::all_of(st.merged.begin(), st.merged.end(), [](bool b) { return b; });
    if (!st.merge_queued && !finished && !ids.merges.empty() && st.queue_known) {
        const fs::path log = job.folder / "logs" / "merge.log";
        std::ifstream in(log);
        std::string line, error, last;
        while (std::getline(in, line)) {
            if (!line.empty())
                last = line;
            if (error.empty() && line.find("error") != std::string::npos)
                error = line;
        }
        if (in.is_open() || !last.empty()) {
            st.merge_state = "failed";
            st.merge_error = fmt::format("{}: {}", log.string(), error.empty() ? last : error);
        } else {
            st.merge_state = "not run: a task it waits for failed";
        }
    }
    return st;
}

Submitted resubmit_job(const JobShape& job, const JobStatus& st, const SubmitOptions& options)
{
    const std::string folder = job.folder.string();
    if (!st.queue_known)
        throw std::runtime_error(fmt::format("resubmit of '{}': squeue could not be asked, so "
                                             "the queued tasks are not known",
                                             folder));
    if (st.merge_queued || st.count("running") + st.count("pending") > 0)
        throw std::runtime_error(fmt::format(
            "resubmit of '{}': {} task(s) and {} merge still in Slurm's queue; wait for them "
            "or scancel them first", folder, st.count("running") + st.count("pending"),
            st.merge_queued ? "a" : "no"));
    std::vector<size_t> missing;
    for (size_t i = 0; i < st.tasks.size(); ++i)
        if (st.tasks[i] == "missing" || st.tasks[i] == "broken")
            missing.push_back(i);
    if (missing.empty() && std::all_of(st.merged.begin(), st.merged.end(), [](bool b) { return b; }))
        return {};
    return submit_job(job, missing, options);
}

size_t remove_staging_leftovers(const fs::path& folder)
{
    std::error_code ec;
    size_t removed = 0;
    for (const fs::directory_entry& e : fs::directory_iterator(folder, ec)) {
        if (!e.is_directory(ec) || e.path().filename().string().rfind(".patina-staging-", 0) != 0)
            continue;
        if (fs::remove_all(e.path(), ec) != static_cast<std::uintmax_t>(-1) && !ec)
            ++removed;
    }
    return removed;
}

}  // namespace patina::farm
