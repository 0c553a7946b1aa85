// [environment] and [sun] of a scene file.
#include "render/distant_light.h"
#include "render/environment_light.h"
#include "render/scene_parts.h"

#include "core/color_management.h"
#include "host/host.h"

#include <cmath>

namespace patina::render {

namespace fs = std::filesystem;

// A colour in `space` (any colour space of the config) as working-space RGB.
Imath::V3f working_rgb(const TomlReader& w, const toml::table& t, std::string_view table,
                       const Host& host)
{
    Imath::V3f rgb = w.vec3(t, "color", {1, 1, 1}, table);
    const std::string space = w.string(t, "colorspace", "scene_linear", table);
    if (!host.colors().has_colorspace(space))
        w.fail(t.get("colorspace"), fmt::format("unknown colour space '{}' in OCIO config '{}'",
                                                space, host.colors().config_path().string()));
    if (space != "scene_linear" && space != host.colors().working_space())
        host.colors().convert(space, host.colors().working_space(), &rgb[0], 1);
    for (int i = 0; i < 3; ++i)
        if (!(rgb[i] >= 0.0f))
            w.fail(t.get("color"), fmt::format("[{}] color must not be negative", table));
    return rgb;
}

// [environment]: a lat-long map (file, colorspace, rotation_deg) or a uniform colour.
void add_environment(const TomlReader& w, const toml::table& root, const fs::path& base_dir,
                     const Host& host, std::vector<std::unique_ptr<Light>>& lights)
{
    const toml::table* env = w.table(root, "environment");
    if (!env)
        return;
    w.check_keys(*env, "environment", {"color", "colorspace", "intensity", "file", "rotation_deg"});
    const float intensity = static_cast<float>(w.number(*env, "intensity", 1, 0, 1e30, "environment"));
    const std::string file = w.string(*env, "file", "", "environment");
    if (file.empty()) {
        if (env->get("rotation_deg"))
            w.fail(env->get("rotation_deg"), "[environment] rotation_deg needs a map 'file'");
        const Imath::V3f rgb = working_rgb(w, *env, "environment", host);
        lights.push_back(std::make_unique<EnvironmentLight>(
            host, std::array<float, 3>{rgb.x, rgb.y, rgb.z}, intensity));
        return;
    }
    if (env->get("color"))
        w.fail(env->get("color"), "[environment] takes a 'file' or a 'color', not both");
    const fs::path path = fs::path(file).is_relative() ? base_dir / file : fs::path(file);
    const std::string space = w.string(*env, "colorspace", "scene_linear", "environment");
    const float rotation =
        static_cast<float>(w.number(*env, "rotation_deg", 0, -1e6, 1e6, "environment"));
    try {
        lights.push_back(std::make_unique<EnvironmentLight>(host, path, space, intensity, rotation));
    } catch (const std::exception& e) {
        w.fail(env->get("file"), e.what());
    }
}

// [sun]: a distant light towards `direction` (or elevation/azimuth), with an angular
// diameter, a colour and the irradiance it gives a perpendicular surface.
void add_sun(const TomlReader& w, const toml::table& root, const Host& host,
             std::vector<std::unique_ptr<Light>>& lights)
{
    const toml::table* sun = w.table(root, "sun");
    if (!sun)
        return;
    w.check_keys(*sun, "sun", {"direction", "elevation_deg", "azimuth_deg",
                               "angular_diameter_deg", "color", "colorspace", "irradiance"});
    Imath::V3f dir;
    if (sun->get("direction")) {
        if (sun->get("elevation_deg") || sun->get("azimuth_deg"))
            w.fail(sun->get("direction"), "[sun] takes 'direction' or elevation/azimuth, not both");
        dir = w.vec3(*sun, "direction", {0, 1, 0}, "sun");
        if (dir.length() <= 0.0f)
            w.fail(sun->get("direction"), "[sun] direction must not be zero");
        dir.normalize();
    } else {
        // Azimuth clockwise from north (-z) towards east (+x), elevation above the horizon.
        const double el = w.number(*sun, "elevation_deg", 45, -90, 90, "sun") * M_PI / 180.0;
        const double az = w.number(*sun, "azimuth_deg", 180, -360, 360, "sun") * M_PI / 180.0;
        dir = Imath::V3f(static_cast<float>(std::cos(el) * std::sin(az)),
                         static_cast<float>(std::sin(el)),
                         static_cast<float>(-std::cos(el) * std::cos(az)));
    }
    const float diameter =
        static_cast<float>(w.number(*sun, "angular_diameter_deg", 0.53, 0, 90, "sun"));
    const float irradiance = static_cast<float>(w.number(*sun, "irradiance", 1, 0, 1e30, "sun"));
    const Imath::V3f rgb = working_rgb(w, *sun, "sun", host);
    lights.push_back(std::make_unique<DistantLight>(dir, diameter, host.uplift(&rgb[0], true),
                                                    irradiance));
}

}  // namespace patina::render
