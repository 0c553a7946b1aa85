#include "core/color_management.h"

#include <OpenColorIO/OpenColorIO.h>
#include <fmt/format.h>

#include <cmath>
#include <cstdlib>
#include <map>
#include <mutex>
#include <shared_mutex>
#include <stdexcept>
#include <tuple>

namespace OCIO = OCIO_NAMESPACE;

namespace patina {

struct ColorConversion::Impl {
    OCIO::ConstCPUProcessorRcPtr cpu;
};

void ColorConversion::apply(float* rgb, size_t count) const
{
    if (!impl_ || count == 0)
        return;
    // One row of `count` packed RGB pixels; OCIO handles the loop (and SIMD).
    OCIO::PackedImageDesc desc(rgb, static_cast<long>(count), 1, 3);
    impl_->cpu->apply(desc);
}

struct ColorManager::Impl {
    std::filesystem::path path;
    OCIO::ConstConfigRcPtr config;
    std::string working_space;

    // Processors keyed by canonical names; OCIO processors are immutable once built, so
    // readers share the lock and only a miss takes it exclusively.
    mutable std::shared_mutex mutex;
    mutable std::map<std::pair<std::string, std::string>, ColorConversion> by_spaces;
    mutable std::map<std::tuple<std::string, std::string, std::string>, ColorConversion>
        by_display;

    std::string known_colorspaces() const
    {
        std::string list;
        const int n = config->getNumColorSpaces(OCIO::SEARCH_REFERENCE_SPACE_ALL,
                                                OCIO::COLORSPACE_ALL);
        for (int i = 0; i < n; ++i) {
            if (i)
                list += ", ";
            list += config->getColorSpaceNameByIndex(OCIO::SEARCH_REFERENCE_SPACE_ALL,
                                                     OCIO::COLORSPACE_ALL, i);
        }
        return list;
    }

    /// Canonical name of a colour space given by name, alias or role; throws if unknown.
    std::string canonical(std::string_view name) const
    {
        const std::string key(name);
        OCIO::ConstColorSpaceRcPtr cs = key.empty() ? nullptr : config->getColorSpace(key.c_str());
        if (!cs)
            throw std::runtime_error(fmt::format("unknown colour space '{}' in OCIO config {}; known: {}",
                                                 key, path.string(), known_colorspaces()));
        return cs->getName();
    }

    static ColorConversion wrap(const OCIO::ConstProcessorRcPtr& processor)
    {
        ColorConversion c;
        if (!processor->isNoOp())
            c.impl_ = std::make_shared<ColorConversion::Impl>(
                ColorConversion::Impl{processor->getDefaultCPUProcessor()});
        return c;
    }

    void check_display_view(const std::string& display, const std::string& view) const
    {
        std::string displays;
        bool found = false;
        for (int i = 0; i < config->getNumDisplays(); ++i) {
            const std::string d = config->getDisplay(i);
            displays += (i ? ", " : "") + d;
            found = found || d == display;
        }
        if (!found)
            throw std::runtime_error(fmt::format("unknown display '{}' in OCIO config {}; known: {}",
                                                 display, path.string(), displays));
        std::string views;
        for (int i = 0; i < config->getNumViews(display.c_str()); ++i) {
            const std::string v = config->getView(display.c_str(), i);
            if (v == view)
                return;
            views += (i ? ", " : "") + v;
        }
        throw std::runtime_error(fmt::format("unknown view '{}' of display '{}' in OCIO config {}; known: {}",
                                             view, display, path.string(), views));
    }
};

ColorManager::ColorManager(const std::filesystem::path& config_file)
    : impl_(std::make_unique<Impl>())
{
    impl_->path = config_file;
    std::error_code ec;
    if (!std::filesystem::is_regular_file(config_file, ec))
        throw std::runtime_error(fmt::format("OCIO config {}: file not found", config_file.string()));
    try {
        impl_->config = OCIO::Config::CreateFromFile(config_file.c_str());
        impl_->config->validate();
    } catch (const OCIO::Exception& e) {
        throw std::runtime_error(fmt::format("OCIO config {}: {}", config_file.string(), e.what()));
    }
    OCIO::ConstColorSpaceRcPtr working = impl_->config->getColorSpace(OCIO::ROLE_SCENE_LINEAR);
    if (!working)
        throw std::runtime_error(fmt::format(
            "OCIO config {} has no '{}' role; Patina needs it to name its working space",
            config_file.string(), OCIO::ROLE_SCENE_LINEAR));
    impl_->working_space = working->getName();
}

ColorManager::~ColorManager() = default;

std::filesystem::path ColorManager::default_config_path()
{
    if (const char* env = std::getenv("OCIO"); env && *env)
        return env;
    std::error_code ec;
    const std::filesystem::path exe = std::filesystem::read_symlink("/proc/self/exe", ec);
    std::filesystem::path shipped;
    if (!ec) {
        shipped = (exe.parent_path() / ".." / "share" / "patina" / "ocio" / "config.ocio")
                      .lexically_normal();
        if (std::filesystem::is_regular_file(shipped, ec))
            return shipped;
    }
    throw std::runtime_error(fmt::format(
        "no OCIO config: $OCIO is not set and the shipped config {} does not exist; set OCIO "
        "to a config file (Patina's is ocio/config.ocio in its source tree)",
        shipped.empty() ? std::string("<exe>/../share/patina/ocio/config.ocio") : shipped.string()));
}

const std::filesystem::path& ColorManager::config_path() const { return impl_->path; }

const std::string& ColorManager::working_space() const { return impl_->working_space; }

bool ColorManager::has_colorspace(std::string_view name) const
{
    const std::string key(name);
    return !key.empty() && impl_->config->getColorSpace(key.c_str()) != nullptr;
}

bool ColorManager::is_data(std::string_view name) const
{
    const std::string canonical = impl_->canonical(name);
    return impl_->config->getColorSpace(canonical.c_str())->isData();
}

std::vector<std::string> ColorManager::colorspace_names() const
{
    std::vector<std::string> names;
    const int n = impl_->config->getNumColorSpaces(OCIO::SEARCH_REFERENCE_SPACE_ALL,
                                                   OCIO::COLORSPACE_ALL);
    for (int i = 0; i < n; ++i)
        names.emplace_back(impl_->config->getColorSpaceNameByIndex(
            OCIO::SEARCH_REFERENCE_SPACE_ALL, OCIO::COLORSPACE_ALL, i));
    return names;
}

ColorConversion ColorManager::conversion(std::string_view src, std::string_view dst) const
{
    auto key = std::make_pair(impl_->canonical(src), impl_->canonical(dst));
    {
        std::shared_lock lock(impl_->mutex);
        if (auto it = impl_->by_spaces.find(key); it != impl_->by_spaces.end())
            return it->second;
    }
    ColorConversion c;
    try {
        c = Impl::wrap(impl_->config->getProcessor(key.first.c_str(), key.second.c_str()));
    } catch (const OCIO::Exception& e) {
        throw std::runtime_error(fmt::format("OCIO config {}: cannot convert '{}' to '{}': {}",
                                             impl_->path.string(), key.first, key.second, e.what()));
    }
    std::unique_lock lock(impl_->mutex);
    return impl_->by_spaces.emplace(std::move(key), c).first->second;
}

ColorConversion ColorManager::display_conversion(std::string_view src, std::string_view display,
                                                 std::string_view view) const
{
    auto key = std::make_tuple(impl_->canonical(src), std::string(display), std::string(view));
    {
        std::shared_lock lock(impl_->mutex);
        if (auto it = impl_->by_display.find(key); it != impl_->by_display.end())
            return it->second;
    }
    const auto& [s, d, v] = key;
    impl_->check_display_view(d, v);
    ColorConversion c;
    try {
        c = Impl::wrap(impl_->config->getProcessor(s.c_str(), d.c_str(), v.c_str(),
                                                   OCIO::TRANSFORM_DIR_FORWARD));
    } catch (const OCIO::Exception& e) {
        throw std::runtime_error(fmt::format("OCIO config {}: cannot convert '{}' through display '{}' view '{}': {}",
                                             impl_->path.string(), s, d, v, e.what()));
    }
    std::unique_lock lock(impl_->mutex);
    return impl_->by_display.emplace(std::move(key), c).first->second;
}

void ColorManager::convert(std::string_view src, std::string_view dst, float* rgb, size_t count) const
{
    conversion(src, dst).apply(rgb, count);
}

void ColorManager::convert_display(std::string_view src, std::string_view display,
                                   std::string_view view, float* rgb, size_t count) const
{
    display_conversion(src, display, view).apply(rgb, count);
}

Matrix3 ColorManager::working_rgb_to_xyz() const
{
    // Patina's config names the space; OCIO 2.2+ configs (ACES studio) carry the role.
    std::string xyz;
    for (const char* candidate : {"CIE-XYZ-D65", "cie_xyz_d65_interchange"})
        if (has_colorspace(candidate)) {
            xyz = candidate;
            break;
        }
    if (xyz.empty())
        throw std::runtime_error(fmt::format(
            "OCIO config {} has no colour space 'CIE-XYZ-D65' (nor a cie_xyz_d65_interchange "
            "role); Patina needs it to relate the working space '{}' to CIE XYZ for spectral "
            "rendering. Add one (e.g. a BuiltinTransform 'UTILITY - ACES-AP0_to_CIE-XYZ-D65_BFD' "
            "from ACES2065-1) or unset $OCIO to use Patina's config",
            impl_->path.string(), impl_->working_space));

    // Columns of the matrix are the images of the unit vectors; the images of 2*e_i and
    // (1,1,1) check that the transform is a matrix (linear, no offsets or curves).
    float rgb[5 * 3] = {1, 0, 0, 0, 1, 0, 0, 0, 1, 2, 0, 0, 1, 1, 1};
    convert(impl_->working_space, xyz, rgb, 5);
    Matrix3 m{};
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 3; ++col)
            m[row * 3 + col] = rgb[col * 3 + row];
    for (int row = 0; row < 3; ++row) {
        const float sum = m[row * 3] + m[row * 3 + 1] + m[row * 3 + 2];
        const float tol = 1e-4f * (1.0f + std::abs(sum));
        if (std::abs(rgb[9 + row] - 2 * m[row * 3]) > tol || std::abs(rgb[12 + row] - sum) > tol)
            throw std::runtime_error(fmt::format(
                "OCIO config {}: the conversion from '{}' to '{}' is not linear, so it has no "
                "RGB to XYZ matrix",
                impl_->path.string(), impl_->working_space, xyz));
    }
    return m;
}

}  // namespace patina
