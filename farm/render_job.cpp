#include "farm/render_job.h"

#include "formats/toml_location.h"

#include "farm/job_folder.h"

#include "render/renderer.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <sstream>
#include <stdexcept>

namespace patina::farm {

namespace fs = std::filesystem;

RenderJob plan_render_job(const RenderJobOptions& o, const fs::path& render, const fs::path& farm)
{
    if (o.tiles < 1)
        throw std::invalid_argument(fmt::format("--tiles {}: at least 1", o.tiles));
    if (o.sample_splits < 1)
        throw std::invalid_argument(fmt::format("--sample-splits {}: at least 1", o.sample_splits));
    if (o.sample_splits > 1 && o.spp < o.sample_splits)
        throw std::invalid_argument(fmt::format(
            "--sample-splits {} needs --spp N with N >= {} (the samples to split)",
            o.sample_splits, o.sample_splits));
    RenderJob job;
    job.folder = fs::absolute(o.folder).lexically_normal();
    job.scene = fs::absolute(o.scene).lexically_normal();
    job.frames = !o.frames.empty();
    if (job.frames)
        std::tie(job.first_frame, job.last_frame) = render::parse_frames(o.frames);
    job.tiles = o.tiles;
    job.sample_splits = o.sample_splits;
    job.spp = o.spp;
    job.render = render;
    job.farm = farm;
    for (int frame = job.first_frame; frame <= job.last_frame; ++frame) {
        const fs::path scene = job.frames
                                   ? fs::path(render::substitute_frame(job.scene.string(), frame))
                                   : job.scene;
        std::error_code ec;
        if (!fs::is_regular_file(scene, ec))
            throw std::invalid_argument(fmt::format("scene '{}'{} does not exist", scene.string(),
                                                    job.frames ? fmt::format(" (frame {})", frame)
                                                               : std::string()));
        FrameMerge merge;
        merge.frame = frame;
        merge.output = fmt::format("frames/frame.{:04}.exr", frame);
        for (int s = 0; s < job.sample_splits; ++s)
            for (int t = 0; t < job.tiles; ++t) {
                RenderTask task;
                task.frame = frame;
                task.tile = t;
                task.scene = scene;
                if (job.sample_splits > 1) {
                    task.sample_begin = static_cast<int>(int64_t(job.spp) * s / job.sample_splits);
                    task.sample_end = static_cast<int>(int64_t(job.spp) * (s + 1) / job.sample_splits);
                }
                task.output = fmt::format("parts/f{:04}_t{:03}_s{:03}.exr", frame, t, s);
                merge.parts.push_back(task.output);
                job.tasks.push_back(std::move(task));
            }
        job.merges.push_back(std::move(merge));
    }
    return job;
}

std::string render_job_text(const RenderJob& job)
{
    toml::table root;
    toml::table j{{"kind", "render"},
                  {"scene", job.scene.string()},
                  {"frames", job.frames},
                  {"first_frame", job.first_frame},
                  {"last_frame", job.last_frame},
                  {"tiles", job.tiles},
                  {"sample_splits", job.sample_splits},
                  {"spp", job.spp},
                  {"render", job.render.string()},
                  {"farm", job.farm.string()},
                  {"plugins", job.plugins}};
    root.insert_or_assign("job", std::move(j));
    toml::array tasks;
    for (const RenderTask& t : job.tasks)
        tasks.push_back(toml::table{{"frame", t.frame},
                                    {"tile", t.tile},
                                    {"sample_begin", t.sample_begin},
                                    {"sample_end", t.sample_end},
                                    {"scene", t.scene.string()},
                                    {"output", t.output.generic_string()}});
    root.insert_or_assign("task", std::move(tasks));
    toml::array merges;
    for (const FrameMerge& m : job.merges) {
        toml::array parts;
        for (const fs::path& p : m.parts)
            parts.push_back(p.generic_string());
        merges.push_back(toml::table{{"frame", m.frame},
                                     {"output", m.output.generic_string()},
                                     {"parts", std::move(parts)}});
    }
    root.insert_or_assign("merge", std::move(merges));
    std::ostringstream text;
    text << "# Written by patina-farm submit (docs/farm.md): the tasks of the job array in the\n"
            "# order of SLURM_ARRAY_TASK_ID, and a merge per frame.\n"
         << root << "\n";
    return text.str();
}

RenderJob read_render_job(const fs::path& folder)
{
    const fs::path file = folder / "job.toml";
    const toml::table root = parse_job_file(folder);
    auto fail = [&](const std::string& what) {
        return std::runtime_error(fmt::format("{}: {}", file.string(), what));
    };
    const toml::table* j = root["job"].as_table();
    if (!j || (*j)["kind"].value_or(std::string()) != "render")
        throw fail("no [job] of kind \"render\"");
    formats::toml_check_keys(file, root, "", {"job", "task", "merge"});
    formats::toml_check_keys(file, *j, "job.",
                             {"kind", "scene", "frames", "first_frame", "last_frame", "tiles",
                              "sample_splits", "spp", "render", "farm", "plugins"});
    RenderJob job;
    job.folder = fs::absolute(folder).lexically_normal();
    job.scene = formats::toml_value<std::string>(file, *j, "scene", "job.");
    job.frames = formats::toml_value<bool>(file, *j, "frames", "job.");
    job.first_frame = static_cast<int>(formats::toml_value<int64_t>(file, *j, "first_frame", "job."));
    job.last_frame = static_cast<int>(formats::toml_value<int64_t>(file, *j, "last_frame", "job."));
    job.tiles = static_cast<int>(formats::toml_value<int64_t>(file, *j, "tiles", "job."));
    job.sample_splits = static_cast<int>(formats::toml_value<int64_t>(file, *j, "sample_splits", "job."));
    job.spp = static_cast<int>(formats::toml_value<int64_t>(file, *j, "spp", "job."));
    job.render = formats::toml_value<std::string>(file, *j, "render", "job.");
    job.farm = formats::toml_value<std::string>(file, *j, "farm", "job.");
    job.plugins = formats::toml_value<std::string>(file, *j, "plugins", "job.");
    if (const toml::array* tasks = root["task"].as_array())
        for (const toml::node& n : *tasks) {
            const toml::table* t = n.as_table();
            if (!t)
                throw fail("a [[task]] that is not a table");
            const std::string where = fmt::format("task {}: ", job.tasks.size());
            formats::toml_check_keys(file, *t, where,
                                     {"frame", "tile", "sample_begin", "sample_end", "scene", "output"});
            RenderTask task;
            task.frame = static_cast<int>(formats::toml_value<int64_t>(file, *t, "frame", where));
            task.tile = static_cast<int>(formats::toml_value<int64_t>(file, *t, "tile", where));
            task.sample_begin = static_cast<int>(formats::toml_value<int64_t>(file, *t, "sample_begin", where));
            task.sample_end = static_cast<int>(formats::toml_value<int64_t>(file, *t, "sample_end", where));
            task.scene = formats::toml_value<std::string>(file, *t, "scene", where);
            task.output = formats::toml_value<std::string>(file, *t, "output", where);
            job.tasks.push_back(std::move(task));
        }
    if (const toml::array* merges = root["merge"].as_array())
        for (const toml::node& n : *merges) {
            const toml::table* m = n.as_table();
            if (!m)
                throw fail("a [[merge]] that is not a table");
            const std::string where = fmt::format("merge {}: ", job.merges.size());
            formats::toml_check_keys(file, *m, where, {"frame", "output", "parts"});
            FrameMerge merge;
            merge.frame = static_cast<int>(formats::toml_value<int64_t>(file, *m, "frame", where));
            merge.output = formats::toml_value<std::string>(file, *m, "output", where);
            const toml::array* parts = (*m)["parts"].as_array();
            if (!parts)
                formats::toml_fail(file, m->get("parts"), where + "parts: an array of files is required");
            for (const toml::node& p : *parts) {
                if (!p.is_string())
                    formats::toml_fail(file, &p, where + "parts: not a string");
                merge.parts.emplace_back(**p.as_string());
            }
            job.merges.push_back(std::move(merge));
        }
    if (job.tasks.empty() || job.merges.empty())
        throw fail("no tasks or no merges");
    return job;
}

}  // namespace patina::farm
