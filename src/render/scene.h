// Scene files (TOML): plugins, shader instances, objects, camera, environment, film and
// output. The format is described in docs/scene-format.md.
#pragma once

#include "render/camera.h"
#include "render/light_sampler.h"

#include "core/embree_scene.h"
#include "host/host.h"
#include "core/mesh.h"
#include "host/plugin_registry.h"
#include "host/shader_instance.h"

#include <toml++/toml.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace patina::render {

struct FilmSettings {
    int width = 320;
    int height = 240;
    int spp = 16;
    uint64_t seed = 0;
    int max_depth = 8;
    int wavelengths = 4;  ///< hero-wavelength samples per path
    bool aov_albedo = false;  ///< first-hit albedo (albedo.R/G/B)
    bool aov_normal = false;  ///< first-hit world shading normal (N.X/Y/Z)
    bool aov_depth = false;   ///< first-hit distance along the camera ray (Z)
    bool mis = true;          ///< light sampling + BSDF sampling with MIS; false: BSDF only
    /// The largest radiance (any wavelength) light scattered more than once may add to a
    /// path; 0: no limit (path_common.h, clamp_indirect).
    float clamp_indirect = 0.0f;
};

struct OutputSettings {
    std::filesystem::path exr;  ///< scene-linear EXR in the working space
    std::string display = "sRGB";
    std::string view = "ACES 1.0 - SDR Video";
    bool png = true;            ///< also write <exr stem>.png through display/view
    bool half = false;          ///< EXR pixels as half instead of float
};

/// A surface: its triangles in Embree, its BSDF and optional emitter.
struct SceneObject {
    std::string label;                        ///< for messages: "object 2 (sphere)"
    std::shared_ptr<ShaderInstance> bsdf;     ///< may be null: a pure emitter / black
    std::shared_ptr<ShaderInstance> emitter;  ///< may be null
    /// The medium inside the (closed) mesh, or null. With no bsdf the boundary is
    /// index-matched: rays pass straight through it into and out of the medium.
    std::shared_ptr<ShaderInstance> interior;
};

/// The first phase of loading: the parsed file and the plugin folders it names, so the
/// caller can load plugins before shaders are bound.
struct SceneFile {
    std::filesystem::path path;
    toml::table root;
    std::vector<std::filesystem::path> plugin_dirs;  ///< absolute
    std::string plugins_where;  ///< "file:line:col" of [plugins] path, for messages
};

SceneFile parse_scene_file(const std::filesystem::path& path);

struct Scene {
    FilmSettings film;
    OutputSettings output;
    Camera camera;
    LightSampler lights;               ///< environment, sun and emissive meshes
    std::map<std::string, std::shared_ptr<ShaderInstance>> shaders;
    std::vector<SceneObject> objects;
    std::vector<int> mesh_object;      ///< Embree geometry id -> index into objects
    std::unique_ptr<EmbreeScene> geometry;
    bool has_media = false;            ///< some object has an interior medium
    /// [render] robust: Embree's RTC_SCENE_FLAG_ROBUST (see EmbreeScene's constructor).
    bool robust_traversal = true;
    /// [render] sample_uniform_sky: light-sample a constant environment too (over the
    /// sphere, with MIS); by default BSDF sampling alone finds it (light_sampler.h).
    bool sample_uniform_sky = false;
};

/// Second phase: bind shaders through `registry`, build meshes and the Embree scene.
Scene build_scene(const SceneFile& file, const PluginRegistry& registry, const Host& host);

}  // namespace patina::render
