#include "texgen/sun/cie_sky.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen {

namespace {

constexpr double kPi = 3.14159265358979323846;

// CIE S 011/E:2003 Table 1: the six gradation groups (a, b) and six indicatrix groups
// (c, d, e), and the standard skies that combine them.
struct Gradation {
    double a, b;
};
struct Indicatrix {
    double c, d, e;
};
constexpr Gradation kGradation[6] = {
    {4.0, -0.70}, {1.1, -0.8}, {0.0, -1.0}, {-1.0, -0.55}, {-1.0, -0.32}, {-1.0, -0.15},
};
constexpr Indicatrix kIndicatrix[6] = {
    {0.0, -1.0, 0.0},  {2.0, -1.5, 0.15}, {5.0, -2.5, 0.30},
    {10.0, -3.0, 0.45}, {16.0, -3.0, 0.30}, {24.0, -2.8, 0.15},
};
struct StandardSky {
    int gradation, indicatrix;  // 1-based groups (I..VI, 1..6)
    const char* name;
};
constexpr StandardSky kStandardSkies[15] = {
    {1, 1, "CIE standard overcast sky, alternative form: steep gradation, azimuthally uniform"},
    {1, 2, "overcast, steep gradation, slight brightening towards the sun"},
    {2, 1, "overcast, moderately graded, azimuthally uniform"},
    {2, 2, "overcast, moderately graded, slight brightening towards the sun"},
    {3, 1, "sky of uniform luminance"},
    {3, 2, "partly cloudy, no gradation towards the zenith, slight brightening to the sun"},
    {3, 3, "partly cloudy, no gradation, brighter circumsolar region"},
    {3, 4, "partly cloudy, no gradation, distinct solar corona"},
    {4, 2, "partly cloudy, the obscured sun"},
    {4, 3, "partly cloudy, brighter circumsolar region"},
    {4, 4, "white-blue sky with distinct solar corona"},
    {5, 4, "CIE standard clear sky, low luminance turbidity"},
    {5, 5, "CIE standard clear sky, polluted atmosphere"},
    {6, 5, "cloudless turbid sky with broad solar corona"},
    {6, 6, "white-blue turbid sky with broad solar corona"},
};

double gradation(const CieSky& sky, double cos_z)
{
    // phi(Z) = 1 + a exp(b / cos Z); at the horizon exp(-inf) = 0.
    if (cos_z <= 0.0)
        return 1.0;
    return 1.0 + sky.a * std::exp(sky.b / cos_z);
}

double indicatrix(const CieSky& sky, double chi)
{
    const double cos_chi = std::cos(chi);
    return 1.0 + sky.c * (std::exp(sky.d * chi) - std::exp(sky.d * kPi / 2.0)) +
           sky.e * cos_chi * cos_chi;
}

}  // namespace

CieSky cie_standard_sky(int type)
{
    if (type < 1 || type > 15)
        throw std::runtime_error("CIE standard sky type " + std::to_string(type) +
                                 " does not exist (types are 1 to 15)");
    const StandardSky& s = kStandardSkies[type - 1];
    const Gradation& g = kGradation[s.gradation - 1];
    const Indicatrix& i = kIndicatrix[s.indicatrix - 1];
    CieSky sky;
    sky.type = type;
    sky.name = std::string("CIE S 011 type ") + std::to_string(type) + ": " + s.name;
    sky.a = g.a;
    sky.b = g.b;
    sky.c = i.c;
    sky.d = i.d;
    sky.e = i.e;
    return sky;
}

CieSky cie_traditional_overcast()
{
    CieSky sky;
    sky.type = 0;
    sky.name = "CIE traditional overcast sky (Moon-Spencer)";
    return sky;
}

CieSky parse_cie_sky(const std::string& text, const std::string& what)
{
    if (text == "overcast")
        return cie_traditional_overcast();
    if (text == "clear")
        return cie_standard_sky(12);
    int type = 0;
    size_t used = 0;
    try {
        type = std::stoi(text, &used);
    } catch (const std::exception&) {
        used = 0;
    }
    if (used != text.size() || used == 0 || type < 1 || type > 15)
        throw std::runtime_error(what + ": '" + text +
                                 "' is not a sky (overcast, clear, or a CIE type 1 to 15)");
    return cie_standard_sky(type);
}

double relative_luminance(const CieSky& sky, const Imath::V3d& element, const Imath::V3d& sun)
{
    const double cos_z = element.y;
    if (cos_z <= 0.0)
        return 0.0;
    if (sky.type == 0)  // Moon & Spencer 1942
        return (1.0 + 2.0 * cos_z) / 3.0;
    const double cos_zs = std::clamp(sun.y, 0.0, 1.0);
    // atan2 keeps the angle accurate near the sun, where acos of the dot product is not.
    const double chi = std::atan2(element.cross(sun).length(), element.dot(sun));
    const double zs = std::acos(cos_zs);
    // S 011 Eq. 3: normalised to the zenith, where chi = Zs and Z = 0.
    return indicatrix(sky, chi) * gradation(sky, cos_z) /
           (indicatrix(sky, zs) * gradation(sky, 1.0));
}

double horizontal_integral(const CieSky& sky, const Imath::V3d& sun, int rings)
{
    // Rings of equal width in cos Z carry equal solid angle per azimuth step.
    const int segments = 4 * rings;
    const double cell = (1.0 / rings) * (2.0 * kPi / segments);
    double sum = 0.0;
    for (int i = 0; i < rings; ++i) {
        const double cos_z = (i + 0.5) / rings;
        const double sin_z = std::sqrt(1.0 - cos_z * cos_z);
        for (int j = 0; j < segments; ++j) {
            const double phi = (j + 0.5) * 2.0 * kPi / segments;
            const Imath::V3d w(sin_z * std::cos(phi), cos_z, sin_z * std::sin(phi));
            sum += relative_luminance(sky, w, sun) * cos_z * cell;
        }
    }
    return sum;
}

}  // namespace patina::texgen
