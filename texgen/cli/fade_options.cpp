#include "texgen/cli/fade_options.h"

#include "core/limits.h"

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

}  // namespace patina::texgen
