#include "host/plugin_registry.h"

#include "host/elf_symbol.h"

#include <fmt/format.h>

#include <dlfcn.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <optional>
#include <map>
#include <regex>

namespace patina {

namespace fs = std::filesystem;

struct PluginRegistry::Library {
    fs::path file;
    void* handle = nullptr;
    const PatinaPluginInfo* info = nullptr;
    std::vector<LoadedShader> shaders;

    ~Library()
    {
        if (handle)
            dlclose(handle);
    }
};

namespace {

    std::string version_string(int v) { return fmt::format("{}.{}", v / 100, v % 100); }

    /// An enum field as the integer the plugin stored: a value outside the enumerators must
    /// not be loaded as the enum type (undefined behaviour, which UBSan reports).
    template <class Enum>
    int raw_enum(const Enum& field)
    {
        static_assert(sizeof(Enum) == sizeof(int));
        int value = 0;
        std::memcpy(&value, &field, sizeof value);
        return value;
    }

    bool valid_identifier(const char* s)
    {
        static const std::regex kIdentifier("[a-z_][a-z0-9_]*");
        return s && std::regex_match(s, kIdentifier);
    }

    /// A parameter's range and default: what create() receives when the scene leaves the
    /// parameter out must be a value the scene itself could give.
    template <class Fail>
    void check_default(const PatinaParamDecl& p, int type, const Fail& fail)
    {
        if (std::isnan(p.min_value) || std::isnan(p.max_value) || p.min_value > p.max_value)
            fail(fmt::format("parameter '{}' has an invalid range [{}, {}]", p.name, p.min_value,
                             p.max_value));
        const int components = type == PATINA_PARAM_COLOR ? 3
                               : (type == PATINA_PARAM_FLOAT || type == PATINA_PARAM_INT ||
                                  (type == PATINA_PARAM_SPECTRUM && !p.default_spectrum))
                                   ? 1
                                   : 0;
        for (int c = 0; c < components; ++c) {
            const float v = p.default_value[c];
            if (!std::isfinite(v) || v < p.min_value || v > p.max_value)
                fail(fmt::format("parameter '{}' has default {} outside its range [{}, {}]",
                                 p.name, v, p.min_value, p.max_value));
        }
        if (type == PATINA_PARAM_INT && p.default_value[0] != std::floor(p.default_value[0]))
            fail(fmt::format("parameter '{}' is an integer with default {}", p.name,
                             p.default_value[0]));
        if (type == PATINA_PARAM_SPECTRUM && p.default_spectrum) {
            const PatinaTabulatedSpectrum& s = *p.default_spectrum;
            if (s.count < 1 || !s.lambda_nm || !s.value)
                fail(fmt::format("parameter '{}' has an empty default spectrum", p.name));
            for (int i = 0; i < s.count; ++i)
                if (!std::isfinite(s.lambda_nm[i]) || !std::isfinite(s.value[i]) ||
                    s.value[i] < p.min_value || s.value[i] > p.max_value ||
                    (i > 0 && !(s.lambda_nm[i] > s.lambda_nm[i - 1])))
                    fail(fmt::format("parameter '{}': default spectrum entry {} is invalid "
                                     "(wavelengths must ascend, values lie in [{}, {}])",
                                     p.name, i, p.min_value, p.max_value));
        }
    }

    // Checks a descriptor for the promises abi.h makes, so that a broken plugin is refused
    // at load time instead of crashing the render.
    void check_descriptor(const fs::path& file, const PatinaShaderDesc& d)
    {
        auto fail = [&](const std::string& what) {
            throw PluginError(fmt::format("plugin '{}': shader '{}': {}", file.string(),
                                          d.name ? d.name : "(null)", what));
        };
        if (!valid_identifier(d.name))
            fail("name must match [a-z_][a-z0-9_]*");
        if (!d.create || !d.destroy)
            fail("create and destroy must both be set");
        if (d.param_count < 0 || (d.param_count > 0 && !d.params))
            fail("param_count and params disagree");
        switch (raw_enum(d.kind)) {
        case PATINA_SHADER_BSDF:
            if (!d.bsdf || !d.bsdf->eval || !d.bsdf->pdf || !d.bsdf->sample)
                fail("a bsdf needs eval, pdf and sample");
            break;
        case PATINA_SHADER_MEDIUM:
            if (!d.medium || !d.medium->sample_distance || !d.medium->transmittance ||
                !d.medium->phase_eval || !d.medium->phase_sample)
                fail("a medium needs sample_distance, transmittance, phase_eval and phase_sample");
            break;
        case PATINA_SHADER_EMITTER:
            if (!d.emitter || !d.emitter->emit)
                fail("an emitter needs emit");
            break;
        case PATINA_SHADER_TEXTURE:
            if (!d.texture || !d.texture->eval)
                fail("a texture needs eval");
            break;
        default:
            fail(fmt::format("unknown kind {}", raw_enum(d.kind)));
        }
        std::vector<std::string> seen;
        for (int i = 0; i < d.param_count; ++i) {
            const PatinaParamDecl& p = d.params[i];
            if (!valid_identifier(p.name))
                fail(fmt::format("parameter {} has an invalid name", i));
            if (std::find(seen.begin(), seen.end(), p.name) != seen.end())
                fail(fmt::format("parameter '{}' is declared twice", p.name));
            seen.emplace_back(p.name);
            const int type = raw_enum(p.type);
            if (type < PATINA_PARAM_FLOAT || type > PATINA_PARAM_FILE)
                fail(fmt::format("parameter '{}' has an unknown type {}", p.name, type));
            check_default(p, type, fail);
        }
    }

}  // namespace

void check_abi_version(const fs::path& file, int plugin_version)
{
    if (plugin_version / 100 != PATINA_ABI_VERSION_MAJOR ||
        plugin_version % 100 > PATINA_ABI_VERSION_MINOR)
        throw PluginError(fmt::format(
            "plugin '{}': built for Patina plugin ABI {} but this host speaks ABI {}; "
            "rebuild the plugin against this version's patina/abi.h",
            file.string(), version_string(plugin_version), version_string(PATINA_ABI_VERSION)));
}

PluginRegistry::PluginRegistry(const PatinaHost* host) : host_(host) {}

PluginRegistry::~PluginRegistry() = default;

void PluginRegistry::load_file(const fs::path& file)
{
    std::error_code ec;
    if (!fs::is_regular_file(file, ec))
        throw PluginError(fmt::format("plugin '{}': no such file", file.string()));
    const fs::path canonical = fs::weakly_canonical(file, ec);
    for (const auto& lib : libraries_)
        if (lib->file == canonical)
            return;  // the same file through two search-path entries: load once

    // The ABI version is read from the file before dlopen, which would run the library's
    // constructors: a plugin of another ABI is refused without running any of its code.
    std::optional<int32_t> file_version;
    try {
        file_version = read_elf_int_symbol(canonical, PATINA_PLUGIN_VERSION_SYMBOL);
    } catch (const std::exception& e) {
        throw PluginError(fmt::format("plugin '{}': cannot be loaded as a shared library: {}",
                                      file.string(), e.what()));
    }
    if (!file_version)
        throw PluginError(fmt::format(
            "plugin '{}': missing symbol '{}' — not a Patina plugin, or built without "
            "PATINA_PLUGIN_EXPORT; rebuild it against patina/abi.h",
            file.string(), PATINA_PLUGIN_VERSION_SYMBOL));
    check_abi_version(file, *file_version);

    auto lib = std::make_unique<Library>();
    lib->file = canonical;
    // RTLD_LOCAL: the plugin's symbols never leak into the host or other plugins.
    dlerror();
    lib->handle = dlopen(canonical.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!lib->handle) {
        const char* err = dlerror();
        throw PluginError(fmt::format("plugin '{}': cannot be loaded as a shared library: {}",
                                      file.string(), err ? err : "unknown dlopen error"));
    }

    auto* version = static_cast<const int*>(dlsym(lib->handle, PATINA_PLUGIN_VERSION_SYMBOL));
    if (!version)
        throw PluginError(fmt::format(
            "plugin '{}': missing symbol '{}' — not a Patina plugin, or built without "
            "PATINA_PLUGIN_EXPORT; rebuild it against patina/abi.h",
            file.string(), PATINA_PLUGIN_VERSION_SYMBOL));
    if (*version != *file_version)
        throw PluginError(fmt::format("plugin '{}': its ABI version reads {} in the file but {} "
                                      "once loaded", file.string(), *file_version, *version));

    auto entry = reinterpret_cast<PatinaPluginEntryFn>(dlsym(lib->handle, PATINA_PLUGIN_ENTRY_SYMBOL));
    if (!entry)
        throw PluginError(fmt::format(
            "plugin '{}': missing symbol '{}' — export it with PATINA_PLUGIN_EXPORT and "
            "extern \"C\" linkage",
            file.string(), PATINA_PLUGIN_ENTRY_SYMBOL));
    lib->info = entry(host_);
    if (!lib->info || lib->info->shader_count < 0 ||
        (lib->info->shader_count > 0 && !lib->info->shaders))
        throw PluginError(fmt::format("plugin '{}': {} returned no valid shader table",
                                      file.string(), PATINA_PLUGIN_ENTRY_SYMBOL));
    const std::string plugin_name = lib->info->plugin_name ? lib->info->plugin_name : "";

    for (int i = 0; i < lib->info->shader_count; ++i) {
        const PatinaShaderDesc& d = lib->info->shaders[i];
        check_descriptor(file, d);
        for (const auto& s : lib->shaders)
            if (std::string_view(s.desc->name) == d.name)
                throw PluginError(fmt::format("plugin '{}': declares shader '{}' twice",
                                              file.string(), d.name));
        if (const LoadedShader* other = find(d.name))
            throw PluginError(fmt::format(
                "plugin '{}': shader '{}' is already provided by plugin '{}'; remove one of "
                "the two from the plugin search path",
                file.string(), d.name, other->plugin_file.string()));
        lib->shaders.push_back(LoadedShader{
            &d, canonical, plugin_name,
            lib->info->plugin_version ? lib->info->plugin_version : "", *version});
    }
    libraries_.push_back(std::move(lib));
}

void PluginRegistry::load_directory(const fs::path& dir)
{
    std::error_code ec;
    if (!fs::is_directory(dir, ec))
        throw PluginError(fmt::format("plugin directory '{}' does not exist or is not a directory",
                                      dir.string()));
    std::vector<fs::path> files;
    for (const auto& entry : fs::directory_iterator(dir, ec))
        if (entry.path().extension() == ".so" && entry.is_regular_file(ec))
            files.push_back(entry.path());
    if (ec)
        throw PluginError(fmt::format("plugin directory '{}': {}", dir.string(), ec.message()));
    std::sort(files.begin(), files.end());
    for (const auto& f : files)
        load_file(f);
}

void PluginRegistry::load_path_list(std::string_view list, std::string_view origin)
{
    size_t start = 0;
    while (start <= list.size()) {
        size_t end = list.find(':', start);
        if (end == std::string_view::npos)
            end = list.size();
        const std::string_view item = list.substr(start, end - start);
        if (!item.empty()) {
            const fs::path dir(item);
            // Relative entries would make the search depend on the current directory.
            if (!dir.is_absolute())
                throw PluginError(fmt::format(
                    "{}: plugin directory '{}' is not an absolute path", origin, item));
            try {
                load_directory(dir);
            } catch (const PluginError& e) {
                throw PluginError(fmt::format("{}: {}", origin, e.what()));
            }
        }
        start = end + 1;
    }
}

const LoadedShader* PluginRegistry::find(std::string_view name) const
{
    for (const auto& lib : libraries_)
        for (const auto& s : lib->shaders)
            if (name == s.desc->name)
                return &s;
    return nullptr;
}

const LoadedShader& PluginRegistry::get(std::string_view name) const
{
    if (const LoadedShader* s = find(name))
        return *s;
    std::string known;
    for (const LoadedShader* s : shaders())
        known += (known.empty() ? "" : ", ") + std::string(s->desc->name);
    if (libraries_.empty())
        throw PluginError(fmt::format(
            "no plugin provides shader '{}': no plugins are loaded (set PATINA_PLUGIN_PATH "
            "or pass --plugin-path)", name));
    throw PluginError(fmt::format("no plugin provides shader '{}'; loaded shaders: {}", name, known));
}

std::vector<const LoadedShader*> PluginRegistry::shaders() const
{
    std::vector<const LoadedShader*> out;
    for (const auto& lib : libraries_)
        for (const auto& s : lib->shaders)
            out.push_back(&s);
    std::sort(out.begin(), out.end(), [](const LoadedShader* a, const LoadedShader* b) {
        return std::string_view(a->desc->name) < std::string_view(b->desc->name);
    });
    return out;
}

std::vector<fs::path> PluginRegistry::plugin_files() const
{
    std::vector<fs::path> out;
    for (const auto& lib : libraries_)
        out.push_back(lib->file);
    return out;
}

}  // namespace patina
