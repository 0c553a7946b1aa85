#include "render/scene.h"

#include "render/area_light.h"
#include "render/distant_light.h"
#include "render/environment_light.h"

#include "core/color_management.h"

#include <fmt/format.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <stdexcept>

namespace patina::render {

namespace fs = std::filesystem;

namespace {

    // Every message names the file and line: "<file>:<line>:<col>: <what>".
    struct Where {
        const fs::path& file;

        [[noreturn]] void fail(const toml::node* node, std::string_view what) const
        {
            std::string at = file.string();
            if (node && node->source().begin)
                at += fmt::format(":{}:{}", node->source().begin.line, node->source().begin.column);
            throw std::runtime_error(fmt::format("{}: {}", at, what));
        }

        // Unknown keys are errors: a misspelt setting must not silently fall back.
        void check_keys(const toml::table& t, std::string_view table,
                        std::initializer_list<std::string_view> allowed) const
        {
            for (auto&& [k, v] : t)
                if (std::find(allowed.begin(), allowed.end(), k.str()) == allowed.end()) {
                    std::string list;
                    for (auto a : allowed)
                        list += (list.empty() ? "" : ", ") + std::string(a);
                    fail(&v, fmt::format("unknown key '{}' in [{}] (allowed: {})", k.str(), table, list));
                }
        }

        double number(const toml::table& t, std::string_view key, double def, double lo,
                      double hi, std::string_view table) const
        {
            const toml::node* n = t.get(key);
            if (!n)
                return def;
            if (!n->is_number())
                fail(n, fmt::format("[{}] {} must be a number", table, key));
            const double v = *n->value<double>();
            if (!(v >= lo && v <= hi))
                fail(n, fmt::format("[{}] {} = {} is outside [{}, {}]", table, key, v, lo, hi));
            return v;
        }

        int integer(const toml::table& t, std::string_view key, int def, int lo, int hi,
                    std::string_view table) const
        {
            const toml::node* n = t.get(key);
            if (!n)
                return def;
            if (!n->is_integer())
                fail(n, fmt::format("[{}] {} must be an integer", table, key));
            const int64_t v = **n->as_integer();
            if (v < lo || v > hi)
                fail(n, fmt::format("[{}] {} = {} is outside [{}, {}]", table, key, v, lo, hi));
            return static_cast<int>(v);
        }

        Imath::V3f vec3(const toml::table& t, std::string_view key, Imath::V3f def,
                        std::string_view table) const
        {
            const toml::node* n = t.get(key);
            if (!n)
                return def;
            const toml::array* a = n->as_array();
            if (!a || a->size() != 3)
                fail(n, fmt::format("[{}] {} must be an array of 3 numbers", table, key));
            Imath::V3f v;
            for (size_t i = 0; i < 3; ++i) {
                const toml::node* e = a->get(i);
                if (!e->is_number())
                    fail(e, fmt::format("[{}] {} must be an array of 3 numbers", table, key));
                v[static_cast<int>(i)] = static_cast<float>(*e->value<double>());
                if (!std::isfinite(v[static_cast<int>(i)]))
                    fail(e, fmt::format("[{}] {} is not finite", table, key));
            }
            return v;
        }

        std::string string(const toml::table& t, std::string_view key, std::string def,
                           std::string_view table) const
        {
            const toml::node* n = t.get(key);
            if (!n)
                return def;
            if (!n->is_string())
                fail(n, fmt::format("[{}] {} must be a string", table, key));
            return **n->as_string();
        }

        const toml::table* table(const toml::table& root, std::string_view key) const
        {
            const toml::node* n = root.get(key);
            if (n && !n->is_table())
                fail(n, fmt::format("'{}' must be a table ([{}])", key, key));
            return n ? n->as_table() : nullptr;
        }
    };

    const toml::table kEmpty;

    // A colour in `space` (any colour space of the config) as working-space RGB.
    Imath::V3f working_rgb(const Where& w, const toml::table& t, std::string_view table,
                           const Host& host)
    {
        Imath::V3f rgb = w.vec3(t, "color", {1, 1, 1}, table);
        const std::string space = w.string(t, "colorspace", "scene_linear", table);
        if (!host.colors().has_colorspace(space))
            w.fail(t.get("colorspace"), fmt::format("unknown colour space '{}' in OCIO config '{}'",
                                                    space, host.colors().config_path().string()));
        if (space != "scene_linear" && space != host.colors().working_space())
            host.colors().convert(space, host.colors().working_space(), &rgb[0], 1);
        for (int i = 0; i < 3; ++i)
            if (!(rgb[i] >= 0.0f))
                w.fail(t.get("color"), fmt::format("[{}] color must not be negative", table));
        return rgb;
    }

    // [environment]: a lat-long map (file, colorspace, rotation_deg) or a uniform colour.
    void add_environment(const Where& w, const toml::table& root, const fs::path& base_dir,
                         const Host& host, std::vector<std::unique_ptr<Light>>& lights)
    {
        const toml::table* env = w.table(root, "environment");
        if (!env)
            return;
        w.check_keys(*env, "environment", {"color", "colorspace", "intensity", "file", "rotation_deg"});
        const float intensity = static_cast<float>(w.number(*env, "intensity", 1, 0, 1e30, "environment"));
        const std::string file = w.string(*env, "file", "", "environment");
        if (file.empty()) {
            if (env->get("rotation_deg"))
                w.fail(env->get("rotation_deg"), "[environment] rotation_deg needs a map 'file'");
            const Imath::V3f rgb = working_rgb(w, *env, "environment", host);
            lights.push_back(std::make_unique<EnvironmentLight>(
                host, std::array<float, 3>{rgb.x, rgb.y, rgb.z}, intensity));
            return;
        }
        if (env->get("color"))
            w.fail(env->get("color"), "[environment] takes a 'file' or a 'color', not both");
        const fs::path path = fs::path(file).is_relative() ? base_dir / file : fs::path(file);
        const std::string space = w.string(*env, "colorspace", "scene_linear", "environment");
        const float rotation =
            static_cast<float>(w.number(*env, "rotation_deg", 0, -1e6, 1e6, "environment"));
        try {
            lights.push_back(std::make_unique<EnvironmentLight>(host, path, space, intensity, rotation));
        } catch (const std::exception& e) {
            w.fail(env->get("file"), e.what());
        }
    }

    // [sun]: a distant light towards `direction` (or elevation/azimuth), with an angular
    // diameter, a colour and the irradiance it gives a perpendicular surface.
    void add_sun(const Where& w, const toml::table& root, const Host& host,
                 std::vector<std::unique_ptr<Light>>& lights)
    {
        const toml::table* sun = w.table(root, "sun");
        if (!sun)
            return;
        w.check_keys(*sun, "sun", {"direction", "elevation_deg", "azimuth_deg",
                                   "angular_diameter_deg", "color", "colorspace", "irradiance"});
        Imath::V3f dir;
        if (sun->get("direction")) {
            if (sun->get("elevation_deg") || sun->get("azimuth_deg"))
                w.fail(sun->get("direction"), "[sun] takes 'direction' or elevation/azimuth, not both");
            dir = w.vec3(*sun, "direction", {0, 1, 0}, "sun");
            if (dir.length() <= 0.0f)
                w.fail(sun->get("direction"), "[sun] direction must not be zero");
            dir.normalize();
        } else {
            // Azimuth clockwise from north (-z) towards east (+x), elevation above the horizon.
            const double el = w.number(*sun, "elevation_deg", 45, -90, 90, "sun") * M_PI / 180.0;
            const double az = w.number(*sun, "azimuth_deg", 180, -360, 360, "sun") * M_PI / 180.0;
            dir = Imath::V3f(static_cast<float>(std::cos(el) * std::sin(az)),
                             static_cast<float>(std::sin(el)),
                             static_cast<float>(-std::cos(el) * std::cos(az)));
        }
        const float diameter =
            static_cast<float>(w.number(*sun, "angular_diameter_deg", 0.53, 0, 90, "sun"));
        const float irradiance = static_cast<float>(w.number(*sun, "irradiance", 1, 0, 1e30, "sun"));
        const Imath::V3f rgb = working_rgb(w, *sun, "sun", host);
        lights.push_back(std::make_unique<DistantLight>(dir, diameter, host.uplift(&rgb[0], true),
                                                        irradiance));
    }

}  // namespace

SceneFile parse_scene_file(const fs::path& path)
{
    SceneFile file;
    file.path = path;
    std::error_code ec;
    if (!fs::is_regular_file(path, ec))
        throw std::runtime_error(fmt::format("scene file '{}' does not exist", path.string()));
    try {
        file.root = toml::parse_file(path.string());
    } catch (const toml::parse_error& e) {
        throw std::runtime_error(fmt::format("{}:{}:{}: {}", path.string(), e.source().begin.line,
                                             e.source().begin.column, e.description()));
    }
    const Where w{file.path};
    w.check_keys(file.root, "scene", {"plugins", "film", "camera", "environment", "sun", "output",
                                      "shader", "object"});
    if (const toml::table* p = w.table(file.root, "plugins")) {
        w.check_keys(*p, "plugins", {"path"});
        if (const toml::node* list = p->get("path")) {
            const toml::array* a = list->as_array();
            if (!a)
                w.fail(list, "[plugins] path must be an array of folder names");
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
    const Where w{file.path};
    const toml::table& root = file.root;
    const fs::path base_dir = fs::absolute(file.path).parent_path();
    Scene scene;

    // Film
    const toml::table& film = w.table(root, "film") ? *w.table(root, "film") : kEmpty;
    w.check_keys(film, "film", {"width", "height", "spp", "seed", "max_depth", "wavelengths",
                                "aovs", "integrator"});
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
    auto shader_ref = [&](const toml::table& t, std::string_view key,
                          PatinaShaderKind kind) -> std::shared_ptr<ShaderInstance> {
        const toml::node* n = t.get(key);
        if (!n)
            return nullptr;
        if (!n->is_string())
            w.fail(n, fmt::format("'{}' must name a [[shader]]", key));
        auto it = scene.shaders.find(std::string(**n->as_string()));
        if (it == scene.shaders.end())
            w.fail(n, fmt::format("no [[shader]] named '{}'", **n->as_string()));
        if (it->second->kind() != kind)
            w.fail(n, fmt::format("shader '{}' ({}) cannot be used as '{}'", it->first,
                                  it->second->desc().name, key));
        return it->second;
    };

    // Objects: built-in shapes or mesh files, each with a bsdf and/or an emitter.
    scene.geometry = std::make_unique<EmbreeScene>();
    if (const toml::node* n = root.get("object")) {
        const toml::array* list = n->as_array();
        if (!list || !list->is_array_of_tables())
            w.fail(n, "'object' must be an array of tables ([[object]])");
        for (const toml::node& e : *list) {
            const toml::table& t = *e.as_table();
            w.check_keys(t, "object", {"shape", "mesh", "center", "radius", "size", "bsdf", "emitter"});
            SceneObject obj;
            obj.bsdf = shader_ref(t, "bsdf", PATINA_SHADER_BSDF);
            obj.emitter = shader_ref(t, "emitter", PATINA_SHADER_EMITTER);
            std::vector<TriangleMesh> meshes;
            const std::string shape = w.string(t, "shape", "", "object");
            const std::string mesh = w.string(t, "mesh", "", "object");
            if (shape.empty() == mesh.empty())
                w.fail(&e, "[[object]] needs exactly one of 'shape' or 'mesh'");
            const Imath::V3f center = w.vec3(t, "center", {0, 0, 0}, "object");
            if (shape == "sphere") {
                const float r = static_cast<float>(w.number(t, "radius", 1, 1e-6, 1e9, "object"));
                meshes.push_back(make_uv_sphere(center, r, 64, 128));
            } else if (shape == "plane") {
                const float s = static_cast<float>(w.number(t, "size", 10, 1e-6, 1e9, "object"));
                meshes.push_back(make_plane(center, s));
            } else if (!shape.empty()) {
                w.fail(t.get("shape"), fmt::format("unknown shape '{}' (sphere, plane)", shape));
            } else {
                const fs::path p = fs::path(mesh).is_relative() ? base_dir / mesh : fs::path(mesh);
                try {
                    meshes = load_meshes(p);
                } catch (const std::exception& ex) {
                    w.fail(t.get("mesh"), ex.what());
                }
            }
            obj.label = fmt::format("object {} ({})", scene.objects.size(), shape.empty() ? mesh : shape);
            for (const TriangleMesh& m : meshes) {
                const int id = scene.geometry->add_mesh(m);
                if (static_cast<int>(scene.mesh_object.size()) <= id)
                    scene.mesh_object.resize(static_cast<size_t>(id) + 1, -1);
                scene.mesh_object[static_cast<size_t>(id)] = static_cast<int>(scene.objects.size());
            }
            scene.objects.push_back(std::move(obj));
        }
    }
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
    scene.lights = LightSampler(std::move(lights));
    return scene;
}

}  // namespace patina::render
