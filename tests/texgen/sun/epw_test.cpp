// The EPW reader: header, rows, and broken rows named by file and line.
#include "texgen/sun/epw.h"

#include "test_util.h"

#include <gtest/gtest.h>

#include <sstream>

namespace pt = patina::texgen;

namespace {

// The header and two rows of NREL's TMY3 file for Chicago O'Hare (725300), 20 June.
const std::string kHeader =
    "LOCATION,Chicago Ohare Intl Ap,IL,USA,TMY3,725300,41.98,-87.92,-6.0,201.0\n"
    "DESIGN CONDITIONS,0\n"
    "TYPICAL/EXTREME PERIODS,0\n"
    "GROUND TEMPERATURES,0\n"
    "HOLIDAYS/DAYLIGHT SAVINGS,No,0,0,0\n"
    "COMMENTS 1,test fragment\n"
    "COMMENTS 2,\n"
    "DATA PERIODS,1,1,Data,Sunday, 1/ 1,12/31\n";
const std::string kRow12 =
    "1979,6,20,12,0,?9?9?9?9E0?9?9?9?9?9?9?9?9?9?9?9?9?9?9?9*9*9*9*9*9,30.0,21.1,59,98700,"
    "1253,1323,425,858,520,367,93800,54800,40500,23000,200,8.2,5,3,24.1,77777,9,999999999,"
    "379,0.3670,0,88,999.000,999.0,99.0\n";
const std::string kRow13 =
    "1979,6,20,13,0,?9?9?9?9E0?9?9?9?9?9?9?9?9?9?9?9?9?9?9?9*9*9*9*9*9,31.1,21.7,57,98500,"
    "1240,1323,428,853,551,335,92200,57700,38000,22800,170,9.8,4,3,24.1,77777,9,999999999,"
    "379,0.3670,0,88,999.000,999.0,99.0\n";

pt::EpwFile parse(const std::string& text)
{
    std::istringstream in(text);
    return pt::parse_epw(in, "chicago.epw");
}

std::string error_of(const std::string& text)
{
    return patina::test::message_of([&] { parse(text); });
}

std::string replace_field(std::string row, int field, const std::string& value)
{
    size_t start = 0;
    for (int i = 1; i < field; ++i)
        start = row.find(',', start) + 1;
    const size_t end = row.find_first_of(",\n", start);
    return row.replace(start, end - start, value);
}

}  // namespace

TEST(Epw, ReadsLocationAndRows)
{
    const pt::EpwFile f = parse(kHeader + kRow12 + kRow13);
    EXPECT_EQ(f.location.city, "Chicago Ohare Intl Ap");
    EXPECT_EQ(f.location.wmo, "725300");
    EXPECT_DOUBLE_EQ(f.location.latitude_deg, 41.98);
    EXPECT_DOUBLE_EQ(f.location.longitude_deg, -87.92);
    EXPECT_DOUBLE_EQ(f.location.timezone_hours, -6.0);
    EXPECT_DOUBLE_EQ(f.location.elevation_m, 201.0);
    EXPECT_EQ(f.records_per_hour, 1);
    ASSERT_EQ(f.records.size(), 2u);
    const pt::EpwRecord& r = f.records[1];
    EXPECT_EQ(r.line, 10);
    EXPECT_EQ(r.year, 1979);
    EXPECT_EQ(r.month, 6);
    EXPECT_EQ(r.day, 20);
    EXPECT_EQ(r.hour, 13);
    EXPECT_DOUBLE_EQ(r.dry_bulb_c, 31.1);
    EXPECT_DOUBLE_EQ(r.pressure_pa, 98500.0);
    // Fields 14-16 of the EnergyPlus data dictionary: global, direct normal, diffuse.
    EXPECT_DOUBLE_EQ(r.ghi_wh, 853.0);
    EXPECT_DOUBLE_EQ(r.dni_wh, 551.0);
    EXPECT_DOUBLE_EQ(r.dhi_wh, 335.0);
    EXPECT_NO_THROW(pt::require_irradiance(f, r));
    // Hour 13 is the interval 12:00-13:00 local standard time.
    EXPECT_EQ(pt::format_date_time(pt::record_end(f, r)), "1979-06-20T13:00:00");
}

TEST(Epw, BrokenRowsNameFileAndLine)
{
    // Line 9 is the first data row, line 10 the second.
    EXPECT_NE(error_of(kHeader + kRow12 + "1979,6,20,13,0,x,31.1\n").find("chicago.epw:10:"),
              std::string::npos);
    EXPECT_NE(error_of(kHeader + kRow12 + "1979,6,20,13,0,x,31.1\n").find("7 fields"),
              std::string::npos);
    const std::string bad_number = replace_field(kRow13, 15, "5x1");
    EXPECT_NE(error_of(kHeader + kRow12 + bad_number).find("chicago.epw:10: direct normal"),
              std::string::npos);
    EXPECT_NE(error_of(kHeader + replace_field(kRow12, 2, "13")).find("chicago.epw:9: month 13"),
              std::string::npos);
    EXPECT_NE(error_of(kHeader + replace_field(kRow12, 4, "0")).find("chicago.epw:9: hour 0"),
              std::string::npos);
    EXPECT_NE(error_of(kHeader + replace_field(kRow12, 3, "31")).find("chicago.epw:9: day 31"),
              std::string::npos);
    EXPECT_NE(error_of(kHeader + replace_field(kRow12, 1, "1979.5")).find("chicago.epw:9: year"),
              std::string::npos);
    EXPECT_NE(error_of("DESIGN CONDITIONS,0\n").find("chicago.epw:1: not an EPW file"),
              std::string::npos);
    EXPECT_NE(error_of(kHeader).find("no data rows"), std::string::npos);

    // A missing irradiation value (9999) is read, and refused where it is needed.
    const pt::EpwFile f = parse(kHeader + kRow12 + replace_field(kRow13, 16, "9999"));
    EXPECT_NE(patina::test::message_of([&] { pt::require_irradiance(f, f.records[1]); })
                  .find("chicago.epw:10: diffuse horizontal radiation (field 16) is missing"),
              std::string::npos);
    // A huge value is not reported as missing: it is named as what it is.
    const pt::EpwFile g = parse(kHeader + kRow12 + replace_field(kRow13, 15, "1e308"));
    const std::string huge =
        patina::test::message_of([&] { pt::require_irradiance(g, g.records[1]); });
    EXPECT_NE(huge.find("chicago.epw:10: direct normal radiation (field 15) is 1e+308 Wh/m^2, "
                        "not an irradiation"), std::string::npos) << huge;
}
