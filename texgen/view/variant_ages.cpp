#include "texgen/view/variant_ages.h"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <optional>
#include <string_view>
#include <utility>

namespace patina::texgen {

using nlohmann::json;

namespace {

    /// The time a material records: {value, true} in years, {value, false} in seconds.
    std::optional<std::pair<double, bool>> recorded_time(const json& material)
    {
        if (!material.contains("extras") || !material["extras"].contains("patina"))
            return std::nullopt;
        const json& patina = material["extras"]["patina"];
        if (patina.contains("time_years") && patina["time_years"].is_number())
            return std::pair{patina["time_years"].get<double>(), true};
        if (patina.contains("time_s") && patina["time_s"].is_number())
            return std::pair{patina["time_s"].get<double>(), false};
        return std::nullopt;
    }

}  // namespace

VariantAges variant_ages(const json& gltf)
{
    VariantAges ages;
    const json empty = json::array();
    const json& variants = gltf.contains("extensions") &&
                                   gltf["extensions"].contains("KHR_materials_variants")
                               ? gltf["extensions"]["KHR_materials_variants"]["variants"]
                               : empty;
    for (const json& v : variants)
        ages.labels.push_back(v.value("name", std::string()));
    const json& materials = gltf.contains("materials") ? gltf["materials"] : empty;

    // Every (variant, material) pair the primitives map.
    std::vector<std::optional<std::pair<double, bool>>> time(variants.size());
    bool consistent = true;
    if (gltf.contains("meshes"))
        for (const json& mesh : gltf["meshes"])
            for (const json& primitive : mesh.value("primitives", empty)) {
                if (!primitive.contains("extensions") ||
                    !primitive["extensions"].contains("KHR_materials_variants"))
                    continue;
                for (const json& mapping :
                     primitive["extensions"]["KHR_materials_variants"].value("mappings", empty)) {
                    const size_t m = mapping.value("material", size_t(-1));
                    const auto t = m < materials.size() ? recorded_time(materials[m]) : std::nullopt;
                    for (const json& v : mapping.value("variants", empty)) {
                        const size_t i = v.get<size_t>();
                        if (i >= time.size() || !t)  // a kept-off material records no time
                            continue;
                        if (time[i] && *time[i] != *t)
                            consistent = false;
                        time[i] = t;
                    }
                }
            }
    for (const auto& t : time)
        consistent = consistent && t && t->second == time.front()->second;
    if (!consistent || time.empty())
        return ages;

    // Years as they are; seconds in the largest unit the last age reaches once: 2 days say
    // "2 d", 12 hours "12 h".
    constexpr std::array<std::pair<std::string_view, double>, 4> units{
        {{"d", 86400.0}, {"h", 3600.0}, {"min", 60.0}, {"s", 1.0}}};
    std::string_view unit = "y";
    double scale = 1.0;  // seconds per unit
    if (!time.front()->second) {
        unit = "s";
        for (const auto& [name, seconds] : units)
            if (time.back()->first >= seconds) {
                unit = name;
                scale = seconds;
                break;
            }
    }
    ages.unit.assign(unit.data(), unit.size());
    ages.labels.clear();
    for (const auto& t : time) {
        ages.values.push_back(t->first / scale);
        ages.labels.push_back(fmt::format("{:g} {}", ages.values.back(), ages.unit));
    }
    return ages;
}

}  // namespace patina::texgen
