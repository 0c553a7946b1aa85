// ΔT from the date (Espenak & Meeus 2006) against observed values, and what it does to the
// sun's position from 1900 to 2050.
#include "texgen/sun/date_time.h"
#include "texgen/sun/delta_t.h"
#include "texgen/sun/solar_position.h"

#include <gtest/gtest.h>

#include <cmath>

#include "texgen/spa_example_site.h"

namespace pt = patina::texgen;
using patina::test::spa_example_site;

namespace {

// Observed ΔT at the start of the year, s: Espenak & Meeus 2006 (NASA/TP-2006-214141)
// Table 2.3 "Values of ΔT" for 1900-2000 (from Morrison & Stephenson 2004 and the
// Astronomical Almanac), IERS Bulletin A / USNO for 2010 and 2020.
struct Observed {
    double year, delta_t_s;
};
constexpr Observed kObserved[] = {
    {1900.0, -2.7}, {1910.0, 10.4}, {1920.0, 21.1}, {1930.0, 24.0}, {1940.0, 24.3},
    {1950.0, 29.1}, {1960.0, 33.2}, {1970.0, 40.2}, {1980.0, 50.5}, {1990.0, 56.9},
    {2000.0, 63.8}, {2010.0, 66.1}, {2020.0, 69.4},
};

// The angular distance between two suns given by zenith and azimuth, degrees.
double separation_deg(const pt::SolarPosition& a, const pt::SolarPosition& b)
{
    const Imath::V3d da = pt::sun_direction(a.zenith_deg, a.azimuth_deg);
    const Imath::V3d db = pt::sun_direction(b.zenith_deg, b.azimuth_deg);
    return std::atan2((da % db).length(), da ^ db) * 180.0 / M_PI;
}

}  // namespace

TEST(DeltaT, PolynomialsFollowTheObservedValues)
{
    // Espenak & Meeus give their fit as good to about a second over the 20th century; the
    // 2005-2050 polynomial is an extrapolation made in 2006 (2020: 71.6 s, observed 69.4).
    for (const Observed& o : kObserved)
        EXPECT_NEAR(pt::delta_t_espenak_meeus(o.year), o.delta_t_s, o.year > 2005 ? 2.5 : 1.0)
            << o.year;
}

TEST(DeltaT, PiecesMeetAtTheirBoundaries)
{
    // Consecutive polynomials agree to within a second where they meet (Espenak & Meeus
    // chose the intervals so), except 2050, where the published pieces differ by ~0.1 s.
    for (const double y : {1600.0, 1700.0, 1800.0, 1860.0, 1900.0, 1920.0, 1941.0, 1961.0,
                           1986.0, 2005.0, 2050.0, 2150.0})
        EXPECT_NEAR(pt::delta_t_espenak_meeus(y - 1e-9), pt::delta_t_espenak_meeus(y), 1.0) << y;
}

TEST(DeltaT, DecimalYearOfJulianDay)
{
    // Meeus, Astronomical Algorithms ch. 7: 2000-01-01 0h UT is JD 2451544.5; 1900-01-01
    // 0h is JD 2415020.5.
    EXPECT_NEAR(pt::decimal_year_of_julian_day(2451544.5), 2000.0, 1e-12);
    EXPECT_NEAR(pt::decimal_year_of_julian_day(2415020.5), 1900.0, 1e-3);
}

TEST(DeltaT, ReportExampleWithoutGivingDeltaT)
{
    // Reda & Andreas 2004 Table A5.2 used ΔT = 67 s; from the date the model gives 64.5 s,
    // and the published angles still hold to 0.001 deg.
    pt::SolarSite site = spa_example_site();
    site.delta_t_s.reset();
    const pt::DateTime local = pt::parse_date_time("2003-10-17T12:30:30", "test");
    const pt::SolarPosition p = pt::solar_position(pt::julian_day(local, -7.0), site);
    EXPECT_NEAR(p.delta_t_s, 64.5, 0.1);
    EXPECT_NEAR(p.zenith_deg, 50.11162, 1e-3);
    EXPECT_NEAR(p.azimuth_deg, 194.34024, 1e-3);
    EXPECT_NEAR(pt::incidence_angle_deg(p, 30.0, -10.0), 25.18700, 1e-3);
}

TEST(DeltaT, SunFrom1900To2050MatchesTheObservedDeltaTWithin0001Deg)
{
    // The same site at 10:00 local on 1 January, April, July and October of each year of
    // the table: the position with ΔT from the date against the position with the
    // observed ΔT. For 2030-2050, where nothing is observed yet, against ΔT held at its
    // 2020 value (it has hardly moved since 2016, IERS Bulletin A), the least the
    // extrapolation (93 s in 2050) could be off by.
    double worst_model = 0.0, worst_fixed = 0.0;
    for (const Observed& o : kObserved) {
        for (const int month : {1, 4, 7, 10}) {
            pt::DateTime local;
            local.year = static_cast<int>(o.year);
            local.month = month;
            local.day = 1;
            local.hour = 10;
            const double jd = pt::julian_day(local, -7.0);
            pt::SolarSite observed = spa_example_site(), model = observed, fixed = observed;
            observed.delta_t_s = o.delta_t_s;
            model.delta_t_s.reset();
            fixed.delta_t_s = 69.0;  // the fixed default before ΔT came from the date
            const pt::SolarPosition truth = pt::solar_position(jd, observed);
            worst_model = std::max(worst_model, separation_deg(pt::solar_position(jd, model), truth));
            worst_fixed = std::max(worst_fixed, separation_deg(pt::solar_position(jd, fixed), truth));
        }
    }
    EXPECT_LT(worst_model, 1e-4);  // ΔT within 2.5 s: 3e-5 deg
    // The fixed 69 s is 72 s off in 1900: 8e-4 deg, the defect this model removes.
    EXPECT_GT(worst_fixed, 5e-4);
    for (int year = 2030; year <= 2050; year += 10) {
        pt::DateTime local;
        local.year = year;
        local.month = 6;
        local.day = 21;
        local.hour = 10;
        const double jd = pt::julian_day(local, -7.0);
        pt::SolarSite trend = spa_example_site(), model = trend;
        trend.delta_t_s = 69.4;
        model.delta_t_s.reset();
        EXPECT_LT(separation_deg(pt::solar_position(jd, model), pt::solar_position(jd, trend)),
                  1e-3)
            << year;
    }
}
