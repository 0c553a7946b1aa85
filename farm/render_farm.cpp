#include "farm/render_farm.h"

#include "farm/frame_merge.h"
#include "farm/processes.h"
#include "farm/render_part.h"

#include "core/image_io.h"
#include "render/film_output.h"

#include <fmt/format.h>

#include <cstdio>
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

    std::vector<std::string> array = {
        "sbatch", "--parsable", "--job-name", "patina-" + dir.filename().string(),
        "--output", (dir / "logs" / "task_%a.log").string(), "--chdir", dir.string(),
        options.throttle > 0 ? fmt::format("--array=0-{}%{}", n - 1, options.throttle)
                             : fmt::format("--array=0-{}", n - 1)};
    if (!options.partition.empty())
        array.insert(array.begin() + 2, {"--partition", options.partition});
    array.push_back((dir / "slurm_task.sh").string());
    out.array_job = trimmed(run_and_capture(array));
    std::vector<std::string> merge = {
        "sbatch", "--parsable", "--job-name", "patina-" + dir.filename().string() + "-merge",
        "--output", (dir / "logs" / "merge.log").string(), "--chdir", dir.string(),
        "--dependency=afterok:" + out.array_job, "--kill-on-invalid-dep=yes"};
    if (!options.partition.empty())
        merge.insert(merge.begin() + 2, {"--partition", options.partition});
    merge.push_back((dir / "slurm_merge.sh").string());
    out.merge_job = trimmed(run_and_capture(merge));
    write_file_atomic(dir / "submitted.toml",
                      {fmt::format("# Slurm job ids of this job (patina-farm submit).\n"
                                   "array_job = \"{}\"\nmerge_job = \"{}\"\n",
                                   out.array_job, out.merge_job)},
                      "job file");
    return out;
}

bool valid_part(const RenderTask& task, const fs::path& part)
{
    std::error_code ec;
    if (!fs::is_regular_file(part, ec))
        return false;
    try {
        const RenderPart p = read_render_part(part, false);
        const bool samples = task.sample_end == 0 ||
                             (p.sample_begin == task.sample_begin && p.sample_end == task.sample_end);
        return samples && p.scene_hash == render::scene_hash(task.scene);
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
    if (valid_part(task, output)) {
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
        for (const fs::path& p : m.parts)
            parts.push_back(job.folder / p);
        const MergeResult r = merge_render_parts(parts, job.folder / m.output);
        std::fprintf(stderr, "frame %d: %zu part(s), samples %d-%d -> %s\n", m.frame, r.parts,
                     r.sample_begin, r.sample_end, (job.folder / m.output).string().c_str());
    }
}

}  // namespace patina::farm
