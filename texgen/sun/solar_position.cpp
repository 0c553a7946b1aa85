#include "texgen/sun/solar_position.h"

#include "texgen/sun/delta_t.h"

#include <algorithm>
#include <cmath>
#include <initializer_list>
#include <span>

namespace patina::texgen {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegToRad = kPi / 180.0;

double rad(double deg) { return deg * kDegToRad; }
double deg(double rad) { return rad / kDegToRad; }

// Reduce an angle in degrees to [0, 360).
double limit_degrees(double d)
{
    d = std::fmod(d, 360.0);
    return d < 0.0 ? d + 360.0 : d;
}

// One periodic term A cos(B + C * JME) of the Earth's heliocentric coordinates.
struct PeriodicTerm {
    double a, b, c;
};

// ---------------------------------------------------------------------------------------
// Earth periodic terms, Reda & Andreas 2004 Table A4.2 (VSOP87 as tabulated there).
// ---------------------------------------------------------------------------------------

constexpr PeriodicTerm kL0[] = {
    {175347046.0, 0.0, 0.0}, {3341656.0, 4.6692568, 6283.07585},
    {34894.0, 4.6261, 12566.1517}, {3497.0, 2.7441, 5753.3849}, {3418.0, 2.8289, 3.5231},
    {3136.0, 3.6277, 77713.7715}, {2676.0, 4.4181, 7860.4194}, {2343.0, 6.1352, 3930.2097},
    {1324.0, 0.7425, 11506.7698}, {1273.0, 2.0371, 529.691}, {1199.0, 1.1096, 1577.3435},
    {990.0, 5.233, 5884.927}, {902.0, 2.045, 26.298}, {857.0, 3.508, 398.149},
    {780.0, 1.179, 5223.694}, {753.0, 2.533, 5507.553}, {505.0, 4.583, 18849.228},
    {492.0, 4.205, 775.523}, {357.0, 2.92, 0.067}, {317.0, 5.849, 11790.629},
    {284.0, 1.899, 796.298}, {271.0, 0.315, 10977.079}, {243.0, 0.345, 5486.778},
    {206.0, 4.806, 2544.314}, {205.0, 1.869, 5573.143}, {202.0, 2.458, 6069.777},
    {156.0, 0.833, 213.299}, {132.0, 3.411, 2942.463}, {126.0, 1.083, 20.775},
    {115.0, 0.645, 0.98}, {103.0, 0.636, 4694.003}, {102.0, 0.976, 15720.839},
    {102.0, 4.267, 7.114}, {99.0, 6.21, 2146.17}, {98.0, 0.68, 155.42},
    {86.0, 5.98, 161000.69}, {85.0, 1.3, 6275.96}, {85.0, 3.67, 71430.7},
    {80.0, 1.81, 17260.15}, {79.0, 3.04, 12036.46}, {75.0, 1.76, 5088.63},
    {74.0, 3.5, 3154.69}, {74.0, 4.68, 801.82}, {70.0, 0.83, 9437.76}, {62.0, 3.98, 8827.39},
    {61.0, 1.82, 7084.9}, {57.0, 2.78, 6286.6}, {56.0, 4.39, 14143.5}, {56.0, 3.47, 6279.55},
    {52.0, 0.19, 12139.55}, {52.0, 1.33, 1748.02}, {51.0, 0.28, 5856.48},
    {49.0, 0.49, 1194.45}, {41.0, 5.37, 8429.24}, {41.0, 2.4, 19651.05},
    {39.0, 6.17, 10447.39}, {37.0, 6.04, 10213.29}, {37.0, 2.57, 1059.38},
    {36.0, 1.71, 2352.87}, {36.0, 1.78, 6812.77}, {33.0, 0.59, 17789.85},
    {30.0, 0.44, 83996.85}, {30.0, 2.74, 1349.87}, {25.0, 3.16, 4690.48},
};
constexpr PeriodicTerm kL1[] = {
    {628331966747.0, 0.0, 0.0}, {206059.0, 2.678235, 6283.07585},
    {4303.0, 2.6351, 12566.1517}, {425.0, 1.59, 3.523}, {119.0, 5.796, 26.298},
    {109.0, 2.966, 1577.344}, {93.0, 2.59, 18849.23}, {72.0, 1.14, 529.69},
    {68.0, 1.87, 398.15}, {67.0, 4.41, 5507.55}, {59.0, 2.89, 5223.69}, {56.0, 2.17, 155.42},
    {45.0, 0.4, 796.3}, {36.0, 0.47, 775.52}, {29.0, 2.65, 7.11}, {21.0, 5.34, 0.98},
    {19.0, 1.85, 5486.78}, {19.0, 4.97, 213.3}, {17.0, 2.99, 6275.96}, {16.0, 0.03, 2544.31},
    {16.0, 1.43, 2146.17}, {15.0, 1.21, 10977.08}, {12.0, 2.83, 1748.02},
    {12.0, 3.26, 5088.63}, {12.0, 5.27, 1194.45}, {12.0, 2.08, 4694.0},
    {11.0, 0.77, 553.57}, {10.0, 1.3, 6286.6}, {10.0, 4.24, 1349.87}, {9.0, 2.7, 242.73},
    {9.0, 5.64, 951.72}, {8.0, 5.3, 2352.87}, {6.0, 2.65, 9437.76}, {6.0, 4.67, 4690.48},
};
constexpr PeriodicTerm kL2[] = {
    {52919.0, 0.0, 0.0}, {8720.0, 1.0721, 6283.0758}, {309.0, 0.867, 12566.152},
    {27.0, 0.05, 3.52}, {16.0, 5.19, 26.3}, {16.0, 3.68, 155.42}, {10.0, 0.76, 18849.23},
    {9.0, 2.06, 77713.77}, {7.0, 0.83, 775.52}, {5.0, 4.66, 1577.34}, {4.0, 1.03, 7.11},
    {4.0, 3.44, 5573.14}, {3.0, 5.14, 796.3}, {3.0, 6.05, 5507.55}, {3.0, 1.19, 242.73},
    {3.0, 6.12, 529.69}, {3.0, 0.31, 398.15}, {3.0, 2.28, 553.57}, {2.0, 4.38, 5223.69},
    {2.0, 3.75, 0.98},
};
constexpr PeriodicTerm kL3[] = {
    {289.0, 5.844, 6283.076}, {35.0, 0.0, 0.0}, {17.0, 5.49, 12566.15}, {3.0, 5.2, 155.42},
    {1.0, 4.72, 3.52}, {1.0, 5.3, 18849.23}, {1.0, 5.97, 242.73},
};
constexpr PeriodicTerm kL4[] = {
    {114.0, 3.142, 0.0}, {8.0, 4.13, 6283.08}, {1.0, 3.84, 12566.15},
};
constexpr PeriodicTerm kL5[] = {
    {1.0, 3.14, 0.0},
};
constexpr PeriodicTerm kB0[] = {
    {280.0, 3.199, 84334.662}, {102.0, 5.422, 5507.553}, {80.0, 3.88, 5223.69},
    {44.0, 3.7, 2352.87}, {32.0, 4.0, 1577.34},
};
constexpr PeriodicTerm kB1[] = {
    {9.0, 3.9, 5507.55}, {6.0, 1.73, 5223.69},
};
constexpr PeriodicTerm kR0[] = {
    {100013989.0, 0.0, 0.0}, {1670700.0, 3.0984635, 6283.07585},
    {13956.0, 3.05525, 12566.1517}, {3084.0, 5.1985, 77713.7715},
    {1628.0, 1.1739, 5753.3849}, {1576.0, 2.8469, 7860.4194}, {925.0, 5.453, 11506.77},
    {542.0, 4.564, 3930.21}, {472.0, 3.661, 5884.927}, {346.0, 0.964, 5507.553},
    {329.0, 5.9, 5223.694}, {307.0, 0.299, 5573.143}, {243.0, 4.273, 11790.629},
    {212.0, 5.847, 1577.344}, {186.0, 5.022, 10977.079}, {175.0, 3.012, 18849.228},
    {110.0, 5.055, 5486.778}, {98.0, 0.89, 6069.78}, {86.0, 5.69, 15720.84},
    {86.0, 1.27, 161000.69}, {65.0, 0.27, 17260.15}, {63.0, 0.92, 529.69},
    {57.0, 2.01, 83996.85}, {56.0, 5.24, 71430.7}, {49.0, 3.25, 2544.31},
    {47.0, 2.58, 775.52}, {45.0, 5.54, 9437.76}, {43.0, 6.01, 6275.96}, {39.0, 5.36, 4694.0},
    {38.0, 2.39, 8827.39}, {37.0, 0.83, 19651.05}, {37.0, 4.9, 12139.55},
    {36.0, 1.67, 12036.46}, {35.0, 1.84, 2942.46}, {33.0, 0.24, 7084.9},
    {32.0, 0.18, 5088.63}, {32.0, 1.78, 398.15}, {28.0, 1.21, 6286.6}, {28.0, 1.9, 6279.55},
    {26.0, 4.59, 10447.39},
};
constexpr PeriodicTerm kR1[] = {
    {103019.0, 1.10749, 6283.07585}, {1721.0, 1.0644, 12566.1517}, {702.0, 3.142, 0.0},
    {32.0, 1.02, 18849.23}, {31.0, 2.84, 5507.55}, {25.0, 1.32, 5223.69},
    {18.0, 1.42, 1577.34}, {10.0, 5.91, 10977.08}, {9.0, 1.42, 6275.96},
    {9.0, 0.27, 5486.78},
};
constexpr PeriodicTerm kR2[] = {
    {4359.0, 5.7846, 6283.0758}, {124.0, 5.579, 12566.152}, {12.0, 3.14, 0.0},
    {9.0, 3.63, 77713.77}, {6.0, 1.87, 5573.14}, {3.0, 5.47, 18849.23},
};
constexpr PeriodicTerm kR3[] = {
    {145.0, 4.273, 6283.076}, {7.0, 3.92, 12566.15},
};
constexpr PeriodicTerm kR4[] = {
    {4.0, 2.56, 6283.08},
};

// ---------------------------------------------------------------------------------------
// Nutation in longitude and obliquity, Reda & Andreas 2004 Table A4.3: the multiples
// Y0..Y4 of X0..X4 in each argument, and the coefficients a, b (longitude) and c, d
// (obliquity) in units of 0.0001 arcsec.
// ---------------------------------------------------------------------------------------

struct NutationTerm {
    int y[5];
    double a, b, c, d;
};

constexpr NutationTerm kNutation[] = {
    {{0, 0, 0, 0, 1}, -171996, -174.2, 92025, 8.9},
    {{-2, 0, 0, 2, 2}, -13187, -1.6, 5736, -3.1},
    {{0, 0, 0, 2, 2}, -2274, -0.2, 977, -0.5},
    {{0, 0, 0, 0, 2}, 2062, 0.2, -895, 0.5},
    {{0, 1, 0, 0, 0}, 1426, -3.4, 54, -0.1},
    {{0, 0, 1, 0, 0}, 712, 0.1, -7, 0},
    {{-2, 1, 0, 2, 2}, -517, 1.2, 224, -0.6},
    {{0, 0, 0, 2, 1}, -386, -0.4, 200, 0},
    {{0, 0, 1, 2, 2}, -301, 0, 129, -0.1},
    {{-2, -1, 0, 2, 2}, 217, -0.5, -95, 0.3},
    {{-2, 0, 1, 0, 0}, -158, 0, 0, 0},
    {{-2, 0, 0, 2, 1}, 129, 0.1, -70, 0},
    {{0, 0, -1, 2, 2}, 123, 0, -53, 0},
    {{2, 0, 0, 0, 0}, 63, 0, 0, 0},
    {{0, 0, 1, 0, 1}, 63, 0.1, -33, 0},
    {{2, 0, -1, 2, 2}, -59, 0, 26, 0},
    {{0, 0, -1, 0, 1}, -58, -0.1, 32, 0},
    {{0, 0, 1, 2, 1}, -51, 0, 27, 0},
    {{-2, 0, 2, 0, 0}, 48, 0, 0, 0},
    {{0, 0, -2, 2, 1}, 46, 0, -24, 0},
    {{2, 0, 0, 2, 2}, -38, 0, 16, 0},
    {{0, 0, 2, 2, 2}, -31, 0, 13, 0},
    {{0, 0, 2, 0, 0}, 29, 0, 0, 0},
    {{-2, 0, 1, 2, 2}, 29, 0, -12, 0},
    {{0, 0, 0, 2, 0}, 26, 0, 0, 0},
    {{-2, 0, 0, 2, 0}, -22, 0, 0, 0},
    {{0, 0, -1, 2, 1}, 21, 0, -10, 0},
    {{0, 2, 0, 0, 0}, 17, -0.1, 0, 0},
    {{2, 0, -1, 0, 1}, 16, 0, -8, 0},
    {{-2, 2, 0, 2, 2}, -16, 0.1, 7, 0},
    {{0, 1, 0, 0, 1}, -15, 0, 9, 0},
    {{-2, 0, 1, 0, 1}, -13, 0, 7, 0},
    {{0, -1, 0, 0, 1}, -12, 0, 6, 0},
    {{0, 0, 2, -2, 0}, 11, 0, 0, 0},
    {{2, 0, -1, 2, 1}, -10, 0, 5, 0},
    {{2, 0, 1, 2, 2}, -8, 0, 3, 0},
    {{0, 1, 0, 2, 2}, 7, 0, -3, 0},
    {{-2, 1, 1, 0, 0}, -7, 0, 0, 0},
    {{0, -1, 0, 2, 2}, -7, 0, 3, 0},
    {{2, 0, 0, 2, 1}, -7, 0, 3, 0},
    {{2, 0, 1, 0, 0}, 6, 0, 0, 0},
    {{-2, 0, 2, 2, 2}, 6, 0, -3, 0},
    {{-2, 0, 1, 2, 1}, 6, 0, -3, 0},
    {{2, 0, -2, 0, 1}, -6, 0, 3, 0},
    {{2, 0, 0, 0, 1}, -6, 0, 3, 0},
    {{0, -1, 1, 0, 0}, 5, 0, 0, 0},
    {{-2, -1, 0, 2, 1}, -5, 0, 3, 0},
    {{-2, 0, 0, 0, 1}, -5, 0, 3, 0},
    {{0, 0, 2, 2, 1}, -5, 0, 3, 0},
    {{-2, 0, 2, 0, 1}, 4, 0, 0, 0},
    {{-2, 1, 0, 2, 1}, 4, 0, 0, 0},
    {{0, 0, 1, -2, 0}, 4, 0, 0, 0},
    {{-1, 0, 1, 0, 0}, -4, 0, 0, 0},
    {{-2, 1, 0, 0, 0}, -4, 0, 0, 0},
    {{1, 0, 0, 0, 0}, -4, 0, 0, 0},
    {{0, 0, 1, 2, 0}, 3, 0, 0, 0},
    {{0, 0, -2, 2, 2}, -3, 0, 0, 0},
    {{-1, -1, 1, 0, 0}, -3, 0, 0, 0},
    {{0, 1, 1, 0, 0}, -3, 0, 0, 0},
    {{0, -1, 1, 2, 2}, -3, 0, 0, 0},
    {{2, -1, -1, 2, 2}, -3, 0, 0, 0},
    {{0, 0, 3, 2, 2}, -3, 0, 0, 0},
    {{2, -1, 0, 2, 2}, -3, 0, 0, 0},
};

// Eq. 9: the sum of A cos(B + C JME) over one table.
double periodic_sum(std::span<const PeriodicTerm> terms, double jme)
{
    double sum = 0.0;
    for (const PeriodicTerm& t : terms)
        sum += t.a * std::cos(t.b + t.c * jme);
    return sum;
}

// Eq. 10-11: L, B or R from its series L0 + L1 JME + L2 JME^2 + ..., in 1e-8 units.
double earth_series(std::initializer_list<std::span<const PeriodicTerm>> series, double jme)
{
    double value = 0.0;
    double power = 1.0;
    for (std::span<const PeriodicTerm> terms : series) {
        value += periodic_sum(terms, jme) * power;
        power *= jme;
    }
    return value / 1e8;
}

double polynomial_3(double x, double c0, double c1, double c2, double c3)
{
    return c0 + x * (c1 + x * (c2 + x * c3));
}

}  // namespace

SolarPosition solar_position(double jd_ut, const SolarSite& site)
{
    SolarPosition p;
    // §3.1: Julian day, ephemeris day, centuries and millennia from J2000.0 (Eq. 4-8).
    p.julian_day = jd_ut;
    p.delta_t_s =
        site.delta_t_s.value_or(delta_t_espenak_meeus(decimal_year_of_julian_day(jd_ut)));
    p.julian_ephemeris_day = jd_ut + p.delta_t_s / 86400.0;
    const double jc = (jd_ut - 2451545.0) / 36525.0;
    const double jce = (p.julian_ephemeris_day - 2451545.0) / 36525.0;
    const double jme = jce / 10.0;

    // §3.2: Earth heliocentric longitude, latitude and radius vector (Eq. 9-14).
    p.heliocentric_longitude_deg =
        limit_degrees(deg(earth_series({kL0, kL1, kL2, kL3, kL4, kL5}, jme)));
    p.heliocentric_latitude_deg = deg(earth_series({kB0, kB1}, jme));
    p.earth_radius_vector_au = earth_series({kR0, kR1, kR2, kR3, kR4}, jme);

    // §3.3: geocentric longitude and latitude (Eq. 15-16).
    const double theta = limit_degrees(p.heliocentric_longitude_deg + 180.0);
    const double beta = -p.heliocentric_latitude_deg;

    // §3.4: nutation in longitude and obliquity (Eq. 15-23). X0 mean elongation of the
    // moon from the sun, X1 mean anomaly of the sun, X2 of the moon, X3 the moon's argument
    // of latitude, X4 the longitude of the moon's ascending node, all in degrees.
    const double x[5] = {
        polynomial_3(jce, 297.85036, 445267.111480, -0.0019142, 1.0 / 189474.0),
        polynomial_3(jce, 357.52772, 35999.050340, -0.0001603, -1.0 / 300000.0),
        polynomial_3(jce, 134.96298, 477198.867398, 0.0086972, 1.0 / 56250.0),
        polynomial_3(jce, 93.27191, 483202.017538, -0.0036825, 1.0 / 327270.0),
        polynomial_3(jce, 125.04452, -1934.136261, 0.0020708, 1.0 / 450000.0),
    };
    double sum_psi = 0.0, sum_epsilon = 0.0;
    for (const NutationTerm& t : kNutation) {
        double argument = 0.0;
        for (int j = 0; j < 5; ++j)
            argument += x[j] * t.y[j];
        argument = rad(argument);
        sum_psi += (t.a + t.b * jce) * std::sin(argument);
        sum_epsilon += (t.c + t.d * jce) * std::cos(argument);
    }
    p.nutation_longitude_deg = sum_psi / 36000000.0;
    p.nutation_obliquity_deg = sum_epsilon / 36000000.0;

    // §3.5: true obliquity of the ecliptic (Eq. 24-25), U = JME / 10, in arcseconds.
    const double u = jme / 10.0;
    static constexpr double kObliquity[] = {84381.448, -4680.93, -1.55,  1999.25,
                                            -51.38,    -249.67,  -39.05, 7.12,
                                            27.87,     5.79,     2.45};
    double epsilon0 = 0.0;
    for (int i = 10; i >= 0; --i)
        epsilon0 = epsilon0 * u + kObliquity[i];
    p.true_obliquity_deg = epsilon0 / 3600.0 + p.nutation_obliquity_deg;

    // §3.6-3.7: aberration correction and apparent sun longitude (Eq. 26-27).
    p.aberration_deg = -20.4898 / (3600.0 * p.earth_radius_vector_au);
    p.apparent_longitude_deg = theta + p.nutation_longitude_deg + p.aberration_deg;

    // §3.8: apparent sidereal time at Greenwich (Eq. 28-29).
    const double nu0 = limit_degrees(280.46061837 + 360.98564736629 * (jd_ut - 2451545.0) +
                                     jc * jc * (0.000387933 - jc / 38710000.0));
    p.apparent_sidereal_time_deg =
        nu0 + p.nutation_longitude_deg * std::cos(rad(p.true_obliquity_deg));

    // §3.9-3.10: geocentric right ascension and declination (Eq. 30-31).
    const double lambda = rad(p.apparent_longitude_deg);
    const double epsilon = rad(p.true_obliquity_deg);
    const double beta_rad = rad(beta);
    p.right_ascension_deg =
        limit_degrees(deg(std::atan2(std::sin(lambda) * std::cos(epsilon) -
                                         std::tan(beta_rad) * std::sin(epsilon),
                                     std::cos(lambda))));
    p.declination_deg = deg(std::asin(std::sin(beta_rad) * std::cos(epsilon) +
                                      std::cos(beta_rad) * std::sin(epsilon) * std::sin(lambda)));

    // §3.11: observer local hour angle, measured westward from south (Eq. 32).
    p.hour_angle_deg = limit_degrees(p.apparent_sidereal_time_deg + site.longitude_deg -
                                     p.right_ascension_deg);

    // §3.12: topocentric right ascension and declination: parallax of the sun seen from
    // the observer's place on the ellipsoid rather than the Earth's centre (Eq. 33-39).
    const double xi = rad(8.794 / (3600.0 * p.earth_radius_vector_au));
    const double phi = rad(site.latitude_deg);
    const double u_term = std::atan(0.99664719 * std::tan(phi));
    const double x_term = std::cos(u_term) + site.elevation_m / 6378140.0 * std::cos(phi);
    const double y_term =
        0.99664719 * std::sin(u_term) + site.elevation_m / 6378140.0 * std::sin(phi);
    const double h = rad(p.hour_angle_deg);
    const double delta = rad(p.declination_deg);
    const double denominator = std::cos(delta) - x_term * std::sin(xi) * std::cos(h);
    const double delta_alpha =
        std::atan2(-x_term * std::sin(xi) * std::sin(h), denominator);
    p.topocentric_right_ascension_deg = p.right_ascension_deg + deg(delta_alpha);
    const double delta_prime = std::atan2(
        (std::sin(delta) - y_term * std::sin(xi)) * std::cos(delta_alpha), denominator);
    p.topocentric_declination_deg = deg(delta_prime);

    // §3.13: topocentric local hour angle (Eq. 40).
    p.topocentric_hour_angle_deg = p.hour_angle_deg - deg(delta_alpha);
    const double h_prime = rad(p.topocentric_hour_angle_deg);

    // §3.14: topocentric elevation with refraction, and zenith (Eq. 41-44). Refraction
    // only while the sun's upper limb can be above the horizon.
    p.elevation_no_refraction_deg = deg(std::asin(
        std::sin(phi) * std::sin(delta_prime) +
        std::cos(phi) * std::cos(delta_prime) * std::cos(h_prime)));
    const double e0 = p.elevation_no_refraction_deg;
    p.refraction_deg = 0.0;
    constexpr double kSunRadiusDeg = 0.26667;
    if (e0 >= -(kSunRadiusDeg + site.atmospheric_refraction_deg))
        p.refraction_deg = (site.pressure_mbar / 1010.0) * (283.0 / (273.0 + site.temperature_c)) *
                           1.02 / (60.0 * std::tan(rad(e0 + 10.3 / (e0 + 5.11))));
    p.elevation_deg = e0 + p.refraction_deg;
    p.zenith_deg = 90.0 - p.elevation_deg;

    // §3.15: topocentric astronomers' azimuth (westward from south), then the navigators'
    // azimuth eastward from north (Eq. 45-46).
    const double gamma = deg(std::atan2(std::sin(h_prime), std::cos(h_prime) * std::sin(phi) -
                                                           std::tan(delta_prime) * std::cos(phi)));
    p.azimuth_deg = limit_degrees(limit_degrees(gamma) + 180.0);
    return p;
}

double incidence_angle_deg(const SolarPosition& sun, double slope_deg,
                           double surface_azimuth_rotation_deg)
{
    // Reda & Andreas Eq. 47, with the astronomers' azimuth Gamma = Phi - 180.
    const double zenith = rad(sun.zenith_deg);
    const double slope = rad(slope_deg);
    const double gamma = rad(sun.azimuth_deg - 180.0);
    const double cos_i = std::cos(zenith) * std::cos(slope) +
                         std::sin(slope) * std::sin(zenith) *
                             std::cos(gamma - rad(surface_azimuth_rotation_deg));
    return deg(std::acos(std::clamp(cos_i, -1.0, 1.0)));
}

Imath::V3d sun_direction(double zenith_deg, double azimuth_deg)
{
    const double z = rad(zenith_deg);
    const double a = rad(azimuth_deg);
    // East is +x, north -z: azimuth 90 (east) gives +x, azimuth 0 (north) gives -z.
    return Imath::V3d(std::sin(z) * std::sin(a), std::cos(z), -std::sin(z) * std::cos(a));
}

}  // namespace patina::texgen
