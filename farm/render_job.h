// A render as a farm job: the tasks (one per frame × tile × sample range) with the
// patina-render arguments and output of each, and a merge per frame. Written to and read
// from the job folder's job.toml (docs/farm.md "The job folder"), the one reader and
// writer of that file.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace patina::farm {

struct RenderTask {
    int frame = 0;
    int tile = 0;                 ///< band index of `tiles`
    int sample_begin = 0, sample_end = 0;
    std::filesystem::path scene;  ///< this frame's scene file
    std::filesystem::path output; ///< the part, relative to the job folder
};

struct FrameMerge {
    int frame = 0;
    std::filesystem::path output;              ///< relative to the job folder
    std::vector<std::filesystem::path> parts;  ///< relative to the job folder
};

struct RenderJob {
    std::filesystem::path folder;      ///< the job folder (absolute)
    std::filesystem::path scene;       ///< the scene (absolute; '#' runs are the frame)
    int first_frame = 0, last_frame = 0;
    bool frames = false;               ///< the scene path holds '#': one scene per frame
    int tiles = 1, sample_splits = 1, spp = 0;
    std::filesystem::path render, farm;  ///< the programs' absolute paths, as submitted
    /// The plugins of the scene's shaders where it was submitted (scene_plugin_set): every
    /// part must have been rendered with them.
    std::string plugins;
    std::vector<RenderTask> tasks;
    std::vector<FrameMerge> merges;
};

struct RenderJobOptions {
    std::filesystem::path scene, folder;
    std::string frames;      ///< "" or "A-B"
    int tiles = 1, sample_splits = 1;
    int spp = 0;             ///< total samples per pixel (needed with sample_splits > 1)
};

/// Plans the tasks of a render: for every frame, `tiles` bands × `sample_splits` ranges of
/// [0, spp). Throws std::invalid_argument naming the option for a split that leaves a task
/// without rows or samples, or a scene (a frame's scene) that does not exist.
RenderJob plan_render_job(const RenderJobOptions& options, const std::filesystem::path& render,
                          const std::filesystem::path& farm);

/// job.toml's text, and the job read back from `folder`/job.toml (throws naming the file
/// and line for a malformed one).
std::string render_job_text(const RenderJob& job);
RenderJob read_render_job(const std::filesystem::path& folder);

}  // namespace patina::farm
