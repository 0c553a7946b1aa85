#include "texgen/fade/illuminant.h"

#include "core/data_files.h"
#include "core/spectrum.h"
#include "core/spectrum_csv.h"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <stdexcept>

namespace patina::texgen::fade {

namespace {

// CIE D65 (CIE 15:2004 table 1), as shipped by Debian's colord-data
// (/usr/share/colord/illuminant/CIE-D65.sp), scaled to the CIE table's convention (100 at
// 560 nm). The F and LED lamps are read from data/lamps/ (their sources are in the files).
// CIE D65, 300-830 nm every 5 nm (107 values).
constexpr double kD65[] = {
    0.0341, 1.6643, 3.2945, 11.7652, 20.236, 28.6447, 37.0535, 38.5011, 39.9488, 42.4302,
    44.9117, 45.775, 46.6383, 49.3637, 52.0891, 51.0323, 49.9755, 52.3118, 54.6482, 68.7015,
    82.7549, 87.1204, 91.486, 92.4589, 93.4318, 90.057, 86.6823, 95.7736, 104.865, 110.936,
    117.008, 117.41, 117.812, 116.336, 114.861, 115.392, 115.923, 112.367, 108.811, 109.082,
    109.354, 108.578, 107.802, 106.296, 104.79, 106.239, 107.689, 106.047, 104.405, 104.225,
    104.046, 102.023, 100, 98.1671, 96.3342, 96.0611, 95.788, 92.2368, 88.6856, 89.3459, 90.0062,
    89.8026, 89.5991, 88.6489, 87.6987, 85.4936, 83.2886, 83.4939, 83.6992, 81.863, 80.0268,
    80.1207, 80.2146, 81.2462, 82.2778, 80.281, 78.2842, 74.0027, 69.7213, 70.6652, 71.6091,
    72.979, 74.349, 67.9765, 61.604, 65.7448, 69.8856, 72.4863, 75.087, 69.3398, 63.5927,
    55.0054, 46.4182, 56.6118, 66.8054, 65.0941, 63.3828, 63.8434, 64.304, 61.8779, 59.4519,
    55.7054, 51.959, 54.6998, 57.4406, 58.8765, 60.3125
};

// The lamp tables of data/lamps/ (share/patina/data/lamps/ beside the tools).
struct LampFile {
    const char* file;
    const char* source;
};
constexpr LampFile kLampFiles[] = {
    {"lamps/cie_f_illuminants.csv", "CIE 15:2004 table 10 (= CIE 15:2018), fluorescent lamps"},
    {"lamps/cie_led_illuminants.csv", "CIE 15:2018, typical LED illuminants"},
};

TabulatedSpectrum table_5nm(const double* v, size_t count, double first_nm)
{
    TabulatedSpectrum s;
    // Zero one step beyond each end, so the SPD vanishes outside its table.
    s.nm.push_back(first_nm - 5.0);
    s.value.push_back(0.0);
    for (size_t i = 0; i < count; ++i) {
        s.nm.push_back(first_nm + 5.0 * static_cast<double>(i));
        s.value.push_back(v[i]);
    }
    s.nm.push_back(s.nm.back() + 5.0);
    s.value.push_back(0.0);
    return s;
}

}  // namespace

std::vector<double> Illuminant::spectral_irradiance(const WavelengthGrid& grid,
                                                    double irradiance_w_m2) const
{
    // Normalise over the band at 1 nm (trapezoid): the band irradiance is irradiance_w_m2
    // whatever the solver's grid.
    const int n = std::max(1, static_cast<int>(std::ceil(band_max_nm - band_min_nm)));
    const double h = (band_max_nm - band_min_nm) / n;
    double band = 0.0;
    for (int i = 0; i <= n; ++i)
        band += (i == 0 || i == n ? 0.5 : 1.0) * h * relative.at(band_min_nm + i * h);
    if (!(band > 0.0))
        throw std::runtime_error(fmt::format("illuminant '{}': no power in {}-{} nm", name,
                                             band_min_nm, band_max_nm));
    std::vector<double> e = grid.sample(relative);
    for (double& v : e)
        v *= irradiance_w_m2 / band;
    return e;
}

Illumination Illuminant::illumination(const WavelengthGrid& grid, double irradiance_w_m2,
                                      bool both_sides) const
{
    Illumination light;
    light.top = spectral_irradiance(grid, irradiance_w_m2);
    if (both_sides)
        light.bottom = light.top;
    return light;
}

Illuminant illuminant_by_name(const std::string& name)
{
    std::string n = name;
    std::transform(n.begin(), n.end(), n.begin(),
                   [](unsigned char c) { return static_cast<char>(std::toupper(c)); });
    if (n == "D65")
        return {"D65", table_5nm(kD65, std::size(kD65), 300.0), 300.0, 830.0,
                "CIE 15:2004 table 1 (D65, 300-830 nm)"};
    if (n == "FLUORESCENT")
        n = "F11";
    if (n == "E" || n == "FLAT") {
        // The equal-energy spectrum (CIE illuminant E) over the D65 band: a flat lamp.
        return {"E", TabulatedSpectrum{{300.0, 830.0}, {100.0, 100.0}}, 300.0, 830.0,
                "CIE illuminant E (equal energy), 300-830 nm"};
    }
    for (const LampFile& lamps : kLampFiles) {
        const SpectrumCsv csv = read_spectrum_csv(find_data_file(lamps.file));
        for (size_t c = 0; c < csv.columns.size(); ++c) {
            std::string column = csv.columns[c];
            std::transform(column.begin(), column.end(), column.begin(),
                           [](unsigned char ch) { return static_cast<char>(std::toupper(ch)); });
            if (column != n)
                continue;
            Illuminant il = illuminant_from_table(csv.columns[c], csv.lambda_nm, csv.values[c]);
            il.source = std::string(lamps.source) + " (" + lamps.file + ")";
            return il;
        }
    }
    if (n == "A") {
        // CIE A is defined by Planck's law at 2856 K (core spectrum.h), at any wavelength;
        // tabulated here at 1 nm over the same 300-830 nm band as D65.
        TabulatedSpectrum s;
        for (int nm = 300; nm <= 830; ++nm) {
            s.nm.push_back(nm);
            s.value.push_back(patina::illuminant_a(static_cast<float>(nm)));
        }
        return {"A", s, 300.0, 830.0, "CIE 15:2004 (Planck, 2848 K with c2 = 1.435e-2 m K: 2856 K on today's c2)"};
    }
    throw std::runtime_error(fmt::format(
        "unknown illuminant '{}' (known: {})", name, known_illuminant_names()));
}

std::string known_illuminant_names()
{
    std::string names = "D65, A, E (= flat)";
    for (const LampFile& lamps : kLampFiles) {
        try {
            for (const std::string& column : read_spectrum_csv(find_data_file(lamps.file)).columns)
                names += ", " + column;
        } catch (const std::exception&) {
            names += std::string(", (") + lamps.file + " not found)";
        }
    }
    return names + ", fluorescent (= F11)";
}

Illuminant illuminant_from_csv(const std::filesystem::path& file, const std::string& column)
{
    const SpectrumCsv csv = read_spectrum_csv(file);
    const size_t c = csv.column(column);
    try {
        Illuminant il = illuminant_from_table(csv.columns[c], csv.lambda_nm, csv.values[c]);
        il.source = file.string();
        return il;
    } catch (const std::runtime_error& e) {
        throw std::runtime_error(file.string() + ": " + e.what());
    }
}

Illuminant illuminant_from_text(const std::string& text)
{
    const size_t colon = text.rfind(':');
    const std::filesystem::path file =
        colon == std::string::npos ? std::filesystem::path(text)
                                   : std::filesystem::path(text.substr(0, colon));
    if (text.find('/') != std::string::npos || file.extension() == ".csv" ||
        std::filesystem::exists(file))
        return illuminant_from_csv(file, colon == std::string::npos ? "" : text.substr(colon + 1));
    return illuminant_by_name(text);
}

Illuminant illuminant_from_table(const std::string& name, std::vector<double> nm,
                                 std::vector<double> relative)
{
    if (nm.size() != relative.size() || nm.size() < 2)
        throw std::runtime_error(
            fmt::format("illuminant '{}': need >= 2 wavelengths with one value each", name));
    for (size_t i = 0; i < nm.size(); ++i) {
        if (i > 0 && !(nm[i] > nm[i - 1]))
            throw std::runtime_error(fmt::format("illuminant '{}': wavelengths must increase",
                                                 name));
        if (!(relative[i] >= 0.0))
            throw std::runtime_error(fmt::format("illuminant '{}': negative value at {} nm",
                                                 name, nm[i]));
    }
    Illuminant il;
    il.name = name;
    il.band_min_nm = nm.front();
    il.band_max_nm = nm.back();
    il.source = "table";
    // Zero outside the table.
    const double step = nm[1] - nm[0];
    il.relative.nm.push_back(nm.front() - step);
    il.relative.value.push_back(0.0);
    il.relative.nm.insert(il.relative.nm.end(), nm.begin(), nm.end());
    il.relative.value.insert(il.relative.value.end(), relative.begin(), relative.end());
    il.relative.nm.push_back(nm.back() + (nm.back() - nm[nm.size() - 2]));
    il.relative.value.push_back(0.0);
    return il;
}

}  // namespace patina::texgen::fade
