#include "farm/render_farm.h"

#include "farm/frame_merge.h"
#include "farm/processes.h"
#include "farm/render_part.h"

#include "core/image_io.h"
#include "render/film_output.h"
#include "render/plugin_setup.h"
#include "render/renderer.h"
#include "render/scene.h"

#include "core/host.h"
#include "core/plugin_registry.h"

#include <fmt/format.h>
#include <fmt/ranges.h>
#include <toml++/toml.h>

#include <algorithm>
#include <charconv>
#include <cstdio>
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

    /// The job ids of the submissions so far (submitted.toml), oldest first.
    void read_submitted(const fs::path& dir, std::vector<std::string>& arrays,
                        std::vector<std::string>& merges)
    {
        const fs::path file = dir / "submitted.toml";
        std::error_code ec;
        if (!fs::exists(file, ec))
            return;
        try {
            const toml::table t = toml::parse_file(file.string());
            for (auto [key, out] : {std::pair{"array_jobs", &arrays}, std::pair{"merge_jobs", &merges}})
                if (const toml::array* a = t[key].as_array())
                    for (const toml::node& id : *a)
                        out->push_back(id.value_or(std::string()));
        } catch (const toml::parse_error& e) {
            throw std::runtime_error(fmt::format("{}:{}: {}", file.string(), e.source().begin.line,
                                                 e.description()));
        }
    }

    /// Submits `tasks` of the job (none: the merge alone) as an array, then the merge after
    /// it (afterok), and appends their ids to submitted.toml.
    Submitted sbatch_tasks_and_merge(const RenderJob& job, const std::vector<size_t>& tasks,
                                     const SubmitOptions& options, Submitted out)
    {
        const fs::path& dir = job.folder;
        auto base = [&](const std::string& name, const fs::path& log) {
            std::vector<std::string> a = {"sbatch", "--parsable", "--job-name", name,
                                          "--output", log.string(), "--chdir", dir.string()};
            if (!options.partition.empty())
                a.insert(a.end(), {"--partition", options.partition});
            return a;
        };
        const std::string name = "patina-" + dir.filename().string();
        if (!tasks.empty()) {
            std::vector<std::string> array = base(name, dir / "logs" / "task_%a.log");
            array.push_back("--array=" + index_list(tasks) +
                            (options.throttle > 0 ? fmt::format("%{}", options.throttle) : ""));
            array.push_back((dir / "slurm_task.sh").string());
            out.array_job = trimmed(run_and_capture(array));
        }
        std::vector<std::string> merge = base(name + "-merge", dir / "logs" / "merge.log");
        if (!out.array_job.empty())
            merge.insert(merge.end(), {"--dependency=afterok:" + out.array_job,
                                       "--kill-on-invalid-dep=yes"});
        merge.push_back((dir / "slurm_merge.sh").string());
        out.merge_job = trimmed(run_and_capture(merge));

        std::vector<std::string> arrays, merges;
        read_submitted(dir, arrays, merges);
        if (!out.array_job.empty())
            arrays.push_back(out.array_job);
        merges.push_back(out.merge_job);
        toml::array a, m;
        for (const std::string& id : arrays)
            a.push_back(id);
        for (const std::string& id : merges)
            m.push_back(id);
        std::ostringstream text;
        text << "# Slurm job ids of this job, oldest first (patina-farm submit, resubmit).\n"
             << toml::table{{"array_jobs", a}, {"merge_jobs", m}} << "\n";
        write_file_atomic(dir / "submitted.toml", {text.str()}, "job file");
        return out;
    }

}  // namespace

Submitted submit_render_job(const RenderJob& job, const SubmitOptions& options)
{
    const fs::path& dir = job.folder;
    std::error_code ec;
    for (const char* sub : {"parts", "frames", "logs"})
        if (!fs::create_directories(dir / sub, ec) && ec)
            throw std::runtime_error(fmt::format("submit: cannot make '{}': {}",
                                                 (dir / sub).string(), ec.message()));
    const std::string farm = quoted(job.farm.string()), folder = quoted(dir.string());
    const size_t n = job.tasks.size();
    Submitted out;
    // Each file in place at once (its own transaction): the jobs may start as soon as
    // sbatch has them.
    auto write = [&](const char* name, const std::string& text) {
        const fs::path file = dir / name;
        write_file_atomic(file, {text}, "job file");
        out.files.push_back(file);
    };
    write("job.toml", render_job_text(job));
    write("slurm_task.sh",
          fmt::format("#!/bin/bash\n# Written by patina-farm submit: task $SLURM_ARRAY_TASK_ID "
                      "of the job array (job.toml lists them).\nexec {} task {} "
                      "\"$SLURM_ARRAY_TASK_ID\"\n",
                      farm, folder));
    write("slurm_merge.sh",
          fmt::format("#!/bin/bash\n# Written by patina-farm submit: the merge, after every task "
                      "succeeded.\nexec {} finish {}\n",
                      farm, folder));
    write("run_local.sh",
          fmt::format("#!/bin/bash\n# Written by patina-farm submit: the job without a "
                      "scheduler, one task after the other.\nset -e\nfor i in $(seq 0 {}); do\n"
                      "  {} task {} \"$i\"\ndone\nexec {} finish {}\n",
                      n - 1, farm, folder, farm, folder));
    // OpenJD (Open Job Description, the job template AWS Deadline Cloud runs): a step of
    // n tasks and a merge step that depends on it.
    write("job.openjd.yaml",
          fmt::format("specificationVersion: 'jobtemplate-2023-09'\n"
                      "name: 'patina render {}'\n"
                      "steps:\n"
                      "- name: Render\n"
                      "  parameterSpace:\n"
                      "    taskParameterDefinitions:\n"
                      "    - name: Task\n"
                      "      type: INT\n"
                      "      range: '0-{}'\n"
                      "  script:\n"
                      "    actions:\n"
                      "      onRun:\n"
                      "        command: {}\n"
                      "        args: ['task', {}, '{{{{Task.Param.Task}}}}']\n"
                      "- name: Merge\n"
                      "  dependencies:\n"
                      "  - dependsOn: Render\n"
                      "  script:\n"
                      "    actions:\n"
                      "      onRun:\n"
                      "        command: {}\n"
                      "        args: ['finish', {}]\n",
                      dir.filename().string(), n - 1, farm, folder, farm, folder));
    // Scripts are made executable once they are in place.
    for (const char* name : {"slurm_task.sh", "slurm_merge.sh", "run_local.sh"})
        fs::permissions(dir / name, fs::perms::owner_exec | fs::perms::group_exec,
                        fs::perm_options::add, ec);
    if (options.dry_run)
        return out;

    const std::vector<size_t> all = [&] {
        std::vector<size_t> v(n);
        for (size_t i = 0; i < n; ++i)
            v[i] = i;
        return v;
    }();
    return sbatch_tasks_and_merge(job, all, options, out);
}

bool valid_part(const RenderJob& job, const RenderTask& task, const fs::path& part)
{
    std::error_code ec;
    if (!fs::is_regular_file(part, ec))
        return false;
    try {
        const RenderPart p = read_render_part(part, false);
        // Its samples: the task's range, or the job's spp from sample 0.
        const bool samples =
            task.sample_end > 0
                ? p.sample_begin == task.sample_begin && p.sample_end == task.sample_end
                : job.spp == 0 || (p.sample_begin == 0 && p.sample_end == job.spp);
        // Its pixels: the task's band of the frame (a part of a job split otherwise is not).
        const render::Region band =
            job.tiles > 1 ? render::tile_region(task.tile, job.tiles, p.full_width, p.full_height)
                          : render::Region{0, 0, p.full_width, p.full_height};
        const bool pixels = p.x == band.x0 && p.y == band.y0 && p.width == band.width() &&
                            p.height == band.height();
        return samples && pixels && p.scene_hash == render::scene_hash(task.scene) &&
               (job.plugins.empty() || p.plugins == job.plugins);
    } catch (const std::exception&) {
        return false;
    }
}

int run_render_task(const fs::path& folder, int index)
{
    const RenderJob job = read_render_job(folder);
    if (index < 0 || static_cast<size_t>(index) >= job.tasks.size())
        throw std::runtime_error(fmt::format("task {}: the job in '{}' has tasks 0 to {}", index,
                                             folder.string(), job.tasks.size() - 1));
    const RenderTask& task = job.tasks[static_cast<size_t>(index)];
    const fs::path output = job.folder / task.output;
    if (valid_part(job, task, output)) {
        std::fprintf(stderr, "task %d: %s is already rendered\n", index, output.string().c_str());
        return 0;
    }
    std::vector<std::string> argv = {job.render.string(), task.scene.string(), "--quiet",
                                     "--output", output.string()};
    if (job.tiles > 1) {
        argv.emplace_back("--tile");
        argv.push_back(fmt::format("{}/{}", task.tile, job.tiles));
    }
    if (task.sample_end > 0) {
        argv.emplace_back("--samples");
        argv.push_back(fmt::format("{}-{}", task.sample_begin, task.sample_end));
    } else if (job.spp > 0) {
        argv.emplace_back("--spp");
        argv.push_back(std::to_string(job.spp));
    }
    std::fprintf(stderr, "task %d: frame %d, tile %d/%d%s\n", index, task.frame, task.tile,
                 job.tiles,
                 task.sample_end > 0
                     ? fmt::format(", samples {}-{}", task.sample_begin, task.sample_end).c_str()
                     : "");
    return run_program(argv);
}

void finish_render_job(const fs::path& folder)
{
    const RenderJob job = read_render_job(folder);
    for (const FrameMerge& m : job.merges) {
        std::vector<fs::path> parts;
        for (const fs::path& p : m.parts) {
            parts.push_back(job.folder / p);
            const RenderPart header = read_render_part(parts.back(), false);
            if (!job.plugins.empty() && header.plugins != job.plugins)
                throw std::runtime_error(fmt::format(
                    "finish: part '{}' was rendered with the plugins '{}', the job was "
                    "submitted with '{}': point every node at the same plugin folder "
                    "(PATINA_PLUGIN_PATH) and resubmit the task",
                    parts.back().string(), header.plugins, job.plugins));
        }
        const MergeResult r = merge_render_parts(parts, job.folder / m.output);
        std::fprintf(stderr, "frame %d: %zu part(s), samples %d-%d -> %s\n", m.frame, r.parts,
                     r.sample_begin, r.sample_end, (job.folder / m.output).string().c_str());
    }
}

size_t JobStatus::count(const std::string& state) const
{
    return static_cast<size_t>(std::count(tasks.begin(), tasks.end(), state));
}

JobStatus render_job_status(const fs::path& folder)
{
    const RenderJob job = read_render_job(folder);
    JobStatus st;
    st.tasks.assign(job.tasks.size(), "missing");
    st.failures.assign(job.tasks.size(), "");
    std::vector<std::string> arrays, merges;
    read_submitted(job.folder, arrays, merges);
    std::vector<std::string> queued(job.tasks.size());
    if (!arrays.empty() || !merges.empty()) {
        std::vector<std::string> ids = arrays;
        ids.insert(ids.end(), merges.begin(), merges.end());
        try {
            // One line per job or array task: its array job id, task id (N/A for a plain
            // job) and state; -r lists pending array tasks one by one.
            const std::string out = run_and_capture(
                {"squeue", "-h", "-r", "-j", fmt::format("{}", fmt::join(ids, ",")), "-o",
                 "%F %K %t"});
            std::istringstream lines(out);
            std::string array, task, state;
            while (lines >> array >> task >> state) {
                if (std::find(merges.begin(), merges.end(), array) != merges.end()) {
                    st.merge_queued = true;
                    continue;
                }
                size_t index = 0;
                if (std::from_chars(task.data(), task.data() + task.size(), index).ec == std::errc() &&
                    index < queued.size())
                    queued[index] = state == "PD" ? "pending" : "running";
            }
        } catch (const std::exception&) {
            st.queue_known = false;  // squeue failed: the files alone tell
        }
    }
    for (size_t i = 0; i < job.tasks.size(); ++i) {
        if (!queued[i].empty())
            st.tasks[i] = queued[i];
        else if (valid_part(job, job.tasks[i], job.folder / job.tasks[i].output))
            st.tasks[i] = "done";
        else {
            // Its log says why: the first error line (the renderer's, before the task's
            // own), else the last line.
            std::ifstream log(job.folder / "logs" / fmt::format("task_{}.log", i));
            std::string line, last, error;
            while (std::getline(log, line)) {
                if (!line.empty())
                    last = line;
                if (error.empty() && line.find("error:") != std::string::npos)
                    error = line;
            }
            st.failures[i] = error.empty() ? last : error;
        }
    }
    for (const FrameMerge& m : job.merges) {
        std::error_code ec;
        st.merged.push_back(fs::is_regular_file(job.folder / m.output, ec));
    }
    return st;
}

Submitted resubmit_render_job(const fs::path& folder, const SubmitOptions& options)
{
    const RenderJob job = read_render_job(folder);
    const JobStatus st = render_job_status(folder);
    if (!st.queue_known)
        throw std::runtime_error(fmt::format("resubmit of '{}': squeue could not be asked, so "
                                             "the queued tasks are not known",
                                             folder.string()));
    if (st.merge_queued || st.count("running") + st.count("pending") > 0)
        throw std::runtime_error(fmt::format(
            "resubmit of '{}': {} task(s) and {} merge still in Slurm's queue; wait for them "
            "or scancel them first", folder.string(), st.count("running") + st.count("pending"),
            st.merge_queued ? "a" : "no"));
    std::vector<size_t> missing;
    for (size_t i = 0; i < st.tasks.size(); ++i)
        if (st.tasks[i] == "missing")
            missing.push_back(i);
    if (missing.empty() && std::all_of(st.merged.begin(), st.merged.end(), [](bool b) { return b; }))
        return {};
    return sbatch_tasks_and_merge(job, missing, options, {});
}

std::string plugin_set_of(const fs::path& scene)
{
    const render::SceneFile file = render::parse_scene_file(scene);
    render::PluginSearch search;
    render::check_scene_plugins(file.plugin_dirs, file.plugins_where, search);
    search.scene = file.plugin_dirs;
    PluginRegistry registry(default_host().c_host());
    render::load_plugins(registry, search);
    return render::scene_plugin_set(file.root, registry);
}

}  // namespace patina::farm
