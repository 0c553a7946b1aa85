#include "texgen/patina/patina_domain.h"

#include "texgen/growth/surface_lattice.h"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>

#include <stdexcept>

namespace patina::texgen {

std::vector<std::vector<float>> PatinaDomain::per_tile(const std::vector<float>& node_values) const
{
    if (node_values.size() != size())
        throw std::invalid_argument("PatinaDomain::per_tile: one value per node expected");
    std::vector<std::vector<float>> out;
    size_t first = 0;
    for (const TexelGrid& grid : grids) {
        const size_t n = grid.groups.group_count();
        out.emplace_back(node_values.begin() + first, node_values.begin() + first + n);
        first += n;
    }
    return out;
}

PatinaDomain make_strip_domain(int width, int height, double size_m, GridBoundary boundary)
{
    if (width <= 0 || height <= 0 || !(size_m > 0.0))
        throw std::invalid_argument("strip: resolution and size must be positive");
    PatinaDomain d;
    d.is_strip = true;
    d.boundary = boundary;
    d.width = width;
    d.height = height;
    d.cell_size_m = size_m / width;
    d.lattice = make_grid_lattice(width, height, static_cast<float>(d.cell_size_m), boundary);

    // Every texel is covered by the strip; its sample is the cell centre, facing up (+y)
    // like a strip laid out on a rack, so `inclination` is 1 everywhere.
    TexelGrid grid;
    grid.udim = 1001;
    grid.width = width;
    grid.height = height;
    const size_t n = static_cast<size_t>(width) * height;
    grid.group_of_texel.resize(n);
    grid.coverage.assign(n, 1.0f);
    grid.groups.samples.reserve(n);
    grid.groups.offsets.reserve(n + 1);
    d.position.resize(n);
    d.normal.assign(n, Imath::V3f(0, 1, 0));
    d.uv.resize(n);
    d.area_weight.assign(n, 1.0f);
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const size_t i = static_cast<size_t>(y) * width + x;
            grid.group_of_texel[i] = static_cast<int32_t>(i);
            // The strip in the x-z plane, v along -z (north) as on a map.
            const Imath::V2f uv((x + 0.5f) / width, 1.0f - (y + 0.5f) / height);
            SurfaceSample s;
            s.P = Imath::V3f(static_cast<float>(uv.x * size_m), 0.0f,
                             static_cast<float>(-uv.y * size_m * height / width));
            s.N = s.Ng = Imath::V3f(0, 1, 0);
            s.uv = uv;
            grid.groups.samples.push_back(s);
            grid.groups.offsets.push_back(static_cast<uint32_t>(i + 1));
            d.position[i] = s.P;
            d.uv[i] = uv;
            d.bounds.extendBy(s.P);
        }
    }
    d.grids.push_back(std::move(grid));
    return d;
}

std::vector<float> material_fraction(const PatinaDomain& domain, const std::string& material)
{
    if (!domain.mesh)
        throw std::runtime_error(fmt::format("material '{}': a strip has no source materials "
                                             "(grow on a mesh with --mesh)", material));
    const TriangleMesh& mesh = *domain.mesh;
    std::vector<std::string> names = mesh.materials;
    if (names.empty())
        names.push_back(mesh.material_name);
    const auto found = std::find(names.begin(), names.end(), material);
    if (found == names.end())
        throw std::runtime_error(fmt::format("the mesh has no material '{}' (its materials: "
                                             "'{}')", material, fmt::join(names, "', '")));
    std::vector<float> fraction;
    fraction.reserve(domain.size());
    for (const TexelGrid& grid : domain.grids)
        for (size_t g = 0; g < grid.groups.group_count(); ++g) {
            size_t inside = 0;
            const size_t size = grid.groups.group_size(g);
            for (size_t k = 0; k < size; ++k)
                inside += mesh.material_of(grid.groups.samples[grid.groups.offsets[g] + k].triangle) ==
                          material;
            fraction.push_back(size ? static_cast<float>(inside) / static_cast<float>(size) : 0.0f);
        }
    return fraction;
}

PatinaDomain make_mesh_domain(const TriangleMesh& mesh, const RasterOptions& options)
{
    PatinaDomain d;
    d.mesh = &mesh;
    d.grids = rasterize_uv(mesh, options);
    d.lattice = build_surface_lattice(mesh, d.grids);
    for (const TexelGrid& grid : d.grids) {
        for (size_t g = 0; g < grid.groups.group_count(); ++g) {
            const SurfaceSample& s = grid.groups.samples[grid.groups.offsets[g]];
            d.position.push_back(s.P);
            d.normal.push_back(s.N);
            d.uv.push_back(s.uv);
        }
        std::vector<float> weight(grid.groups.group_count(), 0.0f);
        for (size_t t = 0; t < grid.texel_count(); ++t)
            if (const int32_t g = grid.group_of_texel[t]; g >= 0)
                weight[g] = grid.coverage[t];
        d.area_weight.insert(d.area_weight.end(), weight.begin(), weight.end());
    }
    for (const Imath::V3f& p : mesh.positions)
        d.bounds.extendBy(p);
    if (d.lattice.size() != d.size())
        throw std::logic_error("surface lattice and texel groups disagree in size");
    return d;
}

}  // namespace patina::texgen
