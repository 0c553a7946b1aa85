// Header-only helpers for writing a plugin's create functions and descriptors in C++: a
// printf-style error through the host, an allocation that never throws across the C ABI,
// and a descriptor with the fields every shader fills.
#pragma once

#include <patina/abi.h>

#include <cstddef>
#include <cstdio>
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

}  // namespace patina::plugin
