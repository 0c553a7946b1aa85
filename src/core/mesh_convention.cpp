#include "core/mesh_convention.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <stdexcept>

namespace patina {

namespace {

    struct NamedUnit {
        const char* name;
        double metres;
        std::array<const char*, 4> aliases;
        bool metric = true;
    };

    // Exact by definition: the international inch is 25.4 mm, the foot 12 in, the yard 3 ft
    // (International Yard and Pound Agreement, 1959).
    constexpr NamedUnit kUnits[] = {
        {"m", 1.0, {"metre", "metres", "meter", "meters"}},
        {"cm", 0.01, {"centimetre", "centimetres", "centimeter", "centimeters"}},
        {"mm", 0.001, {"millimetre", "millimetres", "millimeter", "millimeters"}},
        {"um", 1e-6, {"micrometre", "micrometres", "micrometer", "micron"}},
        {"km", 1000.0, {"kilometre", "kilometres", "kilometer", "kilometers"}},
        {"in", 0.0254, {"inch", "inches", "", ""}, false},
        {"ft", 0.3048, {"foot", "feet", "", ""}, false},
        {"yd", 0.9144, {"yard", "yards", "", ""}, false},
    };

    std::string lower(std::string_view text)
    {
        std::string s(text);
        std::transform(s.begin(), s.end(), s.begin(),
                       [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
        return s;
    }

} // namespace

std::string Axis::name() const
{
    return fmt::format("{}{}", sign < 0 ? '-' : '+', "xyz"[index]);
}

Axis parse_axis(std::string_view text, std::string_view what)
{
    const std::string s = lower(text);
    Axis a;
    std::string_view letter = s;
    if (!letter.empty() && (letter.front() == '+' || letter.front() == '-')) {
        a.sign = letter.front() == '-' ? -1 : 1;
        letter.remove_prefix(1);
    }
    if (letter.size() != 1 || letter[0] < 'x' || letter[0] > 'z')
        throw std::invalid_argument(
            fmt::format("{}: '{}' is not an axis (expected x, y, z, -x, -y or -z)", what, text));
    a.index = letter[0] - 'x';
    return a;
}

double parse_unit(std::string_view text, std::string_view what)
{
    const std::string s = lower(text);
    for (const NamedUnit& u : kUnits) {
        if (s == u.name)
            return u.metres;
        for (const char* alias : u.aliases)
            if (*alias && s == alias)
                return u.metres;
    }
    std::string known;
    for (const NamedUnit& u : kUnits)
        known += (known.empty() ? "" : ", ") + std::string(u.name);
    throw std::invalid_argument(
        fmt::format("{}: '{}' is not a unit (expected one of {}; or give --scale with the metres "
                    "per unit)",
                    what, text, known));
}

std::string unit_name(double metres_per_unit)
{
    for (const NamedUnit& u : kUnits)
        if (std::abs(metres_per_unit - u.metres) <= 1e-9 * u.metres)
            return u.name;
    return fmt::format("{:g} m", metres_per_unit);
}

std::string MeshConvention::describe() const
{
    return fmt::format("up {} ({}), unit {} ({})", up.name(), up_from, unit_name(metres_per_unit),
                       unit_from);
}

Imath::M44f convention_matrix(Axis up, double metres_per_unit)
{
    // Row vectors: row i is where the file's axis i goes.
    Imath::V3f rows[3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
    const float s = static_cast<float>(up.sign);
    if (up.index == 2) { // +z: (x, y, z) -> (x, z, -y); -z: (x, y, z) -> (x, -z, y)
        rows[1] = Imath::V3f(0, 0, -s);
        rows[2] = Imath::V3f(0, s, 0);
    } else if (up.index == 0) { // +x: (x, y, z) -> (-y, x, z); -x: (x, y, z) -> (y, -x, z)
        rows[0] = Imath::V3f(0, s, 0);
        rows[1] = Imath::V3f(-s, 0, 0);
    } else if (up.sign < 0) { // -y: a half turn about x
        rows[1] = Imath::V3f(0, -1, 0);
        rows[2] = Imath::V3f(0, 0, -1);
    }
    const float k = static_cast<float>(metres_per_unit);
    Imath::M44f m;
    for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j)
            m[i][j] = k * rows[i][j];
    return m;
}

MeshConvention resolve_convention(const DeclaredConvention& declared,
                                  const MeshConventionOptions& options)
{
    MeshConvention c;
    const std::string source = declared.source.empty() ? "the file" : declared.source;
    if (options.up) {
        c.up = *options.up;
        c.up_from = "--up";
        if (declared.up && *declared.up != *options.up)
            c.warnings.push_back(fmt::format("the file declares {} up ({}); {} up is used as "
                                             "the option says",
                                             declared.up->name(), source, options.up->name()));
    } else if (declared.up) {
        c.up = *declared.up;
        c.up_from = source;
    }
    if (options.metres_per_unit) {
        c.metres_per_unit = *options.metres_per_unit;
        c.unit_from = "--unit";
        if (declared.metres_per_unit &&
            std::abs(*declared.metres_per_unit - *options.metres_per_unit) >
                1e-9 * *options.metres_per_unit)
            c.warnings.push_back(fmt::format("the file declares its unit as {} ({}); {} is used "
                                             "as the option says",
                                             unit_name(*declared.metres_per_unit), source,
                                             unit_name(*options.metres_per_unit)));
    } else if (declared.metres_per_unit) {
        c.metres_per_unit = *declared.metres_per_unit;
        c.unit_from = source;
    }
    c.file_to_world = convention_matrix(c.up, c.metres_per_unit);
    return c;
}

std::string implausible_size_warning(const Imath::Box3f& bounds, const MeshConvention& applied)
{
    if (bounds.isEmpty())
        return {};
    const Imath::V3f size = bounds.size();
    const double longest = std::max({size.x, size.y, size.z});
    constexpr double kLargest = 100.0, kSmallest = 0.005; // metres
    if (!(longest > kLargest || longest < kSmallest) || !(longest > 0.0))
        return {};
    // The unit that brings the file's longest side within 0.05-20 m and nearest to 1 m on
    // a log scale; metric units first (kUnits lists them first), inches and feet only when
    // none fits.
    const double in_file_units = longest / applied.metres_per_unit;
    const NamedUnit* best = nullptr;
    double best_distance = 0.0;
    for (const NamedUnit& u : kUnits) {
        const double metres = in_file_units * u.metres;
        if (metres < 0.05 || metres > 20.0 || (best && !u.metric))
            continue;
        const double distance = std::abs(std::log(metres));
        if (!best || distance < best_distance) {
            best = &u;
            best_distance = distance;
        }
    }
    std::string remedy =
        best ? fmt::format("; if its unit is {}, say so with --unit {} (it "
                           "would be {:.3g} m)",
                           best->aliases[1], best->name, in_file_units * best->metres)
             : std::string("; give its unit with --unit or --scale");
    return fmt::format("the mesh is {:.4g} m along its longest side ({}), {} for a real "
                       "object{}",
                       longest, applied.describe(), longest > kLargest ? "large" : "small", remedy);
}

} // namespace patina
