#include "texgen/export/export_forecast.h"

#include "formats/texture_stack/texture_stack.h"
#include "texgen/export/export_asset.h"
#include "texgen/export/export_fade.h"
#include "texgen/forecast/years_map.h"
#include "texgen/texels/mesh_merge.h"

#include "core/image_io.h"

#include "texgen/meshes/mesh_input.h"
#include "texgen/texels/uv_wrap.h"

#include <fmt/format.h>

namespace patina::texgen {

namespace fs = std::filesystem;

bool is_forecast_folder(const fs::path& input)
{
    std::error_code ec;
    const fs::path manifest = stack_manifest_of(input);
    if (manifest.filename() != formats::kStackManifest || !fs::exists(manifest, ec))
        return false;
    try {
        return formats::read_texture_stack(manifest).maps.count(forecast::kForecastMap) > 0;
    } catch (const std::exception&) {
        return false;
    }
}

ExportResult export_forecast(const fs::path& input, const fs::path& output,
                             const ExportOptions& given, const ColorManager& colors)
{
    ExportOptions options = given;
    check_export_options(options, output);
    if (options.resolution > 0)
        throw std::runtime_error("--resolution: a forecast exports at its map's resolution");
    const fs::path manifest = stack_manifest_of(input);
    const formats::TextureStack stack = formats::read_texture_stack(manifest);
    const formats::StackMap& entry = stack.maps.at(forecast::kForecastMap);
    const fs::path file = stack.folder() / entry.file;
    const ImageData image = read_image(file);
    const int years = image.channel("years_to_threshold");
    const int delta_e = image.channel("delta_e_after");
    const int coverage = image.channel(formats::kCoverageChannel);
    if (years < 0 || delta_e < 0 || coverage < 0)
        throw std::runtime_error(fmt::format(
            "{}: expected the channels years_to_threshold, delta_e_after and {}",
            file.string(), formats::kCoverageChannel));
    const double threshold = entry.parameters["threshold_de2000"].value<double>().value_or(1.0);
    const double after = entry.parameters["after_years"].value<double>().value_or(0.0);

    forecast::YearsMaps maps;
    maps.width = image.width;
    maps.height = image.height;
    const size_t n = static_cast<size_t>(image.width) * image.height;
    std::vector<float> cover(n);
    maps.years.resize(n);
    maps.delta_e.resize(n);
    for (size_t i = 0; i < n; ++i) {
        maps.years[i] = image.pixels[i * image.channels + years];
        maps.delta_e[i] = image.pixels[i * image.channels + delta_e];
        cover[i] = image.pixels[i * image.channels + coverage];
    }
    forecast::FalseColours pictures = forecast::false_colours(maps, cover, threshold);
    // The pictures are display values; the base colour is linear (encoded again on export)
    colors.convert("srgb_texture", "lin_rec709", pictures.years.data(), n);
    colors.convert("srgb_texture", "lin_rec709", pictures.delta_e.data(), n);

    ExportGeometry geometry;
    fs::path mesh_file = options.mesh;
    BakedMesh baked;
    if (const auto exposure = entry.parameters["exposure"].value<std::string>())
        baked = mesh_of_exposure_map(*exposure);
    if (mesh_file.empty())
        mesh_file = baked.file;
    std::error_code ec;
    if (mesh_file.empty() || !fs::is_regular_file(mesh_file, ec))
        throw std::runtime_error(fmt::format(
            "export of '{}': the mesh its exposure map was baked on is {}; pass --mesh",
            manifest.string(), mesh_file.empty() ? "not recorded" : "'" + mesh_file.string() + "', which does not exist"));
    geometry.mesh = load_merged_mesh(
        mesh_file, convention_for_stack(options.convention, baked.convention,
                                        "the exposure map of " + manifest.string()));
    if (baked.uv_wrap)
        wrap_uvs_outside_udims(geometry.mesh);

    const std::string years_variant = fmt::format("years to dE00 {:g}", threshold);
    const std::string delta_e_variant = fmt::format("dE00 after {:g} y", after);
    std::vector<ExportStep> steps = make_steps(2, [&](size_t k, ExportStep& out) {
        out.label = k == 0 ? "years" : "delta_e";
        out.variant = k == 0 ? years_variant : delta_e_variant;
        out.manifest = manifest;
        out.extras = {{"forecast", relative_to(manifest, output.parent_path())},
                      {"quantity", k == 0 ? "years_to_threshold" : "delta_e_after"},
                      {"threshold_de2000", threshold},
                      {"after_years", after}};
        if (k == 0)
            out.extras["log10_years_dark_to_bright"] = {pictures.log10_years_dark,
                                                        pictures.log10_years_bright};
        else
            out.extras["delta_e_dark_to_bright"] = {0.0, pictures.delta_e_bright};
        out.flat = rough_dielectric(maps.width, maps.height,
                                    k == 0 ? pictures.years : pictures.delta_e,
                                    k == 0 ? "years to the threshold, false colour"
                                           : "dE00 after N years, false colour");
        encode_step(out, options, colors);
    });
    return write_export(steps, geometry, input, output, options, colors);
}

}  // namespace patina::texgen
