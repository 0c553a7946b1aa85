// Plugin discovery and loading: dlopen with RTLD_LOCAL, ABI version and symbol checks,
// duplicate shader names. DESIGN.md "The plugin ABI".
#pragma once

#include <patina/abi.h>

#include <filesystem>
#include <memory>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace patina {

/// A plugin or shader could not be loaded or found; the message names the file and the fix.
class PluginError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

/// Throw PluginError naming `file` unless `plugin_version` (major*100 + minor) is one this
/// host speaks: the same major version, a minor version no newer than the host's.
void check_abi_version(const std::filesystem::path& file, int plugin_version);

/// One shader declared by a loaded plugin.
struct LoadedShader {
    const PatinaShaderDesc* desc = nullptr;
    std::filesystem::path plugin_file;
    std::string plugin_name;
    std::string plugin_version;  ///< the plugin's own version string
    int abi_version = 0;         ///< the plugin's ABI version, major*100 + minor
};

/// The set of loaded plugins. Not copyable; unloads every plugin on destruction, so every
/// ShaderInstance made from it must be destroyed first.
class PluginRegistry {
public:
    /// `host` must outlive the registry; it is handed to every plugin's entry point.
    explicit PluginRegistry(const PatinaHost* host);
    ~PluginRegistry();
    PluginRegistry(const PluginRegistry&) = delete;
    PluginRegistry& operator=(const PluginRegistry&) = delete;

    /// Load one shared library; throws PluginError naming the file on any problem.
    void load_file(const std::filesystem::path& file);
    /// Load every *.so in a directory (sorted by name, so loading order is deterministic).
    /// A directory that does not exist is an error.
    void load_directory(const std::filesystem::path& dir);
    /// Directories from a colon-separated list such as $PATINA_PLUGIN_PATH; entries must be
    /// absolute; empty entries are skipped.
    void load_path_list(std::string_view colon_separated, std::string_view origin);

    /// The shader of that name, or nullptr.
    const LoadedShader* find(std::string_view name) const;
    /// The shader of that name, or PluginError listing what is available.
    const LoadedShader& get(std::string_view name) const;
    /// Every loaded shader, sorted by name.
    std::vector<const LoadedShader*> shaders() const;
    /// Files loaded so far, in loading order.
    std::vector<std::filesystem::path> plugin_files() const;

    const PatinaHost* host() const { return host_; }

private:
    struct Library;
    const PatinaHost* host_;
    std::vector<std::unique_ptr<Library>> libraries_;
};

}  // namespace patina
