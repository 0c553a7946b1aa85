// Header-only helpers for writing a plugin in C++: a printf-style error through the host,
// an allocation that never throws across the C ABI, the values `create` receives read by
// parameter name, descriptors with the fields every shader fills, and the entry point.
#pragma once

#include <patina/abi.h>

#include <cstddef>
#include <cstdio>
#include <cstring>
#include <new>
#include <utility>

namespace patina::plugin {

/// Reports a create-time error through the host, formatted like printf.
template <typename... Args>
void report_error(const PatinaHost* host, const char* shader, const char* format, Args... args)
{
    if (!host || !host->error)
        return;
    char message[1024];
    if constexpr (sizeof...(Args) == 0) {
        std::snprintf(message, sizeof message, "%s", format);
    } else {
        std::snprintf(message, sizeof message, format, args...);
    }
    host->error(host, shader, message);
}

/// Allocates an instance (create only); reports an error and returns nullptr when memory
/// runs out, so that no exception crosses the C ABI.
template <typename T, typename... Args>
T* make_instance(const PatinaHost* host, const char* shader, Args&&... args)
{
    T* instance = new (std::nothrow) T{std::forward<Args>(args)...};
    if (!instance)
        report_error(host, shader, "out of memory");
    return instance;
}

/// The name of a parameter type as scene files spell it ("float", "color", ...).
inline const char* type_name(PatinaParamType type)
{
    switch (type) {
    case PATINA_PARAM_FLOAT: return "float";
    case PATINA_PARAM_INT: return "int";
    case PATINA_PARAM_BOOL: return "bool";
    case PATINA_PARAM_COLOR: return "color";
    case PATINA_PARAM_SPECTRUM: return "spectrum";
    case PATINA_PARAM_STRING: return "string";
    case PATINA_PARAM_TEXTURE: return "texture";
    case PATINA_PARAM_FILE: return "file";
    }
    return "unknown";
}

/// The values `create` receives, read by the names of the shader's declaration table (the
/// table the descriptor was made with), so that reordering or renaming the table cannot
/// silently rebind a value. A read of a name the table does not declare, or of another type
/// than declared, is reported through the host, naming shader and parameter, and returns an
/// empty value; ok() is then false and create must refuse:
///
///     const Parameters p(host, kName, kParams, values);
///     const float roughness = p.number("roughness");
///     const PatinaParamValue& colour = p.value("reflectance", PATINA_PARAM_COLOR);
///     if (!p.ok())
///         return nullptr;
class Parameters {
public:
    template <std::size_t N>
    Parameters(const PatinaHost* host, const char* shader, const PatinaParamDecl (&decls)[N],
               const PatinaParamValue* values)
        : host_(host), shader_(shader), decls_(decls), count_(static_cast<int>(N)),
          values_(values)
    {
    }

    /// The value of `name`, declared of `type` (FILE and STRING read alike as text).
    const PatinaParamValue& value(const char* name, PatinaParamType type) const
    {
        static const PatinaParamValue kEmpty{};
        for (int i = 0; i < count_; ++i) {
            if (std::strcmp(decls_[i].name, name) != 0)
                continue;
            const PatinaParamType declared = decls_[i].type;
            const bool text = (declared == PATINA_PARAM_STRING || declared == PATINA_PARAM_FILE) &&
                              (type == PATINA_PARAM_STRING || type == PATINA_PARAM_FILE);
            if (declared != type && !text) {
                report_error(host_, shader_,
                             "plugin bug: parameter '%s' is declared %s but read as %s", name,
                             type_name(declared), type_name(type));
                failed_ = true;
                return kEmpty;
            }
            return values_[i];
        }
        report_error(host_, shader_, "plugin bug: reads parameter '%s', which it does not declare",
                     name);
        failed_ = true;
        return kEmpty;
    }

    float number(const char* name) const { return value(name, PATINA_PARAM_FLOAT).f; }
    int integer(const char* name) const { return value(name, PATINA_PARAM_INT).i; }
    bool flag(const char* name) const { return value(name, PATINA_PARAM_BOOL).i != 0; }
    /// A STRING or FILE value ("" when empty).
    const char* text(const char* name) const
    {
        const char* s = value(name, PATINA_PARAM_STRING).s;
        return s ? s : "";
    }
    const PatinaTexture* texture(const char* name) const
    {
        return value(name, PATINA_PARAM_TEXTURE).texture;
    }

    /// False after a read of an undeclared or mistyped parameter.
    bool ok() const { return !failed_; }

private:
    const PatinaHost* host_;
    const char* shader_;
    const PatinaParamDecl* decls_;
    int count_;
    const PatinaParamValue* values_;
    mutable bool failed_ = false;
};

/// A descriptor with the fields every shader fills; the caller sets its function table.
template <std::size_t N>
PatinaShaderDesc describe(const char* name, PatinaShaderKind kind, const char* help,
                          const PatinaParamDecl (&params)[N],
                          void* (*create)(const PatinaHost*, const PatinaParamValue*),
                          void (*destroy)(void*))
{
    PatinaShaderDesc d{};
    d.name = name;
    d.kind = kind;
    d.help = help;
    d.param_count = static_cast<int>(N);
    d.params = params;
    d.create = create;
    d.destroy = destroy;
    return d;
}

/// A complete descriptor of each kind: describe() with the kind's function table set.
template <std::size_t N>
PatinaShaderDesc describe(const char* name, const char* help, const PatinaParamDecl (&params)[N],
                          void* (*create)(const PatinaHost*, const PatinaParamValue*),
                          void (*destroy)(void*), const PatinaBsdfFuncs& funcs)
{
    PatinaShaderDesc d = describe(name, PATINA_SHADER_BSDF, help, params, create, destroy);
    d.bsdf = &funcs;
    return d;
}

template <std::size_t N>
PatinaShaderDesc describe(const char* name, const char* help, const PatinaParamDecl (&params)[N],
                          void* (*create)(const PatinaHost*, const PatinaParamValue*),
                          void (*destroy)(void*), const PatinaMediumFuncs& funcs)
{
    PatinaShaderDesc d = describe(name, PATINA_SHADER_MEDIUM, help, params, create, destroy);
    d.medium = &funcs;
    return d;
}

template <std::size_t N>
PatinaShaderDesc describe(const char* name, const char* help, const PatinaParamDecl (&params)[N],
                          void* (*create)(const PatinaHost*, const PatinaParamValue*),
                          void (*destroy)(void*), const PatinaEmitterFuncs& funcs)
{
    PatinaShaderDesc d = describe(name, PATINA_SHADER_EMITTER, help, params, create, destroy);
    d.emitter = &funcs;
    return d;
}

template <std::size_t N>
PatinaShaderDesc describe(const char* name, const char* help, const PatinaParamDecl (&params)[N],
                          void* (*create)(const PatinaHost*, const PatinaParamValue*),
                          void (*destroy)(void*), const PatinaTextureFuncs& funcs)
{
    PatinaShaderDesc d = describe(name, PATINA_SHADER_TEXTURE, help, params, create, destroy);
    d.texture = &funcs;
    return d;
}

}  // namespace patina::plugin

/// The plugin's two exported symbols in one line, in one source file: the ABI version and
/// patina_plugin_entry returning the table of the shaders the expression list builds
/// (PatinaShaderDesc values, e.g. describe(...) calls), built once on the first call.
///
///     PATINA_PLUGIN("basic", "0.1.0", lambert_shader(), conductor_shader())
#define PATINA_PLUGIN(plugin_name, plugin_version, ...)                                        \
    PATINA_PLUGIN_DEFINE_VERSION;                                                             \
    PATINA_PLUGIN_ENTRY_DECL const PatinaPluginInfo* patina_plugin_entry(const PatinaHost*)  \
    {                                                                                         \
        static const PatinaShaderDesc shaders[] = {__VA_ARGS__};                              \
        static const PatinaPluginInfo info = {                                                \
            plugin_name, plugin_version, static_cast<int>(sizeof shaders / sizeof shaders[0]), \
            shaders};                                                                         \
        return &info;                                                                         \
    }
