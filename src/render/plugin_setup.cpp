#include "render/plugin_setup.h"

#include "formats/toml_location.h"

#include "core/file_fingerprint.h"
#include "core/one_line.h"
#include "host/shader_instance.h"

#include <fmt/format.h>
#include <toml++/toml.h>

#include <cstdlib>
#include <map>

namespace patina::render {

namespace fs = std::filesystem;

fs::path bundled_plugin_dir()
{
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (ec)
        return {};
    return (exe.parent_path().parent_path() / PATINA_PLUGIN_RELDIR).lexically_normal();
}

fs::path trust_file_path()
{
    if (const char* dir = std::getenv("PATINA_CONFIG_DIR"); dir && *dir)
        return fs::path(dir) / "trust.toml";
    if (const char* xdg = std::getenv("XDG_CONFIG_HOME"); xdg && *xdg)
        return fs::path(xdg) / "patina" / "trust.toml";
    if (const char* home = std::getenv("HOME"); home && *home)
        return fs::path(home) / ".config" / "patina" / "trust.toml";
    return {};
}

std::vector<fs::path> trusted_scene_plugin_dirs()
{
    const fs::path file = trust_file_path();
    std::error_code ec;
    if (file.empty() || !fs::exists(file, ec))
        return {};
    toml::table root;
    try {
        root = formats::parse_toml_file(file);
    } catch (const std::runtime_error& e) {
        throw PluginError(e.what());
    }
    std::vector<fs::path> dirs;
    const toml::node* list = root.get("scene_plugin_dirs");
    if (!list)
        return dirs;
    auto fail = [&](const toml::node& node, const std::string& what) {
        throw PluginError(formats::toml_where(file, &node) + ": " + what);
    };
    const toml::array* a = list->as_array();
    if (!a)
        fail(*list, "scene_plugin_dirs must be an array of absolute folder names");
    for (const toml::node& e : *a) {
        const auto* text = e.as_string();
        if (!text || !fs::path(text->get()).is_absolute())
            fail(e, "scene_plugin_dirs entries must be absolute folder names");
        dirs.push_back(fs::weakly_canonical(fs::path(text->get()), ec));
    }
    return dirs;
}

namespace {

    /// `dir` is `root` or lies below it (both canonical).
    bool lies_in(const fs::path& dir, const fs::path& root)
    {
        auto d = dir.begin();
        for (auto r = root.begin(); r != root.end(); ++r, ++d)
            if (d == dir.end() || *d != *r)
                return r->empty();  // a trailing separator of root
        return true;
    }

}  // namespace

void check_scene_plugins(const std::vector<fs::path>& dirs, const std::string& where,
                         const PluginSearch& search)
{
    if (dirs.empty() || search.allow_scene_plugins)
        return;
    const std::vector<fs::path> trusted = trusted_scene_plugin_dirs();
    for (const fs::path& dir : dirs) {
        std::error_code ec;
        const fs::path canonical = fs::weakly_canonical(dir, ec);
        bool ok = false;
        for (const fs::path& root : trusted)
            ok = ok || lies_in(canonical, root);
        if (!ok)
            throw PluginError(fmt::format(
                "{}: [plugins] path names '{}': plugins are native code, and a scene may not "
                "load them unless allowed; pass --allow-scene-plugins for a scene you trust, or "
                "list the folder under scene_plugin_dirs in {}",
                where, one_line(dir.string()),
                trust_file_path().empty() ? std::string("the trust file")
                                          : trust_file_path().string()));
    }
}

void load_plugins(PluginRegistry& registry, const PluginSearch& search)
{
    if (search.bundled) {
        // A missing bundled folder is not an error: the tool may run from an odd place,
        // and the user may point at plugins explicitly.
        const fs::path dir = bundled_plugin_dir();
        std::error_code ec;
        if (!dir.empty() && fs::is_directory(dir, ec))
            registry.load_directory(dir);
    }
    if (search.environment)
        if (const char* env = std::getenv("PATINA_PLUGIN_PATH"))
            registry.load_path_list(env, "PATINA_PLUGIN_PATH");
    for (const fs::path& dir : search.command_line) {
        try {
            registry.load_directory(fs::absolute(dir));
        } catch (const PluginError& e) {
            throw PluginError(fmt::format("--plugin-path: {}", e.what()));
        }
    }
    for (const fs::path& dir : search.scene)
        registry.load_directory(dir);
}

namespace {
    const char* kind_name(PatinaShaderKind k)
    {
        switch (k) {
        case PATINA_SHADER_BSDF: return "bsdf";
        case PATINA_SHADER_MEDIUM: return "medium";
        case PATINA_SHADER_EMITTER: return "emitter";
        case PATINA_SHADER_TEXTURE: return "texture";
        }
        return "?";
    }
}  // namespace

std::string list_shaders(const PluginRegistry& registry)
{
    std::string out;
    const auto shaders = registry.shaders();
    if (shaders.empty())
        return "no shaders found (set PATINA_PLUGIN_PATH or pass --plugin-path)\n";
    for (const LoadedShader* s : shaders) {
        out += fmt::format("{} ({}) from {} [{}]\n", s->desc->name, kind_name(s->desc->kind),
                           s->plugin_file.string(), s->plugin_name);
        if (s->desc->help && *s->desc->help)
            out += fmt::format("    {}\n", s->desc->help);
        out += describe_shader(*s->desc);
        out += "\n";
    }
    return out;
}

std::string list_shaders_markdown(const PluginRegistry& registry)
{
    std::string out =
        "# Shader reference\n\n"
        "Every shader of the plugins shipped with Patina, with its parameters as the plugin\n"
        "declares them. Generated by `patina-render --list-shaders --format markdown`; a test\n"
        "(`cli.shader_reference`) fails when this file and the plugins differ. Parameter\n"
        "types and scene syntax: [scene-format.md](scene-format.md).\n";
    for (const LoadedShader* s : registry.shaders()) {
        out += fmt::format("\n## `{}`\n\nKind `{}`, plugin `{}`.", s->desc->name,
                           kind_name(s->desc->kind), s->plugin_name);
        if (s->desc->help && *s->desc->help)
            out += fmt::format(" {}", s->desc->help);
        out += "\n\n" + describe_shader_markdown(*s->desc);
    }
    return out;
}

std::string scene_plugin_set(const toml::table& scene, const PluginRegistry& registry)
{
    std::map<std::string, std::string> lines;  // by plugin name: sorted, each once
    if (const toml::array* shaders = scene["shader"].as_array())
        for (const toml::node& node : *shaders) {
            const toml::table* t = node.as_table();
            const std::string type = t ? (*t)["type"].value_or(std::string()) : std::string();
            const LoadedShader* shader = registry.find(type);
            if (!shader || lines.count(shader->plugin_name))
                continue;
            lines[shader->plugin_name] = fmt::format(
                "{} {} ABI {}.{} {}", shader->plugin_name,
                shader->plugin_version.empty() ? "-" : shader->plugin_version,
                shader->abi_version / 100, shader->abi_version % 100,
                file_fingerprint(shader->plugin_file));
        }
    std::string out;
    for (const auto& [name, line] : lines)
        out += (out.empty() ? "" : "; ") + line;
    return out;
}

}  // namespace patina::render
