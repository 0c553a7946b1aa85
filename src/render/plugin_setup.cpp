#include "render/plugin_setup.h"

#include "core/shader_instance.h"

#include <fmt/format.h>

#include <cstdlib>

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

}  // namespace patina::render
