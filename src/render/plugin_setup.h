// Where patina-render looks for plugins, in this order: the bundled plugins next to the
// executable, $PATINA_PLUGIN_PATH, --plugin-path, and the scene file's [plugins] path.
// Never the current directory or LD_LIBRARY_PATH (DESIGN.md "The plugin ABI").
//
// A plugin is native code: a scene that names plugin folders could run anything on the
// machine that renders it (on a farm, anyone who can submit a scene). Like Blender's
// "auto-run scripts" switch, scene-declared folders are refused unless the user allows
// them: --allow-scene-plugins, or the folder lies in one the trust file lists:
//
//   # $PATINA_CONFIG_DIR/trust.toml (default: $XDG_CONFIG_HOME/patina, ~/.config/patina)
//   scene_plugin_dirs = ["/studio/patina/plugins"]
#pragma once

#include "host/plugin_registry.h"

#include <toml++/toml.h>

#include <filesystem>
#include <vector>

namespace patina::render {

struct PluginSearch {
    bool bundled = true;                         ///< <prefix>/lib/patina/plugins
    bool environment = true;                     ///< $PATINA_PLUGIN_PATH
    std::vector<std::filesystem::path> command_line;  ///< --plugin-path, in order
    std::vector<std::filesystem::path> scene;         ///< from the scene, already absolute
    bool allow_scene_plugins = false;            ///< --allow-scene-plugins
};

/// The trust file: $PATINA_CONFIG_DIR/trust.toml, else $XDG_CONFIG_HOME/patina/trust.toml,
/// else ~/.config/patina/trust.toml (empty when none of those can be formed).
std::filesystem::path trust_file_path();

/// The folders the trust file lists under scene_plugin_dirs (absolute, canonical); none
/// when there is no trust file. Throws PluginError naming the file and line when it does
/// not parse or lists a relative folder.
std::vector<std::filesystem::path> trusted_scene_plugin_dirs();

/// Throws PluginError (at `where`, the scene's [plugins] path) unless every folder of
/// `dirs` may be loaded: search.allow_scene_plugins, or the folder lies in a trusted one.
void check_scene_plugins(const std::vector<std::filesystem::path>& dirs, const std::string& where,
                         const PluginSearch& search);

/// The folder of the plugins shipped with Patina, relative to the running executable.
std::filesystem::path bundled_plugin_dir();

/// Load every plugin `search` names into `registry`; throws PluginError on the first problem.
void load_plugins(PluginRegistry& registry, const PluginSearch& search);

/// The plugins that provide the shaders `scene` declares ([[shader]] type), sorted by name
/// and joined by "; ": "name version ABI a.b fingerprint" (core/file_fingerprint.h of the
/// plugin file). Renders record it (patina:plugins) and farm jobs compare it, so that the
/// parts of a frame come from the same plugins. A type no plugin provides is skipped (the
/// scene's build reports it).
std::string scene_plugin_set(const toml::table& scene, const PluginRegistry& registry);

/// The `--list-shaders` text: every shader, its kind, plugin file and parameters.
std::string list_shaders(const PluginRegistry& registry);
/// The same as the Markdown shader reference, docs/shaders.md: one section per shader with
/// its kind, plugin, help and parameter table, in the registry's order. Nothing of the
/// machine in it (the plugin's name, not its path), so that the file can be committed.
std::string list_shaders_markdown(const PluginRegistry& registry);

}  // namespace patina::render
