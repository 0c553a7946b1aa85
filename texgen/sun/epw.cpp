#include "texgen/sun/epw.h"

#include <fmt/format.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <stdexcept>
#include <string_view>

namespace patina::texgen {

namespace {

[[noreturn]] void fail_at(const std::string& name, int line, const std::string& what)
{
    throw std::runtime_error(name + ":" + std::to_string(line) + ": " + what);
}

std::vector<std::string_view> split_fields(std::string_view line)
{
    std::vector<std::string_view> fields;
    size_t start = 0;
    while (true) {
        const size_t comma = line.find(',', start);
        fields.push_back(line.substr(start, comma == std::string_view::npos ? std::string_view::npos
                                                                               : comma - start));
        if (comma == std::string_view::npos)
            break;
        start = comma + 1;
    }
    return fields;
}

std::string_view trim(std::string_view s)
{
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
        s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
        s.remove_suffix(1);
    return s;
}

// Field `index` (1-based, as in the data dictionary) of `fields` as a number.
double number_field(const std::vector<std::string_view>& fields, int index, const char* label,
                    const std::string& name, int line)
{
    const std::string text(trim(fields[index - 1]));
    char* end = nullptr;
    errno = 0;
    const double value = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
    if (text.empty() || end != text.c_str() + text.size() || errno == ERANGE ||
        !std::isfinite(value))
        fail_at(name, line,
                std::string(label) + " (field " + std::to_string(index) + ") is '" + text +
                    "', not a number");
    return value;
}

int integer_field(const std::vector<std::string_view>& fields, int index, const char* label,
                  const std::string& name, int line)
{
    const double value = number_field(fields, index, label, name, line);
    if (value != std::floor(value) || std::abs(value) > 1e9)
        fail_at(name, line,
                std::string(label) + " (field " + std::to_string(index) + ") is " +
                    std::string(trim(fields[index - 1])) + ", not a whole number");
    return static_cast<int>(value);
}

void check_range(int value, int low, int high, const char* label, const std::string& name,
                 int line)
{
    if (value < low || value > high)
        fail_at(name, line,
                std::string(label) + " " + std::to_string(value) + " is out of range (" +
                    std::to_string(low) + " to " + std::to_string(high) + ")");
}

bool starts_with(std::string_view line, std::string_view prefix)
{
    return line.substr(0, prefix.size()) == prefix;
}

}  // namespace

EpwFile parse_epw(std::istream& in, const std::string& name)
{
    EpwFile file;
    file.path = name;
    std::string text;
    int line = 0;

    // LOCATION,city,state,country,source,WMO,latitude,longitude,time zone,elevation
    if (!std::getline(in, text))
        fail_at(name, 1, "empty file; an EPW file starts with a LOCATION line");
    line = 1;
    {
        const auto f = split_fields(trim(text));
        if (f.empty() || trim(f[0]) != "LOCATION")
            fail_at(name, 1, "not an EPW file: the first line must be LOCATION,...");
        if (f.size() < 10)
            fail_at(name, 1,
                    "LOCATION has " + std::to_string(f.size()) + " fields, expected 10");
        EpwLocation& loc = file.location;
        loc.city = std::string(trim(f[1]));
        loc.state = std::string(trim(f[2]));
        loc.country = std::string(trim(f[3]));
        loc.source = std::string(trim(f[4]));
        loc.wmo = std::string(trim(f[5]));
        loc.latitude_deg = number_field(f, 7, "LOCATION latitude", name, 1);
        loc.longitude_deg = number_field(f, 8, "LOCATION longitude", name, 1);
        loc.timezone_hours = number_field(f, 9, "LOCATION time zone", name, 1);
        loc.elevation_m = number_field(f, 10, "LOCATION elevation", name, 1);
        if (std::abs(loc.latitude_deg) > 90.0 || std::abs(loc.longitude_deg) > 180.0 ||
            std::abs(loc.timezone_hours) > 14.0)
            fail_at(name, 1, "LOCATION latitude, longitude or time zone out of range");
    }

    // The other header lines up to DATA PERIODS,n,records per hour,...
    bool data_periods = false;
    while (!data_periods && std::getline(in, text)) {
        ++line;
        const std::string_view t = trim(text);
        if (starts_with(t, "DATA PERIODS")) {
            const auto f = split_fields(t);
            if (f.size() < 3)
                fail_at(name, line, "DATA PERIODS needs the number of records per hour");
            file.records_per_hour = integer_field(f, 3, "records per hour", name, line);
            if (file.records_per_hour < 1 || 60 % file.records_per_hour != 0)
                fail_at(name, line, "DATA PERIODS: records per hour must divide 60");
            data_periods = true;
        } else if (!t.empty() && t[0] >= '0' && t[0] <= '9') {
            fail_at(name, line, "data row before the DATA PERIODS header line");
        }
    }
    if (!data_periods)
        fail_at(name, line, "no DATA PERIODS header line");

    while (std::getline(in, text)) {
        ++line;
        const std::string_view t = trim(text);
        if (t.empty())
            continue;
        const auto f = split_fields(t);
        if (static_cast<int>(f.size()) != kEpwFieldCount)
            fail_at(name, line,
                    "data row has " + std::to_string(f.size()) + " fields, expected " +
                        std::to_string(kEpwFieldCount));
        EpwRecord r;
        r.line = line;
        r.year = integer_field(f, 1, "year", name, line);
        r.month = integer_field(f, 2, "month", name, line);
        r.day = integer_field(f, 3, "day", name, line);
        r.hour = integer_field(f, 4, "hour", name, line);
        r.minute = integer_field(f, 5, "minute", name, line);
        check_range(r.month, 1, 12, "month", name, line);
        // February may have a 29th in a typical year assembled from other years.
        check_range(r.day, 1, days_in_month(2000, r.month), "day", name, line);
        check_range(r.hour, 1, 24, "hour", name, line);
        check_range(r.minute, 0, 60, "minute", name, line);
        r.dry_bulb_c = number_field(f, 7, "dry bulb temperature", name, line);
        r.pressure_pa = number_field(f, 10, "atmospheric station pressure", name, line);
        r.ghi_wh = number_field(f, 14, "global horizontal radiation", name, line);
        r.dni_wh = number_field(f, 15, "direct normal radiation", name, line);
        r.dhi_wh = number_field(f, 16, "diffuse horizontal radiation", name, line);
        file.records.push_back(r);
    }
    if (file.records.empty())
        fail_at(name, line, "no data rows after DATA PERIODS");
    return file;
}

EpwFile read_epw(const std::filesystem::path& path)
{
    std::ifstream in(path);
    if (!in)
        throw std::runtime_error(path.string() + ": cannot open the EPW weather file");
    return parse_epw(in, path.string());
}

void require_irradiance(const EpwFile& file, const EpwRecord& r)
{
    const struct {
        double value;
        int field;
        const char* label;
    } fields[] = {{r.ghi_wh, 14, "global horizontal radiation"},
                  {r.dni_wh, 15, "direct normal radiation"},
                  {r.dhi_wh, 16, "diffuse horizontal radiation"}};
    for (const auto& f : fields) {
        if (f.value == 9999.0)
            fail_at(file.path, r.line,
                    std::string(f.label) + " (field " + std::to_string(f.field) +
                        ") is missing (9999), but the exposure needs it");
        if (!(f.value <= 9999.0))
            fail_at(file.path, r.line,
                    std::string(f.label) + " (field " + std::to_string(f.field) + ") is " +
                        fmt::format("{}", f.value) +
                        " Wh/m^2, not an irradiation (9999 marks a missing value)");
        if (f.value < 0.0)
            fail_at(file.path, r.line,
                    std::string(f.label) + " (field " + std::to_string(f.field) +
                        ") is negative");
    }
}

DateTime record_end(const EpwFile& file, const EpwRecord& r)
{
    (void)file;
    DateTime t;
    t.year = r.year;
    t.month = r.month;
    t.day = r.day;
    if (r.minute == 0 || r.minute == 60) {
        t.hour = r.hour;
        t.minute = 0;
    } else {
        t.hour = r.hour - 1;
        t.minute = r.minute;
    }
    return t;
}

}  // namespace patina::texgen
