#include "texgen/export/export_fade.h"

#include "formats/fade_stack/fade_stack.h"
#include "texgen/export/export_asset.h"
#include "texgen/texels/mesh_merge.h"

#include "core/image_io.h"
#include "core/pixel_io.h"
#include "core/spectrum.h"

#include "texgen/meshes/mesh_input.h"
#include "texgen/texels/uv_wrap.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

    /// The side of the swatch a uniform dose is exported on, in metres.
    constexpr double kSwatchSide = 0.1;

    struct FadeStep {
        fs::path folder, manifest;
        formats::FadeDescription description;
        double seconds = -1.0;  ///< the exposure's length; -1: not known
        bool uniform = false;   ///< a --dose stack: no exposure maps
    };

    FadeStep read_step(const fs::path& input)
    {
        FadeStep step;
        std::error_code ec;
        step.folder = fs::is_directory(input, ec) ? input : input.parent_path();
        step.manifest = step.folder / formats::kFadeDescription;
        step.description = formats::read_fade_description(input);
        const formats::FadeExposure& exposure = step.description.exposure;
        step.uniform = exposure.files.empty();
        // As `fade` labels its plot: each map is one period (or --duration) of exposure.
        const double each = exposure.duration_s > 0.0 ? exposure.duration_s : exposure.period_s;
        if (step.uniform && step.description.max_dose_in_map == 0.0)
            step.seconds = 0.0;
        else if (each > 0.0)
            step.seconds = each * static_cast<double>(std::max<size_t>(exposure.files.size(), 1));
        return step;
    }

    /// R_total of every table row as linear Rec.709 (3 floats per row): the reflectance
    /// seen under D65 (CIE 1931 2°, spectrum_to_xyz), through OCIO from CIE-XYZ-D65. Linear
    /// interpolation between rows commutes with this linear map, so a texel's colour is the
    /// interpolation of its rows' colours, as spectral_km interpolates the spectra.
    std::vector<float> row_colors(const FadeStep& step, const ColorManager& colors)
    {
        const formats::FadeDescription& d = step.description;
        const formats::FadeTable table = formats::read_fade_table(ImagePixelReader(), d, step.folder);
        const std::vector<double>& nm = d.wavelength_nm;
        std::vector<float> rgb(3 * static_cast<size_t>(table.rows));
        for (int row = 0; row < table.rows; ++row) {
            const float* r = &table.r_total[static_cast<size_t>(row) * table.columns];
            auto reflectance = [&](double lambda) {
                const auto hi = std::upper_bound(nm.begin(), nm.end(), lambda);
                if (hi == nm.begin())
                    return double(r[0]);
                if (hi == nm.end())
                    return double(r[table.columns - 1]);
                const int i = static_cast<int>(hi - nm.begin());
                const double t = (lambda - nm[i - 1]) / (nm[i] - nm[i - 1]);
                return (1.0 - t) * r[i - 1] + t * r[i];
            };
            const Xyz xyz = spectrum_to_xyz(reflectance, d65);
            for (int k = 0; k < 3; ++k)
                rgb[3 * row + k] = static_cast<float>(xyz[k]);
        }
        colors.convert("CIE-XYZ-D65", "lin_rec709", rgb.data(), static_cast<size_t>(table.rows));
        return rgb;
    }

    /// The maps export writes for a fade stack at `width` x `height`: the base colour at
    /// every texel's table row, and the constant maps of a rough dielectric.
    FlattenedStack fade_maps(const FadeStep& step, int width, int height,
                             const ColorManager& colors)
    {
        const std::vector<float> rows = row_colors(step, colors);
        const int last = static_cast<int>(rows.size() / 3) - 1;
        int dose_width = 0, dose_height = 0;
        const std::vector<float> coordinates = formats::read_dose_coordinates(
            ImagePixelReader(), step.description, step.folder, &dose_width, &dose_height);
        if (!step.uniform && (dose_width != width || dose_height != height))
            throw std::runtime_error(fmt::format(
                "{}: {}x{} texels, not {}x{}",
                step.description.dose_map_path(step.folder).string(), dose_width, dose_height,
                width, height));
        const size_t texels = static_cast<size_t>(width) * height;
        std::vector<float> base(3 * texels);
        for (size_t i = 0; i < texels; ++i) {
            // A uniform stack's small map holds one dose: its first texel, everywhere.
            const float u = coordinates[step.uniform ? 0 : i];
            const float x = std::clamp(u, 0.0f, static_cast<float>(last));
            const int r = std::min(static_cast<int>(x), std::max(last - 1, 0));
            const float t = x - static_cast<float>(r);
            for (int k = 0; k < 3; ++k)
                base[3 * i + k] = last == 0 ? rows[k]
                                            : (1.0f - t) * rows[3 * r + k] + t * rows[3 * (r + 1) + k];
        }
        // spectral_km is Lambertian: a rough dielectric
        return rough_dielectric(width, height, std::move(base), "R_total under D65");
    }

    /// The mesh the first exposure map was baked on ("" when none records it).
    BakedMesh baked_mesh(const std::vector<FadeStep>& steps)
    {
        for (const FadeStep& step : steps)
            for (const fs::path& given : step.description.exposure.files) {
                BakedMesh mesh =
                    mesh_of_exposure_map(given.is_absolute() ? given : step.folder / given);
                if (!mesh.file.empty())
                    return mesh;
            }
        return {};
    }

}  // namespace

BakedMesh mesh_of_exposure_map(const fs::path& map)
{
    std::error_code ec;
    const fs::path manifest = map.parent_path() / formats::kStackManifest;
    if (!fs::exists(manifest, ec))
        return {};
    const formats::TextureStack stack = formats::read_texture_stack(manifest);
    for (const auto& [name, entry] : stack.maps) {
        if (entry.file.empty() || !fs::equivalent(stack.folder() / entry.file, map, ec))
            continue;
        if (const auto mesh = entry.parameters["mesh"].value<std::string>()) {
            const fs::path path(*mesh);
            const MeshConventionOptions convention = recorded_convention(entry.parameters);
            const bool wrap = recorded_uv_wrap(entry.parameters);
            if (path.is_absolute() || fs::exists(path, ec))
                return {path, convention, wrap};
            return {stack.folder() / path, convention, wrap};
        }
    }
    return {};
}

bool is_fade_stack(const fs::path& input)
{
    std::error_code ec;
    if (fs::is_directory(input, ec))
        return fs::exists(input / formats::kFadeDescription, ec);
    return input.filename() == formats::kFadeDescription;
}

std::string fade_age_name(double seconds, double unit_s)
{
    const char* unit = unit_s >= 365.0 * 86400.0 ? "y" : unit_s >= 86400.0 ? "d" : "h";
    const double scale = unit_s >= 365.0 * 86400.0 ? 365.0 * 86400.0
                         : unit_s >= 86400.0        ? 86400.0
                                                    : 3600.0;
    return fmt::format("{:.4g} {}", seconds / scale, unit);
}

ExportResult export_fade(const std::vector<fs::path>& inputs, const fs::path& output,
                         const ExportOptions& given, const ColorManager& colors)
{
    ExportOptions options = given;
    check_export_options(options, output);
    if (options.resolution > 0)
        throw std::runtime_error("--resolution: a fade stack exports at its dose map's "
                                 "resolution");

    std::vector<FadeStep> steps;
    for (const fs::path& input : inputs)
        steps.push_back(read_step(input));
    // In order of age: by time where every step's is known, else by mean dose.
    const bool timed = std::all_of(steps.begin(), steps.end(),
                                   [](const FadeStep& s) { return s.seconds >= 0.0; });
    auto age = [&](const FadeStep& s) { return timed ? s.seconds : s.description.mean_dose; };
    for (size_t k = 1; k < steps.size(); ++k)
        if (!(age(steps[k]) > age(steps[k - 1])))
            throw std::runtime_error(fmt::format(
                "export: the fade stacks must be given in order of age: '{}' ({} {}) comes after "
                "'{}' ({} {})",
                steps[k].manifest.string(), age(steps[k]), timed ? "s" : "J/m^2 mean dose",
                steps[k - 1].manifest.string(), age(steps[k - 1]),
                timed ? "s" : "J/m^2 mean dose"));

    // The dose maps' size: the first map-made stack's (uniform ones take it too).
    int width = 4, height = 4;
    for (const FadeStep& step : steps)
        if (!step.uniform) {
            width = step.description.width;
            height = step.description.height;
            break;
        }

    ExportGeometry geometry;
    const BakedMesh baked = baked_mesh(steps);
    const fs::path mesh_file = options.mesh.empty() ? baked.file : options.mesh;
    if (!mesh_file.empty()) {
        std::error_code ec;
        if (!fs::is_regular_file(mesh_file, ec))
            throw std::runtime_error(fmt::format(
                "export of '{}': the mesh '{}' its exposure maps were baked on does not exist "
                "(pass --mesh)", steps.front().manifest.string(), mesh_file.string()));
        geometry.mesh = load_merged_mesh(
            mesh_file, convention_for_stack(options.convention, baked.convention,
                                            "the exposure map of " +
                                                steps.front().manifest.string()));
        if (baked.uv_wrap)
            wrap_uvs_outside_udims(geometry.mesh);
    } else if (std::any_of(steps.begin(), steps.end(), [](const FadeStep& s) { return !s.uniform; })) {
        throw std::runtime_error(fmt::format(
            "export of '{}': the exposure maps do not say which mesh they were baked on; pass "
            "--mesh", steps.front().manifest.string()));
    } else {
        geometry.width_m = geometry.height_m = kSwatchSide;
    }

    const double oldest = steps.back().seconds;
    std::vector<ExportStep> exported = make_steps(steps.size(), [&](size_t k, ExportStep& out) {
        const FadeStep& step = steps[k];
        out.label = step.folder.filename().string();
        if (out.label.empty())
            out.label = "fade";
        out.variant = timed ? fade_age_name(step.seconds, std::max(oldest, 3600.0))
                            : fmt::format("{:.3g} J/m2", step.description.mean_dose);
        out.manifest = step.manifest;
        out.extras = {{"fade", relative_to(step.manifest, output.parent_path())},
                      {"mean_dose_j_per_m2", step.description.mean_dose}};
        if (timed)
            out.extras["time_s"] = step.seconds;
        out.flat = fade_maps(step, width, height, colors);
        encode_step(out, options, colors);
    });
    return write_export(exported, geometry, inputs.front(), output, options, colors);
}

}  // namespace patina::texgen
