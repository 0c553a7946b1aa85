// Writing and reading fade stacks (format in fade_stack.h).
#include "texgen/fade/fade_stack.h"

#include "texgen/stack/map_output.h"
#include "formats/fade_stack/fade_stack.h"

#include "core/image_io.h"
#include "core/pixel_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#ifndef PATINA_VERSION_STRING
#define PATINA_VERSION_STRING "(unknown version)"
#endif

namespace patina::texgen::fade {

namespace fs = std::filesystem;

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

    // The description (fade.toml), written last: a stack is complete when it exists.
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

    // fade_table.exr: rows = doses, columns = wavelengths (formats/fade_stack/fade_stack.h)
    formats::FadeTable t;
    t.rows = static_cast<int>(rows);
    t.columns = static_cast<int>(columns);
    for (auto* v : {&t.r_bottom, &t.r_top, &t.r_total, &t.t})
        v->resize(rows * columns);
    for (size_t k = 0; k < rows; ++k) {
        const LayerSpectra& s = table.spectra(k);
        for (size_t w = 0; w < columns; ++w) {
            const size_t i = k * columns + w;
            t.r_bottom[i] = static_cast<float>(s.r_bottom[w]);
            t.r_top[i] = static_cast<float>(s.r_top[w]);
            t.r_total[i] = static_cast<float>(s.reflectance[w]);
            t.t[i] = static_cast<float>(s.t[w]);
        }
    }
    write_pixels_atomic(dir / kFadeTableFile, formats::fade_table_pixels(t, d),
                        OIIO::TypeDesc::FLOAT);

    // dose.exr: the table coordinate and the dose of every texel
    TextureOptions tex;
    tex.format = OIIO::TypeDesc::FLOAT;
    // Uncompressed: zip took 5x longer than the rest of a 2048² map (bench_fade_map)
    tex.compression = "none";
    make_texture_atomic(dir / kDoseMapFile,
                        formats::dose_map_pixels(info.width, info.height, dose_pixels, d), tex);

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
    const formats::FadeTable table = formats::read_fade_table(ImagePixelReader(), d, dir);
    for (auto* v : {&s.r_total, &s.r_top, &s.t, &s.r_bottom})
        v->assign(table.rows, std::vector<double>(table.columns));
    for (int k = 0; k < table.rows; ++k)
        for (int w = 0; w < table.columns; ++w) {
            const size_t i = static_cast<size_t>(k) * table.columns + w;
            s.r_total[k][w] = table.r_total[i];
            s.r_top[k][w] = table.r_top[i];
            s.t[k][w] = table.t[i];
            s.r_bottom[k][w] = table.r_bottom[i];
        }
    return s;
}

}  // namespace patina::texgen::fade
