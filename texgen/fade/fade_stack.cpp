// Writing and reading fade stacks (format in fade_stack.h).
#include "texgen/fade/fade_stack.h"

#include "texgen/stack/map_output.h"
#include "formats/fade_stack.h"

#include "core/image_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#ifndef PATINA_VERSION_STRING
#define PATINA_VERSION_STRING "(unknown version)"
#endif

namespace patina::texgen::fade {

namespace fs = std::filesystem;

namespace {

    const std::vector<std::string> kTableChannels(formats::kFadeTableChannels.begin(),
                                                  formats::kFadeTableChannels.end());
    const std::vector<std::string> kDoseChannels(formats::kDoseMapChannels.begin(),
                                                 formats::kDoseMapChannels.end());

}  // namespace

DoseRow::DoseRow(const DoseTable& table)
{
    // dose_table.h: H_k = H_0 (exp(k du) - 1), du = ln(1 + H_max / H_0) / (n - 1)
    const DoseTableOptions& o = table.options();
    const size_t n = table.doses().size();
    knee_ = o.knee_dose_j_m2;
    last_ = n > 1 ? static_cast<double>(n - 1) : 0.0;
    inv_du_ = n > 1 ? last_ / std::log1p(o.max_dose_j_m2 / o.knee_dose_j_m2) : 0.0;
}

double table_coordinate(const DoseTable& table, double dose_j_m2)
{
    return DoseRow(table)(dose_j_m2);
}

double interpolation_error(const DoseTable& table, const DoseTable& fine)
{
    if (fine.doses().size() != 2 * table.doses().size() - 1)
        throw std::runtime_error("interpolation_error: the fine table needs 2n - 1 entries");
    double worst = 0.0;
    for (size_t k = 1; k < fine.doses().size(); k += 2) {
        const LayerSpectra coarse = table.spectra_at(fine.doses()[k]);
        const LayerSpectra& exact = fine.spectra(k);
        for (size_t w = 0; w < exact.reflectance.size(); ++w)
            worst = std::max(worst, std::abs(coarse.reflectance[w] - exact.reflectance[w]));
    }
    return worst;
}

void write_fade_stack(const fs::path& dir, const DoseTable& table, const FadeStackInfo& info,
                      const std::vector<float>& dose_pixels)
{
    const size_t texels = static_cast<size_t>(info.width) * info.height;
    if (info.width <= 0 || info.height <= 0 || dose_pixels.size() != 3 * texels)
        throw std::runtime_error(fmt::format("fade stack '{}': {} dose values for a {}x{} map",
                                             dir.string(), dose_pixels.size() / 3, info.width,
                                             info.height));
    const size_t rows = table.doses().size(), columns = table.grid().size();
    if (info.substrate.size() != columns)
        throw std::runtime_error(fmt::format("fade stack '{}': {} substrate values for {} "
                                             "wavelengths",
                                             dir.string(), info.substrate.size(), columns));

    // fade_table.exr: rows = doses, columns = wavelengths, channels in stored (sorted) order
    std::vector<float> pixels(rows * columns * 4);
    for (size_t k = 0; k < rows; ++k) {
        const LayerSpectra& s = table.spectra(k);
        for (size_t w = 0; w < columns; ++w) {
            float* p = &pixels[(k * columns + w) * 4];
            p[0] = static_cast<float>(s.r_bottom[w]);
            p[1] = static_cast<float>(s.r_top[w]);
            p[2] = static_cast<float>(s.reflectance[w]);
            p[3] = static_cast<float>(s.t[w]);
        }
    }
    const Metadata table_meta = {
        {"patina:map", std::string("fade_table")},
        {"patina:material", info.material},
        {"patina:illuminant", info.illuminant},
        {"patina:colorspace", std::string("raw")},
        {"patina:description",
         std::string("rows: dose samples (see fade.toml [table] dose); columns: wavelengths "
                     "([table] wavelength_nm)")}};
    write_image_atomic(dir / kFadeTableFile, pixels.data(), static_cast<int>(columns),
                       static_cast<int>(rows), 4, kTableChannels, OIIO::TypeDesc::FLOAT,
                       table_meta);

    // dose.exr: the table coordinate and the dose of every texel
    TextureOptions tex;
    tex.format = OIIO::TypeDesc::FLOAT;
    // Uncompressed: zip took 5x longer than the rest of a 2048² map (bench_fade_map)
    tex.compression = "none";
    tex.metadata = {{"patina:map", std::string("dose")},
                    {"patina:baker", std::string("fade")},
                    {"patina:units", std::string("1, J/m^2")},
                    {"patina:colorspace", std::string("raw")},
                    {"patina:material", info.material},
                    {"patina:illuminant", info.illuminant},
                    {"patina:coverage", std::string(kCoverageChannel)},
                    {"patina:description",
                     std::string("coordinate: fractional row of fade_table.exr; dose: radiant "
                                 "exposure of the illuminant band, J/m^2; coverage: the "
                                 "exposure map's")}};
    make_texture_atomic(dir / kDoseMapFile, dose_pixels.data(), info.width, info.height, 3,
                        kDoseChannels, tex);

    // fade.toml, last: a stack is complete when its description exists
    const DoseTableOptions& o = table.options();
    formats::FadeDescription d;
    d.generator = std::string("patina-texgen ") + PATINA_VERSION_STRING;
    d.material = info.material;
    d.material_file = info.material_file.string();
    d.illuminant = info.illuminant;
    d.band_min_nm = info.band_min_nm;
    d.band_max_nm = info.band_max_nm;
    d.sublayers = o.sublayers;
    d.both_sides = o.both_sides;
    d.entries = o.entries;
    d.knee_dose = o.knee_dose_j_m2;
    d.max_dose = o.max_dose_j_m2;
    d.substeps = o.substeps;
    d.max_interpolation_error = info.max_interpolation_error;
    d.wavelength_nm = table.grid().nm;
    d.doses = table.doses();
    d.substrate = info.substrate;
    d.width = info.width;
    d.height = info.height;
    d.min_dose = info.min_dose;
    d.mean_dose = info.mean_dose;
    d.max_dose_in_map = info.max_dose;
    d.exposure = info.exposure;
    write_file_atomic(dir / kFadeToml, {formats::fade_description_text(d)},
                      "fade stack description");
}

FadeStack read_fade_stack(const fs::path& dir)
{
    const fs::path file = dir / kFadeToml;
    const formats::FadeDescription d = formats::read_fade_description(file);
    FadeStack s;
    s.wavelength_nm = d.wavelength_nm;
    s.doses = d.doses;
    s.substrate = d.substrate;
    s.material = d.material;
    s.illuminant = d.illuminant;
    s.max_interpolation_error = d.max_interpolation_error;
    s.dose_map = d.dose_map_path(dir);
    const fs::path table_file = d.table_path(dir);
    const ImageData image = read_image(table_file);
    if (image.width != static_cast<int>(s.wavelength_nm.size()) ||
        image.height != static_cast<int>(s.doses.size()))
        throw std::runtime_error(fmt::format("{}: {}x{} pixels, but {} describes {} wavelengths "
                                             "x {} doses",
                                             table_file.string(), image.width, image.height,
                                             file.string(), s.wavelength_nm.size(),
                                             s.doses.size()));
    const int c_rb = image.channel("R_bottom"), c_rt = image.channel("R_top"),
              c_r = image.channel("R_total"), c_t = image.channel("T");
    if (c_rb < 0 || c_rt < 0 || c_r < 0 || c_t < 0)
        throw std::runtime_error(table_file.string() +
                                 ": needs channels R_bottom, R_top, R_total and T");
    for (auto* v : {&s.r_total, &s.r_top, &s.t, &s.r_bottom})
        v->assign(image.height, std::vector<double>(image.width));
    for (int k = 0; k < image.height; ++k)
        for (int w = 0; w < image.width; ++w) {
            s.r_total[k][w] = image.at(w, k, c_r);
            s.r_top[k][w] = image.at(w, k, c_rt);
            s.t[k][w] = image.at(w, k, c_t);
            s.r_bottom[k][w] = image.at(w, k, c_rb);
        }
    return s;
}

}  // namespace patina::texgen::fade
