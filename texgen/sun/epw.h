// EnergyPlus weather files (EPW): the LOCATION header and the hourly (or sub-hourly) data
// rows, as specified in the EnergyPlus "Auxiliary Programs" manual, "Weather Converter
// Program: EnergyPlus Weather File (EPW) Data Dictionary". Irradiation fields are the
// energy received during the interval that ends at the row's time stamp, in Wh/m^2.
#pragma once

#include "texgen/sun/date_time.h"

#include <filesystem>
#include <istream>
#include <string>
#include <vector>

namespace patina::texgen {

/// The LOCATION line: LOCATION,city,state,country,source,WMO,lat,lon,tz,elevation.
struct EpwLocation {
    std::string city, state, country, source, wmo;
    double latitude_deg = 0;    ///< north positive
    double longitude_deg = 0;   ///< east positive
    double timezone_hours = 0;  ///< of the file's local standard time, east of Greenwich
    double elevation_m = 0;
};

/// One data row. Values the dictionary marks missing are kept as read (9999 for the
/// irradiation fields); require_irradiance() checks them where they are needed.
struct EpwRecord {
    int line = 0;  ///< 1-based line of the file, for messages
    int year = 0, month = 0, day = 0;
    int hour = 0;    ///< 1..24: the interval ends within hour `hour` (hour 1 is 00:00-01:00)
    int minute = 0;  ///< 0 or 60 ends the interval at hour:00, else at (hour - 1):minute
    double dry_bulb_c = 0;      ///< field 7 (99.9 = missing)
    double pressure_pa = 0;     ///< field 10 (999999 = missing)
    double ghi_wh = 0;          ///< field 14, global horizontal radiation, Wh/m^2
    double dni_wh = 0;          ///< field 15, direct normal radiation, Wh/m^2
    double dhi_wh = 0;          ///< field 16, diffuse horizontal radiation, Wh/m^2
};

struct EpwFile {
    std::string path;  ///< as given, for messages
    EpwLocation location;
    int records_per_hour = 1;  ///< from DATA PERIODS
    std::vector<EpwRecord> records;

    /// Length of one record's interval, minutes.
    double interval_minutes() const { return 60.0 / records_per_hour; }
};

/// Number of comma-separated fields of a data row (EPW data dictionary, fields N1-N35 and
/// A1 the data source flags).
constexpr int kEpwFieldCount = 35;

/// Read an EPW file. Throws std::runtime_error "path:line: what" for a missing or broken
/// LOCATION or DATA PERIODS header and for any broken data row: wrong field count, a
/// non-numeric value in a field Patina reads, a month, day, hour or minute out of range.
EpwFile read_epw(const std::filesystem::path& path);
/// As read_epw, from a stream; `name` stands for the file in messages.
EpwFile parse_epw(std::istream& in, const std::string& name);

/// Throw "path:line: ..." if one of the irradiation fields 14-16 of `r` holds the
/// dictionary's missing value (>= 9999) or is negative.
void require_irradiance(const EpwFile& file, const EpwRecord& r);

/// The local standard date-time at which record `r`'s interval ends.
DateTime record_end(const EpwFile& file, const EpwRecord& r);

}  // namespace patina::texgen
