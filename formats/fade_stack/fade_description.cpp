#include "formats/fade_stack/fade_stack.h"

#include "formats/toml_location.h"

#include <cmath>
#include <cstdint>
#include <sstream>

namespace patina::formats {

namespace fs = std::filesystem;

namespace {

    const toml::table& section_of(const fs::path& file, const toml::table& root, const char* name)
    {
        const toml::node* n = root.get(name);
        if (!n)
            toml_fail(file, &root, std::string("no [") + name + "] table");
        if (!n->is_table())
            toml_fail(file, n, std::string("'") + name + "' must be a table");
        return *n->as_table();
    }

    std::vector<double> numbers(const fs::path& file, const toml::table& t, const char* section,
                                const char* key)
    {
        const toml::node* n = t.get(key);
        const toml::array* a = n ? n->as_array() : nullptr;
        if (!a)
            toml_fail(file, n ? n : &t,
                      std::string("[") + section + "] " + key + " is missing or not an array");
        std::vector<double> out;
        for (const toml::node& v : *a) {
            const auto x = v.value<double>();
            if (!x || !std::isfinite(*x))
                toml_fail(file, &v, std::string("[") + section + "] " + key +
                                        " holds a non-number");
            out.push_back(*x);
        }
        return out;
    }

    double number(const fs::path& file, const toml::table& t, const char* section,
                  const char* key, double fallback)
    {
        const toml::node* n = t.get(key);
        if (!n)
            return fallback;
        const auto x = n->value<double>();
        if (!x || !std::isfinite(*x))
            toml_fail(file, n, std::string("[") + section + "] " + key + " must be a number");
        return *x;
    }

    std::string text(const fs::path& file, const toml::table& t, const char* section,
                     const char* key, const std::string& fallback)
    {
        const toml::node* n = t.get(key);
        if (!n)
            return fallback;
        if (!n->is_string())
            toml_fail(file, n, std::string("[") + section + "] " + key + " must be a string");
        return n->value<std::string>().value_or(fallback);
    }

    /// The names of `key` must be `expected`, in that order.
    void check_channels(const fs::path& file, const toml::table& t, const char* section,
                        const char* const* expected, size_t count)
    {
        const toml::node* n = t.get("channels");
        if (!n)
            return;
        const toml::array* a = n->as_array();
        bool same = a && a->size() == count;
        for (size_t c = 0; same && c < count; ++c)
            same = (*a)[c].value<std::string>().value_or("") == expected[c];
        if (!same) {
            std::string list;
            for (size_t c = 0; c < count; ++c)
                list += (c ? ", " : "") + std::string(expected[c]);
            toml_fail(file, n, std::string("[") + section + "] channels must be " + list +
                                   " in that order");
        }
    }

    toml::array array_of(const std::vector<double>& v)
    {
        toml::array a;
        for (double x : v)
            a.push_back(x);
        return a;
    }

    template <size_t N>
    toml::array array_of(const std::array<const char*, N>& v)
    {
        toml::array a;
        for (const char* x : v)
            a.push_back(std::string(x));
        return a;
    }

    fs::path resolve(const std::string& file, const fs::path& folder)
    {
        const fs::path p(file);
        return (p.is_absolute() ? p : folder / p).lexically_normal();
    }

}  // namespace

fs::path FadeDescription::table_path(const fs::path& folder) const
{
    return resolve(table_file, folder);
}

fs::path FadeDescription::dose_map_path(const fs::path& folder) const
{
    return resolve(dose_map_file, folder);
}

FadeDescription read_fade_description(const fs::path& path)
{
    std::error_code ec;
    const fs::path file = fs::is_directory(path, ec) ? path / kFadeDescription : path;
    const toml::table root = parse_toml_file(file);
    FadeDescription d;

    const toml::table& fade = section_of(file, root, "fade");
    const toml::node* format = fade.get("format");
    const auto version = format ? format->value<int64_t>() : std::nullopt;
    if (!version || !format->is_integer() || *version < 1)
        toml_fail(file, format ? format : &fade, "[fade] format must be a positive integer");
    if (*version > kFadeFormatVersion)
        toml_fail(file, format,
                  "fade stack format " + std::to_string(*version) + " is newer than the " +
                      std::to_string(kFadeFormatVersion) +
                      " this Patina reads (the stack was written by a newer Patina)");
    d.format = static_cast<int>(*version);
    d.generator = text(file, fade, "fade", "generator", "");
    d.material = text(file, fade, "fade", "material", "");
    d.material_file = text(file, fade, "fade", "material_file", "");
    d.illuminant = text(file, fade, "fade", "illuminant", "");
    if (fade.contains("illuminant_band_nm")) {
        const std::vector<double> band = numbers(file, fade, "fade", "illuminant_band_nm");
        if (band.size() != 2 || !(band[0] <= band[1]))
            toml_fail(file, fade.get("illuminant_band_nm"),
                      "[fade] illuminant_band_nm must be [min, max] with min <= max");
        d.band_min_nm = band[0];
        d.band_max_nm = band[1];
    }
    d.sublayers = static_cast<int>(number(file, fade, "fade", "sublayers", 0));
    d.both_sides = fade["both_sides"].value<bool>().value_or(false);

    const toml::table& table = section_of(file, root, "table");
    d.table_file = text(file, table, "table", "file", "");
    if (d.table_file.empty())
        toml_fail(file, &table, "[table] file is missing");
    check_channels(file, table, "table", kFadeTableChannels.data(), kFadeTableChannels.size());
    d.entries = static_cast<int>(number(file, table, "table", "entries", 0));
    d.substeps = static_cast<int>(number(file, table, "table", "substeps", 0));
    d.knee_dose = number(file, table, "table", "knee_dose", 0.0);
    d.max_dose = number(file, table, "table", "max_dose", 0.0);
    d.max_interpolation_error = number(file, table, "table", "max_interpolation_error", 0.0);
    d.wavelength_nm = numbers(file, table, "table", "wavelength_nm");
    d.doses = numbers(file, table, "table", "dose");
    if (d.wavelength_nm.empty() || d.doses.empty())
        toml_fail(file, &table, "[table] needs at least one wavelength and one dose");
    for (size_t i = 1; i < d.wavelength_nm.size(); ++i)
        if (!(d.wavelength_nm[i] > d.wavelength_nm[i - 1]))
            toml_fail(file, table.get("wavelength_nm"), "[table] wavelength_nm must increase");
    for (size_t i = 1; i < d.doses.size(); ++i)
        if (!(d.doses[i] > d.doses[i - 1]))
            toml_fail(file, table.get("dose"), "[table] dose must increase");

    const toml::table& substrate = section_of(file, root, "substrate");
    d.substrate = numbers(file, substrate, "substrate", "reflectance");
    if (d.substrate.size() != d.wavelength_nm.size())
        toml_fail(file, substrate.get("reflectance"),
                  "[substrate] reflectance needs one value per wavelength");
    for (double rho : d.substrate)
        if (!(rho >= 0.0 && rho <= 1.0))
            toml_fail(file, substrate.get("reflectance"),
                      "[substrate] reflectance must lie in [0, 1]");

    const toml::table& dose_map = section_of(file, root, "dose_map");
    d.dose_map_file = text(file, dose_map, "dose_map", "file", "");
    if (d.dose_map_file.empty())
        toml_fail(file, &dose_map, "[dose_map] file is missing");
    if (dose_map.contains("resolution")) {
        const std::vector<double> r = numbers(file, dose_map, "dose_map", "resolution");
        if (r.size() != 2 || !(r[0] >= 1 && r[1] >= 1) || r[0] != std::floor(r[0]) ||
            r[1] != std::floor(r[1]))
            toml_fail(file, dose_map.get("resolution"),
                      "[dose_map] resolution must be [width, height] in texels");
        d.width = static_cast<int>(r[0]);
        d.height = static_cast<int>(r[1]);
    }
    d.min_dose = number(file, dose_map, "dose_map", "min_dose", 0.0);
    d.mean_dose = number(file, dose_map, "dose_map", "mean_dose", 0.0);
    d.max_dose_in_map = number(file, dose_map, "dose_map", "max_dose", 0.0);

    if (const toml::table* exposure = root["exposure"].as_table()) {
        if (const toml::array* files = (*exposure)["files"].as_array())
            for (const toml::node& f : *files)
                d.exposure.files.push_back(f.value<std::string>().value_or(""));
        d.exposure.channel = text(file, *exposure, "exposure", "channel", d.exposure.channel);
        d.exposure.units = text(file, *exposure, "exposure", "units", d.exposure.units);
        d.exposure.scale = number(file, *exposure, "exposure", "scale", 1.0);
        d.exposure.duration_s = number(file, *exposure, "exposure", "duration_s", 0.0);
        d.exposure.period_s = number(file, *exposure, "exposure", "period_s", 0.0);
    }
    return d;
}

std::string fade_description_text(const FadeDescription& d)
{
    toml::table fade{{"format", d.format},
                     {"generator", d.generator},
                     {"material", d.material},
                     {"material_file", d.material_file},
                     {"illuminant", d.illuminant},
                     {"illuminant_band_nm", array_of({d.band_min_nm, d.band_max_nm})},
                     {"dose_units", "J/m^2"},
                     {"sublayers", d.sublayers},
                     {"both_sides", d.both_sides}};
    toml::table table{
        {"file", d.table_file},
        {"channels", array_of(kFadeTableChannels)},
        {"rule", "H_k = H_0 (exp(k du) - 1), du = ln(1 + H_max / H_0) / (entries - 1); linear "
                 "in u = ln(1 + H / H_0) between rows"},
        {"entries", d.entries},
        {"knee_dose", d.knee_dose},
        {"max_dose", d.max_dose},
        {"substeps", d.substeps},
        {"max_interpolation_error", d.max_interpolation_error},
        {"wavelength_nm", array_of(d.wavelength_nm)},
        {"dose", array_of(d.doses)}};
    toml::table substrate{{"reflectance", array_of(d.substrate)}};
    toml::table dose_map{{"file", d.dose_map_file},
                         {"channels", array_of(kDoseMapChannels)},
                         {"coverage", kCoverageChannel},
                         {"resolution", toml::array{int64_t{d.width}, int64_t{d.height}}},
                         {"min_dose", d.min_dose},
                         {"mean_dose", d.mean_dose},
                         {"max_dose", d.max_dose_in_map}};
    toml::array files;
    for (const fs::path& f : d.exposure.files)
        files.push_back(f.string());
    toml::table exposure{{"files", files},
                         {"channel", d.exposure.channel},
                         {"units", d.exposure.units},
                         {"scale", d.exposure.scale},
                         {"duration_s", d.exposure.duration_s},
                         {"period_s", d.exposure.period_s}};
    toml::table root{{"fade", fade},
                     {"table", table},
                     {"substrate", substrate},
                     {"dose_map", dose_map},
                     {"exposure", exposure}};
    std::ostringstream out;
    out << "# A fade stack (patina-texgen fade): docs/file-formats.md \"Fade stack\"\n"
        << root << "\n";
    return out.str();
}

}  // namespace patina::formats
