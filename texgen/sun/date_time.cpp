#include "texgen/sun/date_time.h"

#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace patina::texgen {

namespace {

[[noreturn]] void fail(const std::string& what, std::string_view text, const char* why)
{
    throw std::runtime_error(what + ": '" + std::string(text) + "' is not " + why);
}

// Exactly `digits` decimal digits at text[pos...]; advances pos.
bool read_digits(std::string_view text, size_t& pos, int digits, int& value)
{
    if (pos + digits > text.size())
        return false;
    value = 0;
    for (int i = 0; i < digits; ++i) {
        const char c = text[pos + i];
        if (c < '0' || c > '9')
            return false;
        value = value * 10 + (c - '0');
    }
    pos += digits;
    return true;
}

}  // namespace

bool is_leap_year(int year)
{
    return (year % 4 == 0 && year % 100 != 0) || year % 400 == 0;
}

int days_in_month(int year, int month)
{
    static constexpr int kDays[12] = {31, 28, 31, 30, 31, 30, 31, 31, 30, 31, 30, 31};
    if (month < 1 || month > 12)
        return 0;
    return kDays[month - 1] + (month == 2 && is_leap_year(year) ? 1 : 0);
}

void parse_time_of_day(std::string_view text, const std::string& what, DateTime& date)
{
    const char* expected = "a time HH:MM or HH:MM:SS";
    size_t pos = 0;
    int hour = 0, minute = 0;
    if (!read_digits(text, pos, 2, hour) || pos >= text.size() || text[pos++] != ':' ||
        !read_digits(text, pos, 2, minute))
        fail(what, text, expected);
    double second = 0.0;
    if (pos < text.size()) {
        if (text[pos++] != ':')
            fail(what, text, expected);
        int whole = 0;
        if (!read_digits(text, pos, 2, whole))
            fail(what, text, expected);
        second = whole;
        if (pos < text.size()) {
            // A decimal fraction of a second.
            if (text[pos] != '.' || pos + 1 >= text.size())
                fail(what, text, expected);
            double scale = 0.1;
            for (++pos; pos < text.size(); ++pos, scale *= 0.1) {
                if (text[pos] < '0' || text[pos] > '9')
                    fail(what, text, expected);
                second += (text[pos] - '0') * scale;
            }
        }
    }
    const bool end_of_day = hour == 24 && minute == 0 && second == 0.0;
    if ((hour > 23 && !end_of_day) || minute > 59 || second >= 60.0)
        fail(what, text, "a valid time of day (00:00:00 to 24:00:00)");
    date.hour = hour;
    date.minute = minute;
    date.second = second;
}

DateTime parse_date_time(std::string_view text, const std::string& what)
{
    const char* expected = "a date YYYY-MM-DD (optionally followed by THH:MM[:SS])";
    DateTime t;
    size_t pos = 0;
    if (!read_digits(text, pos, 4, t.year) || pos >= text.size() || text[pos++] != '-' ||
        !read_digits(text, pos, 2, t.month) || pos >= text.size() || text[pos++] != '-' ||
        !read_digits(text, pos, 2, t.day))
        fail(what, text, expected);
    if (t.month < 1 || t.month > 12 || t.day < 1 || t.day > days_in_month(t.year, t.month))
        fail(what, text, "a valid calendar date");
    if (pos < text.size()) {
        if (text[pos] != 'T' && text[pos] != ' ')
            fail(what, text, expected);
        parse_time_of_day(text.substr(pos + 1), what, t);
    }
    return t;
}

double julian_day(const DateTime& local, double timezone_hours)
{
    // Reda & Andreas 2004 Eq. 4: January and February count as months 13 and 14 of the
    // previous year; B is the Gregorian correction.
    int year = local.year;
    int month = local.month;
    if (month < 3) {
        year -= 1;
        month += 12;
    }
    const double day_fraction =
        (local.hour - timezone_hours + (local.minute + local.second / 60.0) / 60.0) / 24.0;
    const double day = local.day + day_fraction;
    const int a = static_cast<int>(std::floor(year / 100.0));
    const int b = 2 - a + static_cast<int>(std::floor(a / 4.0));
    return std::floor(365.25 * (year + 4716)) + std::floor(30.6001 * (month + 1)) + day + b -
           1524.5;
}

DateTime date_time_of_julian_day(double jd, double timezone_hours)
{
    // Meeus, Astronomical Algorithms (2nd ed.) ch. 7, "Calendar Date from the JD", in
    // whole milliseconds so that the time of day never rounds to 60 s.
    const double local = jd + 0.5 + timezone_hours / 24.0;
    double z = std::floor(local);
    long long ms = std::llround((local - z) * 86400000.0);
    if (ms >= 86400000LL) {
        ms -= 86400000LL;
        z += 1.0;
    }
    double a = z;
    if (z >= 2299161.0) {
        const double alpha = std::floor((z - 1867216.25) / 36524.25);
        a = z + 1.0 + alpha - std::floor(alpha / 4.0);
    }
    const double b = a + 1524.0;
    const double c = std::floor((b - 122.1) / 365.25);
    const double d = std::floor(365.25 * c);
    const double e = std::floor((b - d) / 30.6001);
    DateTime t;
    t.day = static_cast<int>(b - d - std::floor(30.6001 * e));
    t.month = static_cast<int>(e < 14 ? e - 1 : e - 13);
    t.year = static_cast<int>(t.month > 2 ? c - 4716 : c - 4715);
    t.hour = static_cast<int>(ms / 3600000LL);
    t.minute = static_cast<int>((ms / 60000LL) % 60);
    t.second = static_cast<double>(ms % 60000LL) / 1000.0;
    return t;
}

std::string format_date_time(const DateTime& t)
{
    char buffer[64];
    std::snprintf(buffer, sizeof buffer, "%04d-%02d-%02dT%02d:%02d:%02d", t.year, t.month, t.day,
                  t.hour, t.minute, static_cast<int>(std::lround(std::floor(t.second))));
    return buffer;
}

}  // namespace patina::texgen
