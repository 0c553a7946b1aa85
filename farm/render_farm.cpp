#include "farm/render_farm.h"

#include "farm/frame_merge.h"
#include "farm/job_folder.h"
#include "farm/processes.h"
#include "farm/render_part.h"

#include "core/image_io.h"
#include "render/film_output.h"
#include "render/plugin_setup.h"
#include "render/renderer.h"
#include "render/scene.h"

#include "host/host.h"
#include "host/plugin_registry.h"

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


JobShape render_job_shape(const RenderJob& job)
{
    return {job.folder, job.farm, "render " + job.scene.stem().string(), job.tasks.size(), false};
}

Submitted submit_render_job(const RenderJob& job, const SubmitOptions& options)
{
    return write_and_submit_job(render_job_shape(job), {"parts", "frames"}, render_job_text(job),
                                options);
}

std::string part_state(const RenderJob& job, const RenderTask& task, const fs::path& part)
{
    std::error_code ec;
    if (!fs::exists(part, ec))
        return "missing";
    try {
        // The pixels too: a part cut short after its header reads its header, not them.
        const RenderPart p = read_render_part(part, true);
        // Its samples: the task's range, or the job's spp from sample 0.
        const bool samples =
            task.sample_end > 0
                ? p.header.sample_begin == task.sample_begin && p.header.sample_end == task.sample_end
                : job.spp == 0 || (p.header.sample_begin == 0 && p.header.sample_end == job.spp);
        // Its pixels: the task's band of the frame (a part of a job split otherwise is not).
        const render::Region band =
            job.tiles > 1 ? render::tile_region(task.tile, job.tiles, p.full_width, p.full_height)
                          : render::Region{0, 0, p.full_width, p.full_height};
        const bool pixels = p.x == band.x0 && p.y == band.y0 && p.width == band.width() &&
                            p.height == band.height();
        return samples && pixels && p.header.scene_hash == render::scene_hash(task.scene) &&
                       (job.plugins.empty() || p.header.plugins == job.plugins)
                   ? "done"
                   : "broken";
    } catch (const std::exception&) {
        return "broken";
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
            const RenderPart part = read_render_part(parts.back(), false);
            if (!job.plugins.empty() && part.header.plugins != job.plugins)
                throw std::runtime_error(fmt::format(
                    "finish: part '{}' was rendered with the plugins '{}', the job was "
                    "submitted with '{}': point every node at the same plugin folder "
                    "(PATINA_PLUGIN_PATH) and resubmit the task",
                    parts.back().string(), part.header.plugins, job.plugins));
        }
        const MergeResult r = merge_render_parts(parts, job.folder / m.output);
        std::fprintf(stderr, "frame %d: %zu part(s), samples %d-%d -> %s\n", m.frame, r.parts,
                     r.sample_begin, r.sample_end, (job.folder / m.output).string().c_str());
    }
    // What killed tasks left behind: the job's own folders only the job writes.
    for (const char* sub : {"parts", "frames"})
        if (const size_t n = remove_staging_leftovers(job.folder / sub))
            std::fprintf(stderr, "finish: removed %zu staging folder(s) killed tasks left in %s\n",
                         n, (job.folder / sub).string().c_str());
}

JobStatus render_job_status(const fs::path& folder)
{
    const RenderJob job = read_render_job(folder);
    std::vector<bool> merged;
    for (const FrameMerge& m : job.merges) {
        std::error_code ec;
        merged.push_back(fs::is_regular_file(job.folder / m.output, ec));
    }
    return job_status(
        render_job_shape(job),
        [&](size_t i) { return part_state(job, job.tasks[i], job.folder / job.tasks[i].output); },
        std::move(merged));
}

Submitted resubmit_render_job(const fs::path& folder, const SubmitOptions& options)
{
    const RenderJob job = read_render_job(folder);
    return resubmit_job(render_job_shape(job), render_job_status(folder), options);
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
