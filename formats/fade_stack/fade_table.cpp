// fade_table.exr and dose.exr of a fade stack (formats/fade_stack/fade_stack.h): their one layout.
#include "formats/fade_stack/fade_stack.h"

#include <cmath>
#include <string>

namespace patina::formats {

namespace fs = std::filesystem;

Pixels fade_table_pixels(const FadeTable& table, const FadeDescription& description)
{
    const size_t n = static_cast<size_t>(table.rows) * table.columns;
    if (table.r_bottom.size() != n || table.r_top.size() != n || table.r_total.size() != n ||
        table.t.size() != n)
        throw std::invalid_argument("fade_table_pixels: a value per row and column");
    Pixels p;
    p.width = table.columns;
    p.height = table.rows;
    p.channels = static_cast<int>(kFadeTableChannels.size());
    p.channel_names.assign(kFadeTableChannels.begin(), kFadeTableChannels.end());
    // In kFadeTableChannels' order, which is OpenEXR's sorted one.
    p.values.resize(n * 4);
    for (size_t i = 0; i < n; ++i) {
        p.values[4 * i + 0] = table.r_bottom[i];
        p.values[4 * i + 1] = table.r_top[i];
        p.values[4 * i + 2] = table.r_total[i];
        p.values[4 * i + 3] = table.t[i];
    }
    p.attributes = {{"patina:map", "fade_table"},
                    {"patina:material", description.material},
                    {"patina:illuminant", description.illuminant},
                    {"patina:colorspace", "raw"},
                    {"patina:description",
                     "rows: dose samples (see fade.toml [table] dose); columns: wavelengths "
                     "([table] wavelength_nm)"}};
    return p;
}

FadeTable read_fade_table(const PixelReader& reader, const FadeDescription& description,
                          const fs::path& folder)
{
    const fs::path file = description.table_path(folder);
    const Pixels p = reader.read(file);
    FadeTable table;
    table.rows = static_cast<int>(description.doses.size());
    table.columns = static_cast<int>(description.wavelength_nm.size());
    if (p.width != table.columns || p.height != table.rows)
        throw std::runtime_error(file.string() + ": " + std::to_string(p.width) + "x" +
                                 std::to_string(p.height) + " pixels, but its fade.toml describes " +
                                 std::to_string(table.columns) + " wavelengths x " +
                                 std::to_string(table.rows) + " doses");
    const int rb = channel_index(p, "R_bottom", kFadeTableChannels, file);
    const int rt = channel_index(p, "R_top", kFadeTableChannels, file);
    const int r = channel_index(p, "R_total", kFadeTableChannels, file);
    const int t = channel_index(p, "T", kFadeTableChannels, file);
    const size_t n = static_cast<size_t>(table.rows) * table.columns;
    for (auto* v : {&table.r_bottom, &table.r_top, &table.r_total, &table.t})
        v->resize(n);
    for (size_t i = 0; i < n; ++i) {
        const float* px = &p.values[i * p.channels];
        table.r_bottom[i] = px[rb];
        table.r_top[i] = px[rt];
        table.r_total[i] = px[r];
        table.t[i] = px[t];
        const float top = table.r_top[i] + table.t[i], bottom = table.r_bottom[i] + table.t[i];
        if (!std::isfinite(top) || !std::isfinite(bottom) || table.r_top[i] < 0.0f ||
            table.t[i] < 0.0f || table.r_bottom[i] < 0.0f || top > 1.0f + 1e-4f ||
            bottom > 1.0f + 1e-4f)
            throw std::runtime_error(file.string() + ": row " + std::to_string(i / table.columns) +
                                     ", column " + std::to_string(i % table.columns) +
                                     " is not a passive layer (R, T >= 0, R + T <= 1)");
    }
    return table;
}

Pixels dose_map_pixels(int width, int height, std::vector<float> coordinate_dose_coverage,
                       const FadeDescription& description)
{
    if (width <= 0 || height <= 0 ||
        coordinate_dose_coverage.size() != 3 * static_cast<size_t>(width) * height)
        throw std::invalid_argument("dose_map_pixels: three values per texel");
    Pixels p;
    p.width = width;
    p.height = height;
    p.channels = static_cast<int>(kDoseMapChannels.size());
    p.channel_names.assign(kDoseMapChannels.begin(), kDoseMapChannels.end());
    p.values = std::move(coordinate_dose_coverage);
    p.attributes = {{"patina:map", "dose"},
                    {"patina:baker", "fade"},
                    {"patina:units", "1, J/m^2"},
                    {"patina:colorspace", "raw"},
                    {"patina:material", description.material},
                    {"patina:illuminant", description.illuminant},
                    {"patina:coverage", kCoverageChannel},
                    {"patina:description",
                     "coordinate: fractional row of fade_table.exr; dose: radiant exposure of "
                     "the illuminant band, J/m^2; coverage: the exposure map's"}};
    return p;
}

std::vector<float> read_dose_coordinates(const PixelReader& reader,
                                         const FadeDescription& description,
                                         const fs::path& folder, int* width, int* height)
{
    const fs::path file = description.dose_map_path(folder);
    const Pixels p = reader.read(file);
    const int c = channel_index(p, "coordinate", kDoseMapChannels, file);
    std::vector<float> coordinate(static_cast<size_t>(p.width) * p.height);
    for (size_t i = 0; i < coordinate.size(); ++i) {
        coordinate[i] = p.values[i * p.channels + c];
        if (!std::isfinite(coordinate[i]))
            throw std::runtime_error(file.string() + ": texel (" + std::to_string(i % p.width) +
                                     ", " + std::to_string(i / p.width) +
                                     ") has a coordinate that is not finite");
    }
    *width = p.width;
    *height = p.height;
    return coordinate;
}

}  // namespace patina::formats
