#include "core/spectrum_csv.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <charconv>
#include <cmath>
#include <fstream>
#include <stdexcept>

namespace patina {

namespace {

    std::string trimmed(std::string_view s)
    {
        while (!s.empty() && (s.front() == ' ' || s.front() == '\t'))
            s.remove_prefix(1);
        while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\r'))
            s.remove_suffix(1);
        // A quoted name ("dark skin") loses its quotes.
        if (s.size() >= 2 && s.front() == '"' && s.back() == '"')
            s = s.substr(1, s.size() - 2);
        return std::string(s);
    }

    std::vector<std::string> fields(const std::string& line)
    {
        std::vector<std::string> out;
        size_t start = 0;
        for (;;) {
            const size_t comma = line.find(',', start);
            out.push_back(trimmed(std::string_view(line).substr(
                start, comma == std::string::npos ? std::string::npos : comma - start)));
            if (comma == std::string::npos)
                return out;
            start = comma + 1;
        }
    }

}  // namespace

size_t SpectrumCsv::column(const std::string& name) const
{
    if (name.empty()) {
        if (columns.size() == 1)
            return 0;
        throw std::runtime_error(fmt::format("'{}' holds {} spectra: name one (it has: {})",
                                             file.string(), columns.size(), fmt::join(columns, ", ")));
    }
    for (size_t i = 0; i < columns.size(); ++i)
        if (columns[i] == name)
            return i;
    throw std::runtime_error(fmt::format("'{}' has no column '{}' (it has: {})", file.string(),
                                         name, fmt::join(columns, ", ")));
}

SpectrumCsv read_spectrum_csv(const std::filesystem::path& file)
{
    std::ifstream in(file);
    if (!in)
        throw std::runtime_error(fmt::format("cannot read spectrum file '{}'", file.string()));
    SpectrumCsv csv;
    csv.file = file;
    std::string line;
    int number = 0;
    bool header = false;
    auto fail = [&](const std::string& what) {
        return std::runtime_error(fmt::format("{}:{}: {}", file.string(), number, what));
    };
    while (std::getline(in, line)) {
        ++number;
        const std::string t = trimmed(line);
        if (t.empty() || t.front() == '#')
            continue;
        std::vector<std::string> f = fields(line);
        if (!header) {
            if (f.size() < 2)
                throw fail("the header needs the wavelength's column and at least one more");
            csv.columns.assign(f.begin() + 1, f.end());
            csv.values.resize(csv.columns.size());
            header = true;
            continue;
        }
        if (f.size() != csv.columns.size() + 1)
            throw fail(fmt::format("{} fields, the header has {}", f.size(), csv.columns.size() + 1));
        std::vector<double> row;
        for (size_t i = 0; i < f.size(); ++i) {
            double v = 0.0;
            const char* end = f[i].data() + f[i].size();
            const auto r = std::from_chars(f[i].data(), end, v);
            if (f[i].empty() || r.ec != std::errc() || r.ptr != end || !std::isfinite(v))
                throw fail(fmt::format("'{}' in column '{}' is not a number", f[i],
                                       i == 0 ? std::string("wavelength") : csv.columns[i - 1]));
            row.push_back(v);
        }
        if (!csv.lambda_nm.empty() && !(row[0] > csv.lambda_nm.back()))
            throw fail(fmt::format("wavelength {} nm after {} nm: wavelengths must increase",
                                   row[0], csv.lambda_nm.back()));
        csv.lambda_nm.push_back(row[0]);
        for (size_t i = 1; i < row.size(); ++i)
            csv.values[i - 1].push_back(row[i]);
    }
    if (!header || csv.lambda_nm.empty())
        throw std::runtime_error(fmt::format("spectrum file '{}' has no {}", file.string(),
                                             header ? "rows" : "header"));
    return csv;
}

}  // namespace patina
