// Colour management through OpenColorIO: the config (shipped or $OCIO), a cache of CPU
// processors, and the working space's RGB -> CIE XYZ (D65) matrix derived from OCIO.
#pragma once

#include <array>
#include <filesystem>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

namespace patina {

/// Row-major 3x3 matrix.
using Matrix3 = std::array<float, 9>;

/// A cached OCIO CPU processor between two colour spaces (or through a display/view).
/// Cheap to copy; `apply` is thread-safe. A default-constructed one is the identity.
class ColorConversion {
public:
    /// Convert `count` RGB triples in place.
    void apply(float* rgb, size_t count) const;
    /// True when applying changes nothing (same space, or data/raw involved).
    bool is_identity() const { return !impl_; }

    struct Impl;

private:
    friend class ColorManager;
    std::shared_ptr<const Impl> impl_;
};

class ColorManager {
public:
    /// Load `config_file`; throws std::runtime_error naming the file when it cannot be read
    /// or does not validate.
    explicit ColorManager(const std::filesystem::path& config_file);
    ~ColorManager();
    ColorManager(const ColorManager&) = delete;
    ColorManager& operator=(const ColorManager&) = delete;

    /// The config Patina uses when nothing is said: $OCIO if set and non-empty, else the
    /// shipped `share/patina/ocio/config.ocio` found relative to the running executable
    /// (`<exe>/../share/patina/ocio/config.ocio`; the build tree mirrors the install tree).
    /// The library cannot know the source tree, so otherwise it throws std::runtime_error
    /// naming the places it looked (tests pass `<source>/ocio/config.ocio` explicitly).
    static std::filesystem::path default_config_path();

    const std::filesystem::path& config_path() const;
    /// Name of the scene-linear working space (the config's scene_linear role).
    const std::string& working_space() const;
    /// True if the config knows this colour space (by name or alias or role).
    bool has_colorspace(std::string_view name) const;
    /// True if the colour space is data (`isdata`, e.g. "raw"): never converted. Throws
    /// like `convert` for an unknown name.
    bool is_data(std::string_view name) const;
    /// Every colour space of the config (scene- and display-referred), in config order.
    std::vector<std::string> colorspace_names() const;

    /// Convert `count` RGB triples in place from `src` to `dst`; unknown names throw
    /// std::runtime_error naming the colour space and listing the known ones. Processors
    /// are cached; thread-safe.
    void convert(std::string_view src, std::string_view dst, float* rgb, size_t count) const;
    /// Convert through a display/view from `src`; an unknown display or view throws
    /// std::runtime_error listing the known ones.
    void convert_display(std::string_view src, std::string_view display, std::string_view view,
                         float* rgb, size_t count) const;
    /// The cached conversions behind `convert` and `convert_display`, for callers that
    /// apply one conversion many times (texture lookups) without a cache look-up each time.
    ColorConversion conversion(std::string_view src, std::string_view dst) const;
    ColorConversion display_conversion(std::string_view src, std::string_view display,
                                       std::string_view view) const;

    /// Matrix taking working-space RGB to CIE 1931 XYZ with the D65 white normalised to
    /// Y = 1, found by sending the unit vectors through OCIO (no hand-written matrices) to
    /// the config's colour space "CIE-XYZ-D65" (or its cie_xyz_d65_interchange role).
    /// Throws std::runtime_error when the config has neither or the transform is not linear.
    Matrix3 working_rgb_to_xyz() const;

    struct Impl;

private:
    std::unique_ptr<Impl> impl_;
};

}  // namespace patina
