// The host services table handed to plugins (patina/abi.h PatinaHost), backed by libpatina:
// RGB uplift in the working space, OIIO texture lookups, error collection.
#pragma once

#include <patina/abi.h>

#include <memory>
#include <string>
#include <vector>

namespace patina {

class ColorManager;

/// Owns a PatinaHost table and the state behind it. Thread-safe after construction.
class Host {
public:
    /// Uses `colors` for the working space and uplift; `colors` must outlive the host.
    explicit Host(const ColorManager& colors, std::string host_name = "patina");
    ~Host();
    Host(const Host&) = delete;
    Host& operator=(const Host&) = delete;

    const PatinaHost* c_host() const;

    /// Errors plugins reported through host->error since the last call (then cleared).
    std::vector<std::string> take_errors() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

/// A process-wide host using the default colour configuration (the shipped OCIO config, or
/// $OCIO). Convenient for tools and tests.
Host& default_host();

}  // namespace patina
