#include "texgen/meshes/mesh_input.h"

#include "core/progress.h"
#include "texgen/texels/mesh_merge.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen {

namespace {

    bool same_unit(double a, double b)
    {
        return std::abs(a - b) <= 1e-6 * std::max(a, b);
    }

} // namespace

TriangleMesh load_mesh_with_warnings(const std::filesystem::path& file,
                                     const MeshConventionOptions& convention,
                                     MeshConvention* applied)
{
    MeshConvention used;
    TriangleMesh mesh = load_merged_mesh(file, convention, &used);
    for (const std::string& warning : used.warnings)
        print_warning("patina-texgen", fmt::format("mesh file '{}': {}", file.string(), warning));
    if (const std::string size = implausible_size_warning(bounds_of(mesh), used); !size.empty())
        print_warning("patina-texgen", fmt::format("mesh file '{}': {}", file.string(), size));
    if (applied)
        *applied = std::move(used);
    return mesh;
}

void record_convention(Metadata& parameters, const MeshConvention& applied)
{
    parameters.emplace_back("mesh_up", applied.up.name());
    parameters.emplace_back("mesh_metres_per_unit", static_cast<float>(applied.metres_per_unit));
}

void record_uv_set(Metadata& parameters, int uv_set)
{
    if (uv_set != 0)
        parameters.emplace_back("uv_set", uv_set);
}

void record_uv_wrap(Metadata& parameters)
{
    parameters.emplace_back("uv_wrap", 1);
}

bool recorded_uv_wrap(const toml::table& parameters)
{
    return parameters["uv_wrap"].value_or(0) != 0;
}

MeshConventionOptions recorded_convention(const toml::table& parameters)
{
    MeshConventionOptions o;
    if (const auto up = parameters["mesh_up"].value<std::string>())
        o.up = parse_axis(*up, "mesh_up");
    if (const auto metres = parameters["mesh_metres_per_unit"].value<double>())
        o.metres_per_unit = *metres;
    o.uv_set = parameters["uv_set"].value_or(0);
    return o;
}

MeshConventionOptions convention_for_stack(const MeshConventionOptions& user,
                                           const MeshConventionOptions& recorded,
                                           const std::string& what)
{
    MeshConventionOptions o = recorded;
    if (user.up) {
        if (recorded.up && *recorded.up != *user.up)
            throw std::runtime_error(fmt::format(
                "{} was made with the mesh's up axis {}, not {}: give --up {} or leave it out",
                what, recorded.up->name(), user.up->name(), recorded.up->name()));
        o.up = user.up;
    }
    if (user.metres_per_unit) {
        if (recorded.metres_per_unit &&
            !same_unit(*recorded.metres_per_unit, *user.metres_per_unit))
            throw std::runtime_error(fmt::format(
                "{} was made with the mesh in {}, not {}: give --unit {} or leave it out", what,
                unit_name(*recorded.metres_per_unit), unit_name(*user.metres_per_unit),
                unit_name(*recorded.metres_per_unit)));
        o.metres_per_unit = user.metres_per_unit;
    }
    if (user.uv_set != 0 && recorded.uv_set != 0 && user.uv_set != recorded.uv_set)
        throw std::runtime_error(fmt::format("{} was made in the mesh's uv set {}, not {}: give "
                                             "--uv-set {} or leave it out",
                                             what, recorded.uv_set, user.uv_set, recorded.uv_set));
    o.uv_set = user.uv_set != 0 ? user.uv_set : recorded.uv_set;
    return o;
}

} // namespace patina::texgen
