// Where patina-render looks for plugins, in this order: the bundled plugins next to the
// executable, $PATINA_PLUGIN_PATH, --plugin-path, and the scene file's [plugins] path.
// Never the current directory or LD_LIBRARY_PATH (DESIGN.md "The plugin ABI").
#pragma once

#include "core/plugin_registry.h"

#include <filesystem>
#include <vector>

namespace patina::render {

struct PluginSearch {
    bool bundled = true;                         ///< <prefix>/lib/patina/plugins
    bool environment = true;                     ///< $PATINA_PLUGIN_PATH
    std::vector<std::filesystem::path> command_line;  ///< --plugin-path, in order
    std::vector<std::filesystem::path> scene;         ///< from the scene, already absolute
};

/// The folder of the plugins shipped with Patina, relative to the running executable.
std::filesystem::path bundled_plugin_dir();

/// Load every plugin `search` names into `registry`; throws PluginError on the first problem.
void load_plugins(PluginRegistry& registry, const PluginSearch& search);

/// The `--list-shaders` text: every shader, its kind, plugin file and parameters.
std::string list_shaders(const PluginRegistry& registry);

}  // namespace patina::render
