// Colour differences as the CIE defines them: CIELAB from CIE XYZ (CIE 15:2004 §8.2.1) and
// the CIEDE2000 difference ΔE00 (CIE 142-2001; the implementation notes and test data of
// Sharma, Wu and Dalal 2005, "The CIEDE2000 color-difference formula", Color Research and
// Application 30(1)), the measure of "how different do these two colours look".
#pragma once

#include <Imath/ImathVec.h>

namespace patina {

struct Lab {
    double L = 0.0, a = 0.0, b = 0.0;
};

/// CIELAB of `xyz` relative to the reference white `white` (both CIE 1931 XYZ, any common
/// scale): L* = 116 f(Y/Yn) − 16, a* = 500 (f(X/Xn) − f(Y/Yn)), b* = 200 (f(Y/Yn) − f(Z/Zn)),
/// f(t) = t^(1/3) above (6/29)³, else t / (3 (6/29)²) + 4/29.
Lab xyz_to_lab(const Imath::V3d& xyz, const Imath::V3d& white);

/// CIEDE2000 ΔE00 between two CIELAB colours with the parametric factors kL = kC = kH = 1
/// (Sharma et al. 2005 Eqs. 1-24).
double delta_e2000(const Lab& lab1, const Lab& lab2);

}  // namespace patina
