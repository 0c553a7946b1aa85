#include "texgen/cli/fade_options.h"

#include "core/limits.h"

#include <fmt/format.h>

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace patina::texgen {

double parse_duration(const std::string& text, const std::string& what)
{
    if (text.empty())
        return 0.0;
    size_t used = 0;
    double value = 0.0;
    try {
        value = std::stod(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    const std::string unit = text.substr(used);
    const std::pair<const char*, double> units[] = {
        {"", 1.0}, {"s", 1.0}, {"min", 60.0}, {"h", 3600.0}, {"d", 86400.0},
        {"y", 365.0 * 86400.0}};
    if (used > 0 && value >= 0.0 && std::isfinite(value))
        for (const auto& [name, seconds] : units)
            if (unit == name)
                return value * seconds;
    throw std::runtime_error(what + " '" + text +
                             "': expected a number with an optional unit s, min, h, d or y "
                             "(e.g. 7d, 30y)");
}

fade::WavelengthGrid parse_grid(const std::string& text)
{
    double first = 0, last = 0, step = 0;
    char c1 = 0, c2 = 0;
    if (std::sscanf(text.c_str(), "%lf%c%lf%c%lf", &first, &c1, &last, &c2, &step) != 5 ||
        c1 != ':' || c2 != ':' || !(step > 0.0) || !(last > first))
        throw std::runtime_error("--wavelengths '" + text +
                                 "': expected FIRST:LAST:STEP in nm, e.g. 300:830:5");
    check_limit("--wavelengths '" + text + "'", std::floor((last - first) / step + 1e-9) + 1,
                fade::WavelengthGrid::kMaxWavelengths, "wavelengths");
    return fade::WavelengthGrid::uniform(first, last, step);
}

void add_material_options(CLI::App* cmd, FadeMaterialChoice& c)
{
    cmd->add_option("--material", c.material, "fading material (shaders/fade/*.toml)");
    cmd->add_option("--rates", c.rates, "a named set of fading rates from the material files");
    cmd->add_option("--blue-wool", c.blue_wool,
                    "a generic colorant of ISO Blue Wool category 1-8 instead of --material");
    cmd->add_option("--materials", c.materials, "more fading material files (repeatable)")
        ->check(CLI::ExistingFile);
}

fade::FadeMaterial load_material(const FadeMaterialChoice& c)
{
    if (c.material.empty() == (c.blue_wool == 0))
        throw std::runtime_error("give a material: --material NAME or --blue-wool 1..8");
    if (c.blue_wool != 0 && !c.rates.empty())
        throw std::runtime_error("--blue-wool sets the rates: leave out --rates");
    if (c.blue_wool != 0 && (c.blue_wool < 1 || c.blue_wool > 8))
        throw std::runtime_error(fmt::format(
            "--blue-wool {}: the ISO Blue Wool categories are 1 (most sensitive) to 8", c.blue_wool));
    std::vector<std::filesystem::path> files = fade::FadeLibrary::default_files();
    files.insert(files.end(), c.materials.begin(), c.materials.end());
    if (files.empty())
        throw std::runtime_error("no fading materials: none found under $PATINA_SHADER_PATH or "
                                 "<exe>/../share/patina/shaders/fade; pass --materials FILE");
    const fade::FadeLibrary library = fade::FadeLibrary::load_files(files);
    // An ISO Blue Wool category is the blue_wool material at that category's rate
    return c.blue_wool ? library.material_with_rates("blue_wool", fmt::format("blue_wool_{}", c.blue_wool))
                       : library.material_with_rates(c.material, c.rates);
}

void add_lamp_policy_options(CLI::App* cmd, LampPolicyChoice& c, const std::string& lamp_note)
{
    cmd->add_option("--lamp", c.lamp,
                    "one policy's lamp: D65, A, E, F1..F12, LED-B1..LED-V2, or SPD.csv[:COLUMN]" +
                        lamp_note);
    cmd->add_option("--lux", c.lux, "one policy's illuminance at the object, lux");
    cmd->add_option("--hours-per-day", c.hours_per_day, "one policy's hours lit a day")
        ->capture_default_str();
    cmd->add_option("--days-per-year", c.days_per_year, "one policy's days lit a year")
        ->capture_default_str();
    cmd->add_option("--uv-filter", c.uv_filter,
                    "UV filter: a cut-off in nm (400), or FILTER.csv[:COLUMN] (transmittance)");
    cmd->add_option("--name", c.name, "one policy's name");
}

forecast::LightingPolicy lamp_policy(const LampPolicyChoice& c)
{
    if (!c.lux)
        throw std::runtime_error("--lamp needs --lux (illuminance at the object)");
    if (!(*c.lux >= 0.0) || !std::isfinite(*c.lux))
        throw std::runtime_error(fmt::format("--lux must be a finite number >= 0, got {}", *c.lux));
    forecast::LightingPolicy p;
    p.lamp = forecast::parse_lamp(c.lamp.empty() ? "D65" : c.lamp);
    p.filter = forecast::parse_uv_filter(c.uv_filter, "--uv-filter");
    p.lux = *c.lux;
    p.hours_per_day = c.hours_per_day;
    p.days_per_year = c.days_per_year;
    p.name = !c.name.empty() ? c.name
                             : fmt::format("{} {:g} lx{}", p.lamp.name, p.lux,
                                           p.filter.active() ? ", " + p.filter.label : "");
    return p;
}

}  // namespace patina::texgen
