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
    /// The Host behind a table made by a Host, or nullptr for a foreign table.
    static const Host* from_c(const PatinaHost* host);

    const ColorManager& colors() const;

    /// Uplift a working-space RGB (see PatinaHost::rgb_to_spectrum).
    PatinaRgbSpectrum uplift(const float rgb[3], bool illuminant) const;

    /// Open a texture for plugins (OIIO TextureSystem); `colorspace` is its declared
    /// colour space. Handles stay valid for the host's lifetime. Throws std::runtime_error
    /// naming the file when it cannot be opened.
    const PatinaTexture* open_texture(const std::string& path, const std::string& colorspace) const;

    /// Errors plugins reported through host->error on this thread since the last call
    /// (then cleared).
    std::vector<std::string> take_errors() const;
    /// Warnings are printed to stderr as they come; this counts them (for tests).
    size_t warning_count() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

/// A process-wide host using the default colour configuration (the shipped OCIO config, or
/// $OCIO). Convenient for tools and tests.
Host& default_host();

}  // namespace patina
