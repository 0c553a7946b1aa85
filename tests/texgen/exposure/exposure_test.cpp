// The exposure baker against closed forms: an open horizontal plane receives the time
// integral of the model's global horizontal irradiance (or the EPW file's), surfaces facing
// away from the sun or under a roof get no direct sun, and the bits do not depend on the
// thread count.
#include "texgen/bake/bake_driver.h"
#include "texgen/exposure/exposure_baker.h"
#include "texgen/exposure/exposure_period.h"
#include "texgen/exposure/sky_accumulation.h"
#include "texgen/sun/cie_sky.h"

#include "core/embree_scene.h"
#include "core/mesh.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <sstream>
#include <string>

#include <sys/resource.h>

#include "test_util.h"
#include "texgen/spa_example_site.h"

namespace pt = patina::texgen;

namespace {

pt::ClearSkyPeriodOptions clear_period(const char* start, const char* end, double step = 10.0)
{
    pt::ClearSkyPeriodOptions o;
    o.site = patina::test::spa_example_site();
    o.timezone_hours = -7.0;
    o.start = pt::parse_date_time(start, "start");
    o.end = pt::parse_date_time(end, "end");
    o.step_minutes = step;
    return o;
}

// `count` samples spread over a 0.2 m square around `p`, all with normal `n`.
pt::SampleGroups samples_at(const Imath::V3f& p, const Imath::V3f& n, int count = 4)
{
    pt::SampleGroups groups;
    std::vector<pt::SurfaceSample> group;
    for (int i = 0; i < count; ++i) {
        pt::SurfaceSample s;
        s.uv = Imath::V2f(0.5f, 0.5f);
        const float d = 0.2f * (static_cast<float>(i) / count - 0.5f);
        // Offsets perpendicular to the normal.
        const Imath::V3f t = std::abs(n.y) > 0.5f ? Imath::V3f(1, 0, 0) : Imath::V3f(0, 1, 0);
        s.P = p + t * d;
        s.N = n;
        s.Ng = n;
        group.push_back(s);
    }
    groups.add_group(group);
    return groups;
}

std::vector<float> bake(const patina::EmbreeScene& scene, const pt::ExposureSky& sky,
                        const pt::SampleGroups& groups, bool components = true)
{
    pt::ExposureOptions options;
    options.components = components;
    const pt::ExposureBaker baker(scene, sky, options);
    return pt::bake_groups(groups, baker, {7, 0, nullptr});
}

// The independent reference: the clear-sky model's global horizontal irradiance
// integrated over the period with 1-minute midpoint steps, J/m^2.
double integrated_ghi(const pt::ClearSkyPeriodOptions& o)
{
    const double jd0 = pt::julian_day(o.start, o.timezone_hours);
    const double jd1 = pt::julian_day(o.end, o.timezone_hours);
    const int minutes = static_cast<int>(std::lround((jd1 - jd0) * 1440.0));
    pt::ClearSkyParameters p = o.clear_sky;
    p.elevation_m = o.site.elevation_m;
    double sum = 0.0;
    for (int i = 0; i < minutes; ++i) {
        const pt::SolarPosition sun = pt::solar_position(jd0 + (i + 0.5) / 1440.0, o.site);
        const double i0 = pt::extraterrestrial_normal_irradiance(sun.earth_radius_vector_au);
        sum += pt::ineichen_perez(sun.zenith_deg, i0, p).ghi * 60.0;
    }
    return sum;
}

struct OpenPlane {
    patina::EmbreeScene scene;
    OpenPlane() : OpenPlane(patina::make_plane(Imath::V3f(0, 0, 0), 10.0f)) {}
    explicit OpenPlane(const patina::TriangleMesh& mesh)
    {
        scene.add_mesh(mesh);
        scene.commit();
    }
};

}  // namespace

TEST(Exposure, OpenHorizontalPlaneGetsTheIntegralOfGlobalHorizontal)
{
    // One clear summer day: exposure = integral of GHI = DNI cos z + DHI (Ineichen-Perez),
    // integrated independently with 1-minute steps. 10-minute steps, 0.5-degree sun bins,
    // 256 sky cells: the issue allows 1-2%.
    for (const char* sky_name : {"clear", "overcast"}) {
        const pt::ClearSkyPeriodOptions o = clear_period("2003-06-21", "2003-06-22");
        const pt::ExposurePeriod period = pt::clear_sky_period(o);
        const pt::ExposureSky sky =
            pt::accumulate_exposure(period, pt::parse_cie_sky(sky_name, "sky"), {});
        const double expected = integrated_ghi(o);
        // A clear June day at 40 N, 1830 m: about 30 MJ/m^2.
        EXPECT_GT(expected, 25e6);
        EXPECT_LT(expected, 36e6);
        OpenPlane plane;
        const std::vector<float> v =
            bake(plane.scene, sky, samples_at(Imath::V3f(0, 0, 0), Imath::V3f(0, 1, 0)));
        std::printf("%s sky: exposure %.0f J/m^2, integral of GHI %.0f J/m^2, ratio %.5f\n",
                    sky_name, v[0], expected, v[0] / expected);
        EXPECT_NEAR(v[0] / expected, 1.0, 0.01) << sky_name;
        EXPECT_FLOAT_EQ(v[0], v[1] + v[2]);
        // The parts on their own: direct = integral of DNI cos z, sky = integral of DHI.
        EXPECT_NEAR(v[2] / sky.diffuse_horizontal, 1.0, 0.01) << sky_name;
        // relative: open flat ground is 1 by definition (its estimate jitters within the sun
        // bins and sky cells that H takes at their centres).
        EXPECT_NEAR(v[3], 1.0, 0.01) << sky_name;
        // The average is the total over the 86400 s period.
        pt::ExposureOptions average;
        average.average = true;
        const pt::ExposureBaker baker(plane.scene, sky, average);
        EXPECT_EQ(baker.channels(), (std::vector<std::string>{"irradiance", "relative"}));
        EXPECT_NEAR(baker.horizontal_exposure() / v[0], 1.0, 0.01) << sky_name;
        const std::vector<float> w = pt::bake_groups(
            samples_at(Imath::V3f(0, 0, 0), Imath::V3f(0, 1, 0)), baker, {7, 0, nullptr});
        EXPECT_NEAR(w[0] * 86400.0 / v[0], 1.0, 1e-5);
    }
}

TEST(Exposure, SurfacesFacingAwayFromTheSunGetNoDirectTerm)
{
    // Around noon in October at 39.7 N the sun stands in the south (azimuth 160-200 deg),
    // so a wall facing north (-z) gets no direct sun, only sky; a plane facing down gets
    // neither (no ground reflection).
    const pt::ExposurePeriod period =
        pt::clear_sky_period(clear_period("2003-10-17T11:00", "2003-10-17T13:00", 5.0));
    const pt::ExposureSky sky =
        pt::accumulate_exposure(period, pt::parse_cie_sky("clear", "sky"), {});
    ASSERT_GT(sky.sun_bins.size(), 10u);
    OpenPlane wall(patina::make_plane(Imath::V3f(0, 0, 0), 10.0f, 1, Imath::V3f(0, 0, -1)));
    const std::vector<float> north =
        bake(wall.scene, sky, samples_at(Imath::V3f(0, 0, 0), Imath::V3f(0, 0, -1)));
    EXPECT_EQ(north[1], 0.0f);
    EXPECT_GT(north[2], 0.0f);
    OpenPlane ceiling(patina::make_plane(Imath::V3f(0, 0, 0), 10.0f, 1, Imath::V3f(0, -1, 0)));
    const std::vector<float> down =
        bake(ceiling.scene, sky, samples_at(Imath::V3f(0, 0, 0), Imath::V3f(0, -1, 0)));
    EXPECT_EQ(down[0], 0.0f);
    EXPECT_EQ(down[3], 0.0f);
    EXPECT_GT(north[3], 0.0f);
    EXPECT_LT(north[3], 0.5f);  // sky alone, from half of it
    // The same wall turned south gets the sun: direct = sum of DNI dt cos(incidence), a
    // large share of the period's direct normal energy.
    OpenPlane south_wall(patina::make_plane(Imath::V3f(0, 0, 0), 10.0f, 1, Imath::V3f(0, 0, 1)));
    const std::vector<float> south =
        bake(south_wall.scene, sky, samples_at(Imath::V3f(0, 0, 0), Imath::V3f(0, 0, 1)));
    EXPECT_GT(south[1], 0.6 * sky.direct_normal);
}

TEST(Exposure, APlaneUnderARoofGetsNoDirectSun)
{
    // A 20 m roof 1 m above the sample: from 10:00 to 14:00 in June the sun's zenith stays
    // below 45 deg, so every sun ray (tan z < 1 m off the vertical per metre) meets it.
    // Only sky near the horizon (zenith > atan(10) = 84.3 deg) still reaches the sample.
    const pt::ExposurePeriod period =
        pt::clear_sky_period(clear_period("2003-06-21T10:00", "2003-06-21T14:00"));
    const pt::ExposureSky sky =
        pt::accumulate_exposure(period, pt::parse_cie_sky("clear", "sky"), {});
    patina::EmbreeScene scene;
    scene.add_mesh(patina::make_plane(Imath::V3f(0, 0, 0), 10.0f));
    scene.add_mesh(patina::make_plane(Imath::V3f(0, 1, 0), 20.0f, 1, Imath::V3f(0, -1, 0)));
    scene.commit();
    const std::vector<float> covered =
        bake(scene, sky, samples_at(Imath::V3f(0, 0, 0), Imath::V3f(0, 1, 0)));
    EXPECT_EQ(covered[1], 0.0f);
    EXPECT_LT(covered[2], 0.05 * sky.diffuse_horizontal);
    // Without the roof the same sample gets the full direct term.
    OpenPlane open;
    const std::vector<float> v =
        bake(open.scene, sky, samples_at(Imath::V3f(0, 0, 0), Imath::V3f(0, 1, 0)));
    EXPECT_GT(v[1], 0.5 * sky.direct_normal);
}

TEST(Exposure, CostDoesNotGrowWithThePeriod)
{
    // Ten days around the June solstice: the sun retraces nearly the same path, so the
    // direction bins (and the rays per sample) barely grow while the energy is ten-fold.
    const pt::CieSky clear = pt::parse_cie_sky("clear", "sky");
    const pt::ExposureSky one = pt::accumulate_exposure(
        pt::clear_sky_period(clear_period("2003-06-21", "2003-06-22")), clear, {});
    const pt::ExposureSky ten = pt::accumulate_exposure(
        pt::clear_sky_period(clear_period("2003-06-16", "2003-06-26")), clear, {});
    EXPECT_NEAR(ten.direct_normal / one.direct_normal, 10.0, 0.1);
    // Measured: 89 bins for one day, 199 for ten (the track shifts by ~0.3 deg of
    // declination, crossing 0.5-degree bin edges), against 10x the time steps.
    EXPECT_LT(ten.sun_bins.size(), 3 * one.sun_bins.size());
    EXPECT_EQ(ten.sky_resolution, one.sky_resolution);
}

TEST(Exposure, SameBitsForAnyThreadCount)
{
    const pt::ExposureSky sky = pt::accumulate_exposure(
        pt::clear_sky_period(clear_period("2003-10-17T07:00", "2003-10-17T17:00")),
        pt::parse_cie_sky("clear", "sky"), {});
    patina::EmbreeScene scene;
    scene.add_mesh(patina::make_plane(Imath::V3f(0, 0, 0), 4.0f, 4));
    scene.add_mesh(patina::make_box(Imath::V3f(0.5f, 0.5f, 0.2f), Imath::V3f(0.6f, 1.0f, 0.6f)));
    scene.commit();
    pt::SampleGroups groups;
    for (int i = 0; i < 300; ++i) {
        pt::SurfaceSample s;
        s.uv = Imath::V2f(0.5f, 0.5f);
        s.P = Imath::V3f(-1.5f + 0.01f * i, 0.0f, 0.3f * std::sin(0.1f * i));
        s.N = s.Ng = Imath::V3f(0, 1, 0);
        groups.add_group({s, s});
    }
    pt::ExposureOptions options;
    options.components = true;
    const pt::ExposureBaker baker(scene, sky, options);
    std::vector<float> one, two;
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 1);
        one = pt::bake_groups(groups, baker, {3, 0, nullptr});
    }
    {
        tbb::global_control c(tbb::global_control::max_allowed_parallelism, 2);
        two = pt::bake_groups(groups, baker, {3, 0, nullptr});
    }
    ASSERT_EQ(one.size(), two.size());
    EXPECT_EQ(std::memcmp(one.data(), two.data(), one.size() * sizeof(float)), 0);
    // The box shades some samples: not all values are equal.
    float lo = 1e30f, hi = 0.0f;
    for (size_t g = 0; g < groups.group_count(); ++g) {
        lo = std::min(lo, one[g * 3]);
        hi = std::max(hi, one[g * 3]);
    }
    EXPECT_LT(lo, 0.8f * hi);
}

TEST(Exposure, BadOptionsNameTheOption)
{
    OpenPlane plane;
    const pt::ExposurePeriod period =
        pt::clear_sky_period(clear_period("2003-10-17T11:00", "2003-10-17T12:00"));
    const pt::CieSky clear = pt::parse_cie_sky("clear", "sky");
    pt::AccumulationOptions bins;
    bins.sun_bin_deg = 0.0;
    EXPECT_THROW(pt::accumulate_exposure(period, clear, bins), std::runtime_error);
    const pt::ExposureSky sky = pt::accumulate_exposure(period, clear, {});
    pt::ExposureOptions options;
    options.max_distance = 0.0f;
    EXPECT_THROW(pt::ExposureBaker(plane.scene, sky, options), std::runtime_error);
    EXPECT_THROW(pt::clear_sky_period(clear_period("2003-10-17T12:00", "2003-10-17T11:00")),
                 std::runtime_error);
}

namespace {

// An EPW file for Chicago O'Hare: the LOCATION line and the radiation of 20 June (TMY3,
// NREL 2008, fields 7, 10, 14-16 as in the file; the other fields are fillers in range).
std::string chicago_epw(bool broken_row)
{
    struct Hour {
        int hour;
        double temperature, pressure, ghi, dni, dhi;
    };
    const Hour hours[] = {
        {1, 25.0, 99000, 0, 0, 0},        {2, 24.4, 99000, 0, 0, 0},
        {3, 24.4, 99000, 0, 0, 0},        {4, 24.4, 98900, 0, 0, 0},
        {5, 24.4, 98900, 13, 0, 13},      {6, 25.0, 99000, 74, 5, 73},
        {7, 25.0, 98900, 193, 44, 177},   {8, 25.6, 98800, 294, 99, 240},
        {9, 27.2, 98800, 572, 385, 303},  {10, 28.3, 98800, 580, 280, 350},
        {11, 29.4, 98700, 728, 335, 425}, {12, 30.0, 98700, 858, 520, 367},
        {13, 31.1, 98500, 853, 551, 335}, {14, 32.2, 98400, 800, 518, 341},
        {15, 32.2, 98300, 714, 566, 265}, {16, 31.7, 98200, 333, 68, 288},
        {17, 31.7, 98300, 257, 73, 220},  {18, 30.0, 98600, 157, 71, 133},
        {19, 28.3, 98700, 48, 6, 47},     {20, 25.6, 98700, 7, 0, 7},
        {21, 22.2, 98800, 0, 0, 0},       {22, 21.7, 98800, 0, 0, 0},
        {23, 20.6, 98800, 0, 0, 0},       {24, 21.7, 98800, 0, 0, 0},
    };
    std::ostringstream s;
    s << "LOCATION,Chicago Ohare Intl Ap,IL,USA,TMY3,725300,41.98,-87.92,-6.0,201.0\n"
         "DESIGN CONDITIONS,0\nTYPICAL/EXTREME PERIODS,0\nGROUND TEMPERATURES,0\n"
         "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\nCOMMENTS 1,test\nCOMMENTS 2,\n"
         "DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31\n";
    for (const Hour& h : hours) {
        s << "1979,6,20," << h.hour << ",0,?9?9?9?9E0?9?9?9?9*9*9*9*9*9," << h.temperature
          << ",15.0,60," << h.pressure << ",0,0,400," << h.ghi << ","
          << (broken_row && h.hour == 12 ? std::string("9999") : std::to_string(h.dni)) << ","
          << h.dhi << ",0,0,0,0,200,5.0,5,3,24.1,77777,9,999999999,379,0.3670,0,88,999.000,"
          << "999.0,99.0\n";
    }
    return s.str();
}

pt::EpwFile chicago(bool broken_row = false)
{
    std::istringstream in(chicago_epw(broken_row));
    return pt::parse_epw(in, "chicago.epw");
}

}  // namespace

TEST(Exposure, EpwHorizontalPlaneGetsTheGlobalHorizontalColumn)
{
    const pt::EpwFile file = chicago();
    double ghi_wh = 0.0, dhi_wh = 0.0;
    for (const pt::EpwRecord& r : file.records) {
        ghi_wh += r.ghi_wh;
        dhi_wh += r.dhi_wh;
    }
    const pt::ExposurePeriod period = pt::epw_period(file, {});
    EXPECT_DOUBLE_EQ(period.duration_s, 24 * 3600.0);
    const pt::ExposureSky sky =
        pt::accumulate_exposure(period, pt::parse_cie_sky("overcast", "sky"), {});
    // Every row's energy is kept: the sky carries the DHI column exactly.
    EXPECT_NEAR(sky.diffuse_horizontal, dhi_wh * 3600.0, 1e-6 * dhi_wh * 3600.0);
    OpenPlane plane;
    const std::vector<float> v =
        bake(plane.scene, sky, samples_at(Imath::V3f(0, 0, 0), Imath::V3f(0, 1, 0)));
    std::printf("EPW day: exposure %.0f J/m^2, GHI column %.0f J/m^2, ratio %.5f\n", v[0],
                ghi_wh * 3600.0, v[0] / (ghi_wh * 3600.0));
    EXPECT_NEAR(v[0] / (ghi_wh * 3600.0), 1.0, 0.02);
    EXPECT_NEAR(v[2] / (dhi_wh * 3600.0), 1.0, 0.01);
}

TEST(Exposure, EpwDateRangeAndBrokenRows)
{
    const pt::EpwFile file = chicago();
    // 10:00-14:00 holds the rows of hours 11 to 14.
    pt::EpwPeriodOptions range;
    range.start = pt::parse_date_time("2020-06-20T10:00", "start");
    range.end = pt::parse_date_time("2020-06-20T14:00", "end");
    const pt::ExposurePeriod period = pt::epw_period(file, range);
    EXPECT_DOUBLE_EQ(period.duration_s, 4 * 3600.0);
    const pt::ExposureSky sky =
        pt::accumulate_exposure(period, pt::parse_cie_sky("clear", "sky"), {});
    EXPECT_NEAR(sky.direct_normal, (335.0 + 520 + 551 + 518) * 3600.0, 1e-3);
    EXPECT_NEAR(sky.diffuse_horizontal, (425.0 + 367 + 335 + 341) * 3600.0, 1e-3);
    // Out of range: nothing to bake.
    range.start = pt::parse_date_time("2020-07-01", "start");
    range.end = pt::parse_date_time("2020-07-02", "end");
    EXPECT_THROW(pt::epw_period(file, range), std::runtime_error);
    // A missing value (9999) in range names the file and the row's line (line 20: hour
    // 12 after the 8 header lines); out of range it does not matter.
    const pt::EpwFile broken = chicago(true);
    try {
        pt::epw_period(broken, {});
        ADD_FAILURE() << "no exception";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("chicago.epw:20: direct normal radiation"),
                  std::string::npos)
            << e.what();
    }
    range.start = pt::parse_date_time("2020-06-20T13:00", "start");
    range.end = pt::parse_date_time("2020-06-21T00:00", "end");
    EXPECT_NO_THROW(pt::epw_period(broken, range));
}

TEST(Exposure, VerticalWallUnderTheOvercastSky)
{
    // Under the Moon-Spencer sky L = Lz (1 + 2 cos Z) / 3 the horizontal irradiance is
    // 7 pi / 9 Lz and a vertical surface receives (2/3) (pi/4 + 2/3) Lz (integrate
    // L sin Z cos(phi) over the half hemisphere it faces), so E_v / E_h = 0.39618: the
    // classic 0.396 of daylighting (no ground reflection).
    const double expected = (2.0 / 3.0) * (M_PI / 4.0 + 2.0 / 3.0) / (7.0 * M_PI / 9.0);
    EXPECT_NEAR(expected, 0.39618, 1e-5);
    const pt::ExposureSky sky = pt::accumulate_exposure(
        pt::clear_sky_period(clear_period("2003-10-17T08:00", "2003-10-17T16:00")),
        pt::parse_cie_sky("overcast", "sky"), {});
    for (const Imath::V3f& n : {Imath::V3f(1, 0, 0), Imath::V3f(0, 0, -1)}) {
        OpenPlane wall(patina::make_plane(Imath::V3f(0, 0, 0), 10.0f, 1, n));
        const std::vector<float> v =
            bake(wall.scene, sky, samples_at(Imath::V3f(0, 0, 0), n, 16));
        std::printf("vertical wall (%g, %g, %g): sky / DHI %.5f (closed form %.5f)\n", n.x, n.y,
                    n.z, v[2] / sky.diffuse_horizontal, expected);
        EXPECT_NEAR(v[2] / sky.diffuse_horizontal, expected, 0.01 * expected);
    }
}

TEST(ExposureSky, ALongPeriodIsAccumulatedWithoutKeepingItsSteps)
{
    // 40 years at 30-minute steps: 701,000 steps, about half of them lit. Kept in a vector
    // (as before) they took 56 bytes each, ~20 MB with its growth; streamed, the memory
    // does not depend on the period. (A 1000-year period at 0.1 minutes grew past 1.4 GB.)
    const auto peak_kib = [] {
        rusage usage{};
        ::getrusage(RUSAGE_SELF, &usage);
        return usage.ru_maxrss;
    };
    const pt::CieSky clear = pt::parse_cie_sky("clear", "sky");
    // A short period first, so that every lazily made table already exists.
    pt::accumulate_exposure(pt::clear_sky_period(clear_period("2003-06-21", "2003-06-22")),
                            clear, {});
    const long before = peak_kib();
    const pt::ExposureSky sky = pt::accumulate_exposure(
        pt::clear_sky_period(clear_period("2000-01-01", "2040-01-01", 30.0)), clear, {});
    const long grown_kib = peak_kib() - before;
    EXPECT_GT(sky.steps, 300000u);
    EXPECT_LT(grown_kib, 4 * 1024) << "the period's steps were kept in memory";
}

TEST(ExposureSky, APeriodOfTooManyStepsIsRefusedNamingTheStep)
{
    const std::string msg = patina::test::message_of(
        [] { pt::clear_sky_period(clear_period("2000-01-01", "3000-01-01", 0.1)); });
    EXPECT_NE(msg.find("--step-minutes 0.1: the period from 2000-01-01"), std::string::npos)
        << msg;
    EXPECT_NE(msg.find("more than the limit of 1e+08"), std::string::npos) << msg;
}
