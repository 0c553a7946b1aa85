// Sky luminance distributions: the 15 CIE standard general skies (CIE S 011/E:2003 =
// ISO 15469:2004) and the traditional CIE overcast sky of Moon & Spencer (1942), adopted
// by the CIE in 1955 and kept beside the general skies by S 011.
//
// General sky, relative to the zenith (S 011 Eq. 1-3):
//   L(chi, Z) / Lz = f(chi) phi(Z) / (f(Zs) phi(0)),
//   phi(Z) = 1 + a exp(b / cos Z)  (phi = 1 at the horizon), gradation;
//   f(chi) = 1 + c (exp(d chi) - exp(d pi/2)) + e cos^2 chi, scattering indicatrix;
// Z the element's zenith angle, Zs the sun's, chi the angle between element and sun.
// Traditional overcast: L(Z) / Lz = (1 + 2 cos Z) / 3.
#pragma once

#include <Imath/ImathVec.h>

#include <string>

namespace patina::texgen {

struct CieSky {
    /// 1..15 for the standard general skies; 0 for the traditional overcast sky.
    int type = 0;
    std::string name;  ///< e.g. "CIE traditional overcast (Moon-Spencer)"
    double a = 0, b = 0, c = 0, d = 0, e = 0;  ///< S 011 Table 1 parameters
};

/// CIE S 011 Table 1: standard general sky `type` (1..15); throws otherwise.
CieSky cie_standard_sky(int type);
/// The traditional CIE overcast sky (Moon & Spencer 1942; CIE 1955).
CieSky cie_traditional_overcast();
/// "overcast" (the traditional overcast sky), "clear" (type 12, standard clear sky, low
/// luminance turbidity) or a type number "1".."15"; throws naming `what` otherwise.
CieSky parse_cie_sky(const std::string& text, const std::string& what);

/// Luminance of the sky element in unit direction `element` relative to the zenith
/// luminance, with the sun in unit direction `sun` (world frame, +y up). 0 for elements
/// at or below the horizon. The sun may be below the horizon (twilight skies are still
/// defined by the formula, clamped to the horizon for f(Zs)).
double relative_luminance(const CieSky& sky, const Imath::V3d& element, const Imath::V3d& sun);

/// Integral over the upper hemisphere of relative_luminance * cos Z d(omega): the
/// diffuse horizontal irradiance per unit zenith radiance (7 pi / 9 for the traditional
/// overcast sky). Midpoint rule on `rings` x 4 `rings` cells of equal solid angle.
double horizontal_integral(const CieSky& sky, const Imath::V3d& sun, int rings = 90);

}  // namespace patina::texgen
