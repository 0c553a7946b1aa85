// [[object]] of a scene file: shapes and meshes, transforms, shader bindings.
#include "render/scene_parts.h"

#include "core/mesh.h"
#include "core/progress.h"

#include <Imath/ImathMatrix.h>

#include <cmath>
#include <stdexcept>
#include <map>
#include <set>

namespace patina::render {

namespace fs = std::filesystem;

namespace {

    // The [[shader]] a key names, checked to be of the expected kind.
    std::shared_ptr<ShaderInstance> shader_named(const TomlReader& w, const Scene& scene,
                                                 const toml::node* n, std::string_view key,
                                                 PatinaShaderKind kind)
    {
        if (!n)
            return nullptr;
        if (!n->is_string())
            w.fail(n, fmt::format("'{}' must name a [[shader]]", key));
        const std::string name(**n->as_string());
        auto it = scene.shaders.find(name);
        if (it == scene.shaders.end())
            w.fail(n, fmt::format("no [[shader]] named '{}'", name));
        if (it->second->kind() != kind)
            w.fail(n, fmt::format("shader '{}' ({}) cannot be used as '{}'", it->first,
                                  it->second->desc().name, key));
        return it->second;
    }

    // transform = { scale = s or [sx, sy, sz], rotate_deg = [rx, ry, rz], translate = [...] }:
    // scale, then rotations about x, y and z, then translation (row vectors, p' = p M).
    Imath::M44f read_transform(const TomlReader& w, const toml::table& object)
    {
        Imath::M44f m;
        const toml::node* n = object.get("transform");
        if (!n)
            return m;
        const toml::table* t = n->as_table();
        if (!t)
            w.fail(n, "[[object]] transform must be a table { scale, rotate_deg, translate }");
        w.check_keys(*t, "object.transform", {"scale", "rotate_deg", "translate"});
        Imath::V3f scale(1, 1, 1);
        if (const toml::node* s = t->get("scale"); s && s->is_number())
            scale = Imath::V3f(static_cast<float>(*s->value<double>()));
        else if (s)
            scale = w.vec3(*t, "scale", scale, "object.transform");
        if (scale.x == 0 || scale.y == 0 || scale.z == 0)
            w.fail(t->get("scale"), "[[object]] transform scale must not be zero");
        const Imath::V3f rot = w.vec3(*t, "rotate_deg", {0, 0, 0}, "object.transform") *
                               static_cast<float>(M_PI / 180.0);
        const Imath::V3f tr = w.vec3(*t, "translate", {0, 0, 0}, "object.transform");
        Imath::M44f S, Rx, Ry, Rz, T;
        S.setScale(scale);
        Rx.setAxisAngle(Imath::V3f(1, 0, 0), rot.x);
        Ry.setAxisAngle(Imath::V3f(0, 1, 0), rot.y);
        Rz.setAxisAngle(Imath::V3f(0, 0, 1), rot.z);
        T.setTranslation(tr);
        return S * Rx * Ry * Rz * T;
    }

    void apply_transform(TriangleMesh& mesh, const Imath::M44f& m)
    {
        for (Imath::V3f& p : mesh.positions)
            p = p * m;
        // Normals by the inverse transpose, so non-uniform scales keep them perpendicular.
        const Imath::M44f n = m.inverse().transposed();
        for (Imath::V3f& v : mesh.normals) {
            Imath::V3f t;
            n.multDirMatrix(v, t);
            v = t.length() > 0 ? t.normalized() : t;
        }
        // A mirroring transform turns the winding inside out: keep it consistent.
        if (m.determinant() < 0)
            for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3)
                std::swap(mesh.indices[i + 1], mesh.indices[i + 2]);
    }

    /// `up = "z"` and `unit = "cm"` (or a number of metres per unit): the axes and unit of
    /// the object's mesh file where they differ from what the file declares; `uv_set = 1`:
    /// the uv set its textures are looked up in (a stack baked with --uv-set 1).
    MeshConventionOptions read_convention(const TomlReader& w, const toml::table& t)
    {
        MeshConventionOptions c;
        if (const toml::node* up = t.get("up")) {
            const auto text = up->value<std::string>();
            if (!text)
                w.fail(up, "'up' must be a string: x, y, z, -x, -y or -z");
            try {
                c.up = parse_axis(*text, "up");
            } catch (const std::invalid_argument& e) {
                w.fail(up, e.what());
            }
        }
        if (const toml::node* unit = t.get("unit")) {
            if (const auto text = unit->value<std::string>()) {
                try {
                    c.metres_per_unit = parse_unit(*text, "unit");
                } catch (const std::invalid_argument& e) {
                    w.fail(unit, e.what());
                }
            } else if (const auto metres = unit->value<double>();
                       metres && *metres > 0 && std::isfinite(*metres)) {
                c.metres_per_unit = *metres;
            } else {
                w.fail(unit, "'unit' must be a unit name (m, cm, mm, in, ft, ...) or the metres "
                             "per unit, a number > 0");
            }
        }
        if (const toml::node* set = t.get("uv_set")) {
            const auto index = set->value<int64_t>();
            if (!index || *index < 0 || *index > 7)
                w.fail(set, "'uv_set' must be a uv set of the mesh file, 0 (its first) to 7");
            c.uv_set = static_cast<int>(*index);
        }
        return c;
    }

    std::vector<TriangleMesh> read_geometry(const TomlReader& w, const toml::table& t,
                                            const fs::path& base_dir)
    {
        const std::string shape = w.string(t, "shape", "", "object");
        const std::string mesh = w.string(t, "mesh", "", "object");
        if (shape.empty() == mesh.empty())
            w.fail(&t, "[[object]] needs exactly one of 'shape' or 'mesh'");
        const Imath::M44f m = read_transform(w, t);
        std::vector<TriangleMesh> meshes;
        if (!mesh.empty()) {
            const fs::path p = fs::path(mesh).is_relative() ? base_dir / mesh : fs::path(mesh);
            const MeshConventionOptions convention = read_convention(w, t);
            try {
                MeshConvention applied;
                meshes = load_meshes(p, convention, &applied, m);
                for (const std::string& warning : applied.warnings)
                    print_warning("patina-render", fmt::format("mesh file '{}': {}", p.string(),
                                                               warning));
                return meshes;
            } catch (const std::exception& ex) {
                w.fail(t.get("mesh"), ex.what());
            }
        }
        for (const char* key : {"up", "unit", "uv_set"})
            if (t.contains(key))
                w.fail(t.get(key), "'up', 'unit' and 'uv_set' describe a mesh file; a shape is "
                                   "in metres, +Y up, with one uv set");
        const Imath::V3f center = w.vec3(t, "center", {0, 0, 0}, "object");
        if (shape == "sphere") {
            const float r = static_cast<float>(w.number(t, "radius", 1, 1e-6, 1e9, "object"));
            meshes.push_back(make_uv_sphere(center, r, 64, 128));
        } else if (shape == "plane") {
            const float s = static_cast<float>(w.number(t, "size", 10, 1e-6, 1e9, "object"));
            meshes.push_back(make_plane(center, s));
        } else if (shape == "box") {
            meshes.push_back(make_box(center, w.vec3(t, "size", {1, 1, 1}, "object")));
        } else {
            w.fail(t.get("shape"), fmt::format("unknown shape '{}' (sphere, plane, box)", shape));
        }
        for (TriangleMesh& tm : meshes)
            apply_transform(tm, m);
        return meshes;
    }

}  // namespace

void add_objects(const TomlReader& w, const toml::table& root, const fs::path& base_dir,
                 Scene& scene)
{
    const toml::node* n = root.get("object");
    if (!n)
        return;
    const toml::array* list = n->as_array();
    if (!list || !list->is_array_of_tables())
        w.fail(n, "'object' must be an array of tables ([[object]])");
    for (const toml::node& e : *list) {
        const toml::table& t = *e.as_table();
        w.check_keys(t, "object", {"shape", "mesh", "center", "radius", "size", "transform",
                                   "up", "unit", "uv_set", "bsdf", "emitter", "materials", "interior"});
        const auto interior = shader_named(w, scene, t.get("interior"), "interior", PATINA_SHADER_MEDIUM);
        if (interior)
            scene.has_media = true;
        const auto bsdf = shader_named(w, scene, t.get("bsdf"), "bsdf", PATINA_SHADER_BSDF);
        const auto emitter = shader_named(w, scene, t.get("emitter"), "emitter", PATINA_SHADER_EMITTER);
        // materials = { "<mesh material name>" = "<shader>" } overrides `bsdf` per material.
        std::map<std::string, std::shared_ptr<ShaderInstance>> by_material;
        if (const toml::node* mats = t.get("materials")) {
            const toml::table* mt = mats->as_table();
            if (!mt)
                w.fail(mats, "[[object]] materials must be a table { \"material\" = \"shader\" }");
            for (auto&& [name, shader] : *mt)
                by_material[std::string(name.str())] =
                    shader_named(w, scene, &shader, "materials", PATINA_SHADER_BSDF);
        }
        const std::vector<TriangleMesh> meshes = read_geometry(w, t, base_dir);
        // A binding for a material the mesh does not have is a typo.
        std::set<std::string> materials;
        for (const TriangleMesh& m : meshes)
            materials.insert(m.material_name);
        for (const auto& [name, shader] : by_material)
            if (!materials.count(name)) {
                std::string known;
                for (const std::string& m : materials)
                    known += (known.empty() ? "'" : ", '") + m + "'";
                w.fail(t.get("materials"), fmt::format("materials: the mesh has no material named "
                                                       "'{}' (it has {})", name, known));
            }
        for (const TriangleMesh& m : meshes) {
            SceneObject obj;
            obj.emitter = emitter;
            obj.bsdf = bsdf;
            obj.interior = interior;
            if (auto it = by_material.find(m.material_name); it != by_material.end()) {
                obj.bsdf = it->second;
            } else if (!bsdf && !emitter && !interior) {
                w.fail(&e, fmt::format("mesh '{}' has material '{}', which neither 'materials' "
                                       "nor a 'bsdf' binds to a shader",
                                       m.name, m.material_name));
            }
            obj.label = fmt::format("object {} mesh '{}'", scene.objects.size(), m.name);
            const int id = scene.geometry->add_mesh(m);
            if (static_cast<int>(scene.mesh_object.size()) <= id)
                scene.mesh_object.resize(static_cast<size_t>(id) + 1, -1);
            scene.mesh_object[static_cast<size_t>(id)] = static_cast<int>(scene.objects.size());
            scene.objects.push_back(std::move(obj));
        }
    }
}

}  // namespace patina::render
