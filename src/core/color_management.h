// Colour management through OpenColorIO: the config (shipped or $OCIO), a cache of CPU
// processors, and the working space's RGB -> CIE XYZ (D65) matrix derived from OCIO.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>

namespace patina {

/// Row-major 3x3 matrix.
using Matrix3 = std::array<float, 9>;

class ColorManager {
public:
    /// Load `config_file`; throws std::runtime_error naming the file when it cannot be read
    /// or does not validate.
    explicit ColorManager(const std::filesystem::path& config_file);
    ~ColorManager();
    ColorManager(const ColorManager&) = delete;
    ColorManager& operator=(const ColorManager&) = delete;

    /// The config Patina uses when nothing is said: $OCIO if set, else the shipped
    /// `share/patina/ocio/config.ocio` found relative to the running executable
    /// (`<exe>/../share/patina/ocio/config.ocio`), else the one in the source tree.
    static std::filesystem::path default_config_path();

    const std::filesystem::path& config_path() const;
    /// Name of the scene-linear working space (the config's scene_linear role).
    const std::string& working_space() const;
    /// True if the config knows this colour space (by name or alias or role).
    bool has_colorspace(std::string_view name) const;

    /// Convert `count` RGB triples in place from `src` to `dst`; unknown names throw
    /// std::runtime_error naming the colour space and listing the known ones. Processors
    /// are cached; thread-safe.
    void convert(std::string_view src, std::string_view dst, float* rgb, size_t count) const;
    /// Convert through a display/view from `src`.
    void convert_display(std::string_view src, std::string_view display, std::string_view view,
                         float* rgb, size_t count) const;

    /// Matrix taking working-space RGB to CIE 1931 XYZ with the D65 white normalised to
    /// Y = 1, found by sending the unit vectors through OCIO (no hand-written matrices).
    Matrix3 working_rgb_to_xyz() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace patina
