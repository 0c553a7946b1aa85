#include "render/scene.h"

#include "render/area_light.h"
#include "render/distant_light.h"
#include "render/environment_light.h"

#include "render/scene_parts.h"
#include "render/toml_reader.h"

#include "core/color_management.h"

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>

namespace patina::render {

namespace fs = std::filesystem;

namespace {

    const toml::table kEmpty;

}  // namespace

SceneFile parse_scene_file(const fs::path& path)
{
    SceneFile file;
    file.path = path;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw std::runtime_error(fmt::format("scene file '{}' does not exist", path.string()));
    file.root = formats::parse_toml_file(path);
    const TomlReader w{file.path};
    w.check_keys(file.root, "scene", {"plugins", "film", "render", "camera", "environment", "sun",
                                      "output", "shader", "object"});
    if (const toml::table* p = w.table(file.root, "plugins")) {
        w.check_keys(*p, "plugins", {"path"});
        if (const toml::node* list = p->get("path")) {
            const toml::array* a = list->as_array();
            if (!a)
                w.fail(list, "[plugins] path must be an array of folder names");
            file.plugins_where = formats::toml_where(path, list);
            for (const toml::node& e : *a) {
                if (!e.is_string())
                    w.fail(&e, "[plugins] path entries must be strings");
                fs::path dir(**e.as_string());
                // Relative to the scene file, never to the current directory.
                if (dir.is_relative())
                    dir = fs::absolute(path).parent_path() / dir;
                file.plugin_dirs.push_back(dir.lexically_normal());
            }
        }
    }
    return file;
}

Scene build_scene(const SceneFile& file, const PluginRegistry& registry, const Host& host)
{
    const TomlReader w{file.path};
    const toml::table& root = file.root;
    const fs::path base_dir = fs::absolute(file.path).parent_path();
    Scene scene;

    // Film
    const toml::table& film = w.table(root, "film") ? *w.table(root, "film") : kEmpty;
    w.check_keys(film, "film", {"width", "height", "spp", "seed", "max_depth", "wavelengths",
                                "aovs", "integrator", "clamp_indirect"});
    if (const std::string integ = w.string(film, "integrator", "mis", "film"); integ == "bsdf")
        scene.film.mis = false;
    else if (integ != "mis")
        w.fail(film.get("integrator"),
               fmt::format("[film] integrator '{}' must be 'mis' or 'bsdf'", integ));
    scene.film.width = w.integer(film, "width", scene.film.width, 1, 1 << 15, "film");
    scene.film.height = w.integer(film, "height", scene.film.height, 1, 1 << 15, "film");
    scene.film.spp = w.integer(film, "spp", scene.film.spp, 1, 1 << 20, "film");
    scene.film.seed = static_cast<uint64_t>(w.integer(film, "seed", 0, 0, INT32_MAX, "film"));
    scene.film.max_depth = w.integer(film, "max_depth", scene.film.max_depth, 1, 1024, "film");
    scene.film.wavelengths =
        w.integer(film, "wavelengths", scene.film.wavelengths, 1, PATINA_MAX_WAVELENGTHS, "film");
    scene.film.clamp_indirect =
        static_cast<float>(w.number(film, "clamp_indirect", 0.0, 0.0, 1e30, "film"));

    if (const toml::node* n = film.get("aovs")) {
        const toml::array* a = n->as_array();
        if (!a)
            w.fail(n, "[film] aovs must be an array of names (albedo, normal, depth)");
        for (const toml::node& e : *a) {
            const std::string name = e.value_or<std::string>("");
            if (name == "albedo")
                scene.film.aov_albedo = true;
            else if (name == "normal")
                scene.film.aov_normal = true;
            else if (name == "depth")
                scene.film.aov_depth = true;
            else
                w.fail(&e, fmt::format("unknown AOV '{}' (albedo, normal, depth)", name));
        }
    }

    // Ray tracing: Embree's robust traversal (the default) or its faster one; whether a
    // uniform sky is light-sampled as well as found by BSDF sampling.
    const toml::table& render = w.table(root, "render") ? *w.table(root, "render") : kEmpty;
    w.check_keys(render, "render", {"robust", "sample_uniform_sky"});
    scene.robust_traversal = w.boolean(render, "robust", scene.robust_traversal, "render");
    scene.sample_uniform_sky =
        w.boolean(render, "sample_uniform_sky", scene.sample_uniform_sky, "render");

    // Output
    const toml::table& out = w.table(root, "output") ? *w.table(root, "output") : kEmpty;
    w.check_keys(out, "output", {"file", "display", "view", "png", "format"});
    if (const std::string f = w.string(out, "format", "float", "output"); f == "half")
        scene.output.half = true;
    else if (f != "float")
        w.fail(out.get("format"), fmt::format("[output] format '{}' must be 'half' or 'float'", f));
    if (const std::string f = w.string(out, "file", "", "output"); !f.empty())
        scene.output.exr = fs::path(f).is_relative() ? base_dir / f : fs::path(f);
    scene.output.display = w.string(out, "display", scene.output.display, "output");
    scene.output.view = w.string(out, "view", scene.output.view, "output");
    if (const toml::node* n = out.get("png")) {
        if (!n->is_boolean())
            w.fail(n, "[output] png must be true or false");
        scene.output.png = **n->as_boolean();
    }

    // Camera
    const toml::table& cam = w.table(root, "camera") ? *w.table(root, "camera") : kEmpty;
    w.check_keys(cam, "camera", {"from", "to", "up", "fov_deg", "aperture_radius", "focus_distance"});
    try {
        scene.camera = Camera(w.vec3(cam, "from", {0, 1, 5}, "camera"),
                              w.vec3(cam, "to", {0, 0, 0}, "camera"),
                              w.vec3(cam, "up", {0, 1, 0}, "camera"),
                              static_cast<float>(w.number(cam, "fov_deg", 40, 1e-3, 179.9, "camera")),
                              static_cast<float>(scene.film.width) / scene.film.height,
                              static_cast<float>(w.number(cam, "aperture_radius", 0, 0, 1e9, "camera")),
                              static_cast<float>(w.number(cam, "focus_distance", 0, 0, 1e12, "camera")));
    } catch (const std::invalid_argument& e) {
        w.fail(&cam, e.what());
    }

    std::vector<std::unique_ptr<Light>> lights;
    add_environment(w, root, base_dir, host, lights);
    add_sun(w, root, host, lights);

    // Shaders: [[shader]] name = "...", type = "<shader>", then its parameters.
    if (const toml::node* n = root.get("shader")) {
        const toml::array* list = n->as_array();
        if (!list || !list->is_array_of_tables())
            w.fail(n, "'shader' must be an array of tables ([[shader]])");
        for (const toml::node& e : *list) {
            const toml::table& t = *e.as_table();
            const std::string name = w.string(t, "name", "", "shader");
            const std::string type = w.string(t, "type", "", "shader");
            if (name.empty() || type.empty())
                w.fail(&e, "[[shader]] needs a 'name' and a 'type' (the shader to instance)");
            if (scene.shaders.count(name))
                w.fail(t.get("name"), fmt::format("shader name '{}' is used twice", name));
            ParamSource src{file.path.string(), base_dir, {"name", "type"}};
            scene.shaders[name] = create_shader_instance(registry, type, t, name, src);
        }
    }
    // Objects: built-in shapes or mesh files, each with a bsdf and/or an emitter.
    scene.geometry = std::make_unique<EmbreeScene>(scene.robust_traversal);
    add_objects(w, root, base_dir, scene);
    scene.geometry->commit();

    // Lights at infinity compare their power with the scene's by its bounding sphere.
    if (scene.geometry->mesh_count() > 0) {
        const Imath::Box3f b = scene.geometry->bounds();
        const float radius = std::max(0.5f * (b.max - b.min).length(), 1e-6f);
        for (auto& light : lights)
            if (auto* sun = dynamic_cast<DistantLight*>(light.get()))
                sun->set_scene_radius(radius);
            else if (auto* env = dynamic_cast<EnvironmentLight*>(light.get()))
                env->set_scene_radius(radius);
    }

    // Every mesh of an object with an emitter is an area light.
    for (size_t id = 0; id < scene.mesh_object.size(); ++id) {
        const SceneObject& obj = scene.objects[static_cast<size_t>(scene.mesh_object[id])];
        if (obj.emitter)
            lights.push_back(std::make_unique<AreaLight>(*scene.geometry, static_cast<int>(id),
                                                         obj.emitter, host.c_host()));
    }
    scene.lights = LightSampler(std::move(lights), scene.sample_uniform_sky);
    return scene;
}

}  // namespace patina::render
