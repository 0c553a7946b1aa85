// patina-render's top level: load a scene file, load the plugins it needs, render a frame
// (or a crop or farm tile of it) in sample passes, and write the outputs.
#pragma once

#include "render/plugin_setup.h"

#include "core/cancel.h"

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace patina::render {

struct Scene;

/// A window of pixels [x0, x1) x [y0, y1) of the full frame.
struct Region {
    int x0 = 0, y0 = 0, x1 = 0, y1 = 0;
    int width() const { return x1 - x0; }
    int height() const { return y1 - y0; }
};

/// Tile `index` of `count` (0-based) of a width x height frame: horizontal bands of whole
/// rows, the first height % count bands one row taller. Throws std::invalid_argument.
Region tile_region(int index, int count, int width, int height);
/// Parse "i/n" for --tile.
std::pair<int, int> parse_tile(const std::string& text);
/// Parse "first-last" or "n" for --frames.
std::pair<int, int> parse_frames(const std::string& text);
/// Replace the run of '#' in `pattern` by `frame`, zero-padded to the run's length.
std::string substitute_frame(const std::string& pattern, int frame);

/// Command-line overrides of the scene's [film] and [output] settings.
struct RenderOptions {
    std::filesystem::path output;    ///< EXR path; empty = the scene's [output] file
    std::optional<int> spp;
    std::optional<uint64_t> seed;
    int threads = 0;                 ///< 0 = every core
    std::vector<int> resolution;     ///< {} or {width, height}
    std::vector<int> crop;           ///< {} or {x0, y0, x1, y1} in pixels
    std::string tile;                ///< "" or "i/n"
    std::string frames;              ///< "" or "first-last": '#' runs in paths become the frame
    std::optional<double> time_limit;  ///< seconds; stops after the last whole sample pass
    std::string samples;             ///< "" or "A-B": samples A..B-1 of every pixel
    bool checkpoint = false;         ///< store the film's sums in the EXR (part "sums")
    std::filesystem::path resume;    ///< continue this EXR's render (written with --checkpoint)
    bool quiet = false;
};

/// A signal stopped a render that keeps its sums (--checkpoint) after its whole passes were
/// written as a checkpoint (core/cancel.h).
using patina::CheckpointWritten;

/// Parse "A-B" for --samples: the half-open range [A, B) of sample indices, 0 <= A < B.
/// Throws std::invalid_argument naming the option.
std::pair<int, int> parse_samples(const std::string& text);

/// A film's per-pixel sums of its samples (double, in sample order): the state a render is
/// continued from (--checkpoint, --resume). Each vector is empty or 3 (1 for depth) per
/// pixel of the region.
struct FilmSums {
    std::vector<double> xyz, albedo, normal, depth;
};

/// Accumulated film of one region: per-pixel means of what was asked for.
struct FilmResult {
    Region region;
    int spp = 0;                   ///< samples per pixel actually taken
    int sample_begin = 0;          ///< the first sample's index (samples sample_begin..+spp-1)
    std::vector<float> xyz;        ///< CIE XYZ (D65), 3 per pixel
    std::vector<float> albedo_xyz; ///< first-hit albedo as XYZ under unit D65 (if asked)
    std::vector<float> normal;     ///< first-hit world shading normal (if asked)
    std::vector<float> depth;      ///< first-hit distance along the camera ray, 0 = none
    FilmSums sums;                 ///< the sums themselves, when RenderControl::keep_sums
    /// A signal stopped a render that keeps its sums: the film holds its whole passes.
    bool interrupted = false;
};

struct RenderControl {
    int threads = 0;
    bool quiet = true;
    std::optional<double> time_limit;
    /// The samples of every pixel to take, [sample_begin, sample_end); sample_end 0: the
    /// film's spp. Sample s draws from the stream of (seed, pixel, s) whatever the range, so
    /// ranges of one render are its parts.
    int sample_begin = 0, sample_end = 0;
    /// Continue from these sums of `resume_samples` samples (the ones just before
    /// sample_begin): adding the new samples to them in order gives the bits of the render
    /// that never stopped.
    const FilmSums* resume = nullptr;
    int resume_samples = 0;
    bool keep_sums = false;  ///< return the sums in FilmResult::sums
};

/// Render `region` of the scene's frame. Pixels depend only on (seed, pixel, sample index),
/// so the result is bitwise the same for any thread count, pass size or region split.
FilmResult render_region(const Scene& scene, const Region& region, const RenderControl& control);

/// Render the whole frame to interleaved CIE XYZ (D65, Y = 1 for a unit white).
std::vector<float> render_xyz(const Scene& scene, int threads, bool quiet);

/// Render `scene_file` and write its outputs (scene-linear EXR + display PNG), for every
/// frame of options.frames. Throws std::exception with a message naming the file, line
/// and key on any error; writes nothing of a frame unless its render completed.
void render_scene_file(const std::filesystem::path& scene_file, PluginSearch search,
                       const RenderOptions& options);

}  // namespace patina::render
