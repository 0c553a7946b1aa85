// Calendar date-times of a site's local standard time, parsed from the command line or a
// weather file, and their Julian day (the time scale of the solar position algorithm).
#pragma once

#include <string>
#include <string_view>

namespace patina::texgen {

/// A Gregorian calendar date and time of day. `second` may have a fraction.
struct DateTime {
    int year = 2000;
    int month = 1;   ///< 1..12
    int day = 1;     ///< 1..days_in_month
    int hour = 0;    ///< 0..24 (24:00 is the end of the day)
    int minute = 0;  ///< 0..59
    double second = 0.0;
};

bool is_leap_year(int year);
int days_in_month(int year, int month);

/// Parse "YYYY-MM-DD", "YYYY-MM-DDTHH:MM[:SS[.s]]" or "YYYY-MM-DD HH:MM[:SS]"; throws
/// std::runtime_error naming `what` (e.g. "--start") on anything else or an invalid date.
DateTime parse_date_time(std::string_view text, const std::string& what);
/// Parse "HH:MM[:SS[.s]]" into the time fields of `date`; throws naming `what`.
void parse_time_of_day(std::string_view text, const std::string& what, DateTime& date);

/// Julian day (UT) of `local`, a time in the zone `timezone_hours` east of Greenwich
/// (e.g. -7 for Mountain Standard Time): Reda & Andreas 2004 Eq. 4, Gregorian calendar.
double julian_day(const DateTime& local, double timezone_hours);
/// The local date-time of Julian day `jd` (UT) in the zone `timezone_hours` (Meeus,
/// Astronomical Algorithms ch. 7), rounded to the millisecond.
DateTime date_time_of_julian_day(double jd, double timezone_hours);

/// "YYYY-MM-DDTHH:MM:SS" (seconds rounded).
std::string format_date_time(const DateTime& t);

}  // namespace patina::texgen
