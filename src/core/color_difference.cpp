#include "core/color_difference.h"

#include <cmath>

namespace patina {

namespace {

    constexpr double kPi = 3.14159265358979323846;

    double f_lab(double t)
    {
        constexpr double d = 6.0 / 29.0;
        return t > d * d * d ? std::cbrt(t) : t / (3.0 * d * d) + 4.0 / 29.0;
    }

    double degrees(double radians) { return radians * 180.0 / kPi; }
    double radians(double degrees) { return degrees * kPi / 180.0; }

}  // namespace

Lab xyz_to_lab(const Imath::V3d& xyz, const Imath::V3d& white)
{
    const double fx = f_lab(xyz.x / white.x), fy = f_lab(xyz.y / white.y),
                 fz = f_lab(xyz.z / white.z);
    return {116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)};
}

double delta_e2000(const Lab& lab1, const Lab& lab2)
{
    // Sharma et al. 2005, Eqs. 2-7: a' scaled by G from the mean chroma.
    const double c1 = std::hypot(lab1.a, lab1.b), c2 = std::hypot(lab2.a, lab2.b);
    const double c_mean = 0.5 * (c1 + c2);
    const double c7 = std::pow(c_mean, 7.0);
    const double g = 0.5 * (1.0 - std::sqrt(c7 / (c7 + std::pow(25.0, 7.0))));
    const double a1 = (1.0 + g) * lab1.a, a2 = (1.0 + g) * lab2.a;
    const double cp1 = std::hypot(a1, lab1.b), cp2 = std::hypot(a2, lab2.b);
    auto hue = [](double b, double a) {
        if (b == 0.0 && a == 0.0)
            return 0.0;
        const double h = degrees(std::atan2(b, a));
        return h < 0.0 ? h + 360.0 : h;
    };
    const double hp1 = hue(lab1.b, a1), hp2 = hue(lab2.b, a2);

    // Eqs. 8-12: the differences.
    const double dl = lab2.L - lab1.L, dc = cp2 - cp1;
    double dh = 0.0;
    if (cp1 * cp2 != 0.0) {
        dh = hp2 - hp1;
        if (dh > 180.0)
            dh -= 360.0;
        else if (dh < -180.0)
            dh += 360.0;
    }
    const double dH = 2.0 * std::sqrt(cp1 * cp2) * std::sin(radians(0.5 * dh));

    // Eqs. 13-22: the weights.
    const double l_mean = 0.5 * (lab1.L + lab2.L), cp_mean = 0.5 * (cp1 + cp2);
    double hp_mean = hp1 + hp2;
    if (cp1 * cp2 != 0.0) {
        if (std::abs(hp1 - hp2) <= 180.0)
            hp_mean *= 0.5;
        else
            hp_mean = hp_mean < 360.0 ? 0.5 * (hp_mean + 360.0) : 0.5 * (hp_mean - 360.0);
    }
    const double t = 1.0 - 0.17 * std::cos(radians(hp_mean - 30.0)) +
                     0.24 * std::cos(radians(2.0 * hp_mean)) +
                     0.32 * std::cos(radians(3.0 * hp_mean + 6.0)) -
                     0.20 * std::cos(radians(4.0 * hp_mean - 63.0));
    const double d_theta = 30.0 * std::exp(-std::pow((hp_mean - 275.0) / 25.0, 2.0));
    const double cp7 = std::pow(cp_mean, 7.0);
    const double rc = 2.0 * std::sqrt(cp7 / (cp7 + std::pow(25.0, 7.0)));
    const double l50 = (l_mean - 50.0) * (l_mean - 50.0);
    const double sl = 1.0 + 0.015 * l50 / std::sqrt(20.0 + l50);
    const double sc = 1.0 + 0.045 * cp_mean;
    const double sh = 1.0 + 0.015 * cp_mean * t;
    const double rt = -std::sin(radians(2.0 * d_theta)) * rc;

    // Eq. 23 with kL = kC = kH = 1.
    const double x = dl / sl, y = dc / sc, z = dH / sh;
    return std::sqrt(x * x + y * y + z * z + rt * y * z);
}

}  // namespace patina
