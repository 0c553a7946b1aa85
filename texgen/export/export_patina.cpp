#include "texgen/export/export_patina.h"

#include "formats/texture_stack/texture_stack.h"
#include "texgen/export/export_asset.h"
#include "texgen/export/gltf_geometry.h"
#include "texgen/flatten/flatten_stack.h"
#include "texgen/flatten/patina_stack_files.h"
#include "texgen/texels/mesh_merge.h"

#include "core/cancel.h"

#include "texgen/meshes/mesh_input.h"
#include "texgen/texels/uv_wrap.h"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

    struct Step {
        double time_years = 0.0;
        std::string label;  ///< "t30": the step's folder, or "stack" for a lone stack
        PatinaStackFiles stack;
    };

    /// The steps of `input`: every step of a series, or the one stack.
    std::vector<Step> read_steps(const fs::path& input)
    {
        std::vector<Step> steps;
        std::error_code ec;
        if (fs::is_directory(input, ec) && !fs::exists(input / formats::kStackManifest, ec) &&
            fs::exists(input / formats::kSeriesManifest, ec)) {
            const formats::StackSeries series = formats::read_stack_series(input);
            for (const formats::SeriesStep& s : series.steps) {
                Step step;
                step.time_years = s.time_years;
                step.label = s.folder;
                step.stack = read_patina_stack(series.folder() / s.folder);
                steps.push_back(std::move(step));
            }
        } else {
            Step step;
            step.stack = read_patina_stack(input);
            step.time_years = step.stack.time_years;
            step.label = step.stack.manifest.parent_path().filename().string();
            if (step.label.empty())
                step.label = "stack";
            steps.push_back(std::move(step));
        }
        return steps;
    }

}  // namespace

std::string age_name(double years)
{
    return fmt::format("{} y", years);
}

ExportResult export_patina(const fs::path& input, const fs::path& output,
                           const ExportOptions& given, const ColorManager& colors)
{
    ExportOptions options = given;
    check_export_options(options, output);

    // Every step read and flattened before anything is written.
    std::vector<Step> steps = read_steps(input);
    const PatinaStackFiles& first_stack = steps.front().stack;
    TriangleMesh mesh;
    FlattenOptions flatten;
    if (!(first_stack.strip_size_m > 0.0)) {
        const fs::path mesh_file = options.mesh.empty() ? first_stack.mesh : options.mesh;
        if (mesh_file.empty())
            throw std::runtime_error(fmt::format(
                "export of '{}': the stack was grown on the mesh '{}' and does not record its "
                "path; pass --mesh", first_stack.manifest.string(), first_stack.domain));
        std::error_code ec;
        if (!fs::is_regular_file(mesh_file, ec))
            throw std::runtime_error(fmt::format(
                "export of '{}': the mesh '{}' the stack was grown on does not exist{}",
                first_stack.manifest.string(), mesh_file.string(),
                options.mesh.empty() ? " (pass --mesh)" : ""));
        mesh = load_merged_mesh(
            mesh_file, convention_for_stack(options.convention, first_stack.mesh_convention,
                                            first_stack.manifest.string()));
        if (first_stack.uv_wrap)
            wrap_uvs_outside_udims(mesh);
        const int width = options.resolution > 0 ? options.resolution : first_stack.width;
        flatten.texel_size_m = mean_texel_size_m(mesh, width, mesh_file.string());
    }
    flatten.resolution = options.resolution;
    flatten.normal_scale = options.normal_scale;
    flatten.target = gltf_target(options.target);
    flatten.only.assign(formats::kGltfExportMaps.begin(), formats::kGltfExportMaps.end());
    // The steps must be of one strip or mesh (the maps' sizes are checked with the rest).
    for (const Step& step : steps)
        if (step.stack.strip_size_m != first_stack.strip_size_m ||
            step.stack.domain != first_stack.domain)
            throw std::runtime_error(fmt::format(
                "export of '{}': the steps disagree: {} was grown on {} ({} m), {} on {} ({} m)",
                input.string(), steps.front().label, first_stack.domain,
                first_stack.strip_size_m, step.label, step.stack.domain,
                step.stack.strip_size_m));

    // Each step flattened (and, for glTF, encoded) in parallel with the others.
    std::vector<ExportStep> exported = make_steps(steps.size(), [&](size_t k, ExportStep& out) {
        const Step& step = steps[k];
        out.label = step.label;
        out.variant = age_name(step.time_years);
        out.manifest = step.stack.manifest;
        out.extras = {{"time_years", step.time_years},
                      {"stack", relative_to(step.stack.manifest, output.parent_path())}};
        out.flat = flatten_stack(step.stack, colors, flatten);
        encode_step(out, options, colors);
    });

    ExportGeometry geometry;
    geometry.mesh = std::move(mesh);
    geometry.keep_off = first_stack.keep_off;
    geometry.width_m = first_stack.strip_size_m;
    geometry.height_m = first_stack.strip_size_m * exported.front().flat.height /
                        std::max(1, exported.front().flat.width);
    return write_export(exported, geometry, input, output, options, colors);
}

}  // namespace patina::texgen
