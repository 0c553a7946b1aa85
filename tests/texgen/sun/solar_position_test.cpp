// NREL SPA against the example published in its report, and date-time handling.
#include "texgen/sun/date_time.h"
#include "texgen/sun/solar_position.h"

#include "test_util.h"

#include <gtest/gtest.h>

#include <cmath>

#include "texgen/spa_example_site.h"

namespace pt = patina::texgen;
using patina::test::spa_example_site;

namespace {

// Reda & Andreas 2004 (NREL/TP-560-34302, rev. 2008), Table A5.1 input: 2003-10-17
// 12:30:30 local time, time zone -7, delta T 67 s, Golden CO.
pt::SolarPosition spa_example()
{
    const pt::DateTime local = pt::parse_date_time("2003-10-17T12:30:30", "test");
    return pt::solar_position(pt::julian_day(local, -7.0), spa_example_site());
}

}  // namespace

TEST(SolarPosition, ReportExampleIntermediates)
{
    const pt::SolarPosition p = spa_example();
    // Published values, Reda & Andreas 2004 Table A5.2 (to the digits printed there).
    EXPECT_NEAR(p.julian_day, 2452930.312847, 0.5e-6);
    EXPECT_NEAR(p.heliocentric_longitude_deg, 24.0182616917, 0.5e-10 * 24 + 1e-9);
    EXPECT_NEAR(p.heliocentric_latitude_deg, -0.0001011219, 1e-10);
    EXPECT_NEAR(p.earth_radius_vector_au, 0.9965422974, 1e-10);
    EXPECT_NEAR(p.nutation_longitude_deg, -0.00399840, 0.5e-8);
    EXPECT_NEAR(p.nutation_obliquity_deg, 0.00166657, 0.5e-8);
    EXPECT_NEAR(p.true_obliquity_deg, 23.440465, 0.5e-6);
    EXPECT_NEAR(p.hour_angle_deg, 11.105902, 0.5e-6);
    EXPECT_NEAR(p.right_ascension_deg, 202.22741, 0.5e-5);
    EXPECT_NEAR(p.declination_deg, -9.31434, 0.5e-5);
}

TEST(SolarPosition, ReportExampleTopocentric)
{
    const pt::SolarPosition p = spa_example();
    // Table A5.2: topocentric zenith 50.11162, azimuth 194.34024 (eastward from north),
    // incidence 25.18700 on a surface of slope 30 deg, azimuth rotation -10 deg. The
    // issue asks for 0.01 deg; the report's precision is 1e-5 deg.
    EXPECT_NEAR(p.zenith_deg, 50.11162, 1e-5);
    EXPECT_NEAR(p.azimuth_deg, 194.34024, 1e-5);
    EXPECT_NEAR(p.elevation_deg, 90.0 - 50.11162, 1e-5);
    EXPECT_NEAR(pt::incidence_angle_deg(p, 30.0, -10.0), 25.18700, 1e-5);
}

TEST(SolarPosition, DirectionFollowsTheRendererConvention)
{
    // +y up, azimuth clockwise from north (-z) towards east (+x).
    const Imath::V3d up = pt::sun_direction(0.0, 123.0);
    EXPECT_NEAR(up.y, 1.0, 1e-12);
    const Imath::V3d east = pt::sun_direction(90.0, 90.0);
    EXPECT_NEAR(east.x, 1.0, 1e-12);
    const Imath::V3d north = pt::sun_direction(90.0, 0.0);
    EXPECT_NEAR(north.z, -1.0, 1e-12);
    const Imath::V3d south = pt::sun_direction(60.0, 180.0);
    EXPECT_NEAR(south.z, std::sin(M_PI / 3), 1e-12);
    EXPECT_NEAR(south.y, 0.5, 1e-12);
}

TEST(SolarPosition, NoonSunIsSouthInTheNorthAndNorthInTheSouth)
{
    pt::SolarSite site;
    site.latitude_deg = 45.0;
    site.longitude_deg = 0.0;
    // Around the June solstice at 12:00 UT on the Greenwich meridian the sun culminates
    // within 2 minutes (the equation of time), i.e. within 0.5 deg of hour angle, which
    // near a zenith of 21.5 deg moves the azimuth by up to ~1.5 deg; the zenith is
    // latitude - declination to second order.
    const double jd = pt::julian_day(pt::parse_date_time("2021-06-21T12:00", "t"), 0.0);
    const pt::SolarPosition north = pt::solar_position(jd, site);
    EXPECT_NEAR(north.azimuth_deg, 180.0, 1.5);
    EXPECT_NEAR(north.zenith_deg, 45.0 - north.declination_deg, 0.05);
    EXPECT_NEAR(north.declination_deg, 23.44, 0.01);
    site.latitude_deg = -30.0;
    const pt::SolarPosition south = pt::solar_position(jd, site);
    EXPECT_TRUE(south.azimuth_deg < 1.0 || south.azimuth_deg > 359.0) << south.azimuth_deg;
}

TEST(DateTime, JulianDayRoundTrip)
{
    // Meeus, Astronomical Algorithms, Example 7.a: 1957 October 4.81 = JD 2436116.31.
    pt::DateTime sputnik = pt::parse_date_time("1957-10-04T19:26:24", "t");
    EXPECT_NEAR(pt::julian_day(sputnik, 0.0), 2436116.31, 1e-9);
    // J2000.0 is JD 2451545.0 = 2000-01-01 12:00 UT.
    EXPECT_DOUBLE_EQ(pt::julian_day(pt::parse_date_time("2000-01-01T12:00", "t"), 0.0),
                     2451545.0);
    const pt::DateTime back = pt::date_time_of_julian_day(2452930.312847222, -7.0);
    EXPECT_EQ(pt::format_date_time(back), "2003-10-17T12:30:30");
    const pt::DateTime leap = pt::date_time_of_julian_day(
        pt::julian_day(pt::parse_date_time("2024-02-29T23:59:59", "t"), 5.5) + 1.0 / 86400.0,
        5.5);
    EXPECT_EQ(pt::format_date_time(leap), "2024-03-01T00:00:00");
}

TEST(DateTime, BadInputNamesTheOption)
{
    EXPECT_NE(patina::test::message_of([] { pt::parse_date_time("2003-13-01", "--start"); })
                  .find("--start"),
              std::string::npos);
    EXPECT_THROW(pt::parse_date_time("2003-02-29", "--start"), std::runtime_error);
    EXPECT_THROW(pt::parse_date_time("2003-10-17T25:00", "--end"), std::runtime_error);
    EXPECT_THROW(pt::parse_date_time("17/10/2003", "--end"), std::runtime_error);
    EXPECT_NO_THROW(pt::parse_date_time("2004-02-29 24:00", "--end"));
}
