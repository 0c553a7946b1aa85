#include "texgen/stone_export/volume_export.h"

#include "formats/stone_volume/stone_volume.h"

#include "core/pixel_io.h"

#include "core/embree_scene.h"
#include "core/image_io.h"
#include "core/limits.h"
#include "core/output_transaction.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <system_error>

namespace patina::texgen::stone {

namespace fs = std::filesystem;
using Imath::V3d;

Imath::V3d WorldVolume::centre(int i, int j, int k) const
{
    const V3d size = bounds.max - bounds.min;
    return bounds.min + V3d((i + 0.5) * size.x / nx, (j + 0.5) * size.y / ny,
                            (k + 0.5) * size.z / nz);
}

void output_fractions(const StoneState& st, std::vector<float>& crust, std::vector<float>& iron,
                      std::vector<float>& salt)
{
    const size_t n = st.density.size();
    crust.assign(n, 0.0f);
    iron.assign(n, 0.0f);
    salt.assign(n, 0.0f);
    const StoneParameters& p = st.params;
    tbb::parallel_for(size_t(0), n, [&](size_t c) {
        crust[c] = std::clamp(float(st.black[c] / p.crust_scale), 0.0f, 1.0f);
        // Iron oxide seen at c: the yellowing crust and the stone's own iron minerals.
        iron[c] = std::clamp(float(st.crust[kIron][c] / p.iron_scale +
                                   st.solid[kIron][c] / p.mineral_iron_scale),
                             0.0f, 1.0f);
        salt[c] = std::clamp(float(st.crust[kSalt][c] / p.salt_scale), 0.0f, 1.0f);
    });
    for (auto* f : {&crust, &iron, &salt})
        st.lattice->fill_halo(f->data());
}

namespace {

    /// The world grid's box, voxel size and counts for `mesh` at `resolution`.
    struct WorldGrid {
        Imath::Box3d box;
        double h = 0;
        int nx = 0, ny = 0, nz = 0;
    };

    WorldGrid world_grid(const TriangleMesh& mesh, int resolution)
    {
        if (resolution < 2)
            throw std::runtime_error(fmt::format("world grid: resolution must be >= 2 (got {})",
                                                 resolution));
        WorldGrid g;
        for (const auto& p : mesh.positions)
            g.box.extendBy(V3d(p.x, p.y, p.z));
        const V3d size = g.box.max - g.box.min;
        const double longest = std::max({size.x, size.y, size.z});
        g.h = longest / (resolution - 2);
        g.nx = std::max(2, int(std::ceil(size.x / g.h)) + 2);
        g.ny = std::max(2, int(std::ceil(size.y / g.h)) + 2);
        g.nz = std::max(2, int(std::ceil(size.z / g.h)) + 2);
        return g;
    }

}  // namespace

void check_world_volume_memory(const TriangleMesh& mesh, int resolution, const char* option)
{
    const WorldGrid g = world_grid(mesh, resolution);
    // What the volume's readers load (formats/stone_volume/stone_volume.h): refused before the run.
    if (static_cast<double>(g.nx) * g.ny * g.nz > formats::kMaxVolumeVoxels)
        throw std::runtime_error(fmt::format(
            "{} {}: a {}x{}x{} world volume is more than the 512^3 voxels a stone volume may "
            "hold; lower {}",
            option, resolution, g.nx, g.ny, g.nz, option));
    // Six float channels (four voxel channels, two fields), twice: the volume and the
    // file's interleaved pixels.
    check_memory(option, 2.0 * 6.0 * sizeof(float) * g.nx * g.ny * g.nz,
                 fmt::format("a {}x{}x{} world volume", g.nx, g.ny, g.nz));
}

WorldVolume resample_to_world(const StoneState& st, const TriangleMesh& mesh, int resolution,
                              const Quarry* quarry)
{
    const WorldGrid g = world_grid(mesh, resolution);
    const Imath::Box3d& box = g.box;
    const double h = g.h;
    const V3d size = box.max - box.min;
    const double longest = std::max({size.x, size.y, size.z});
    const SlabLattice& lat = *st.lattice;
    WorldVolume vol;
    vol.nx = g.nx;
    vol.ny = g.ny;
    vol.nz = g.nz;
    const V3d centre = 0.5 * (box.min + box.max);
    const V3d half(0.5 * vol.nx * h, 0.5 * vol.ny * h, 0.5 * vol.nz * h);
    vol.bounds = Imath::Box3d(centre - half, centre + half);
    const size_t n = size_t(vol.nx) * vol.ny * vol.nz;
    vol.density.assign(n, 0.0f);
    vol.crust.assign(n, 0.0f);
    vol.iron.assign(n, 0.0f);
    vol.salt.assign(n, 0.0f);
    vol.decay.assign(n, 0.0f);
    vol.moisture.assign(n, 0.0f);

    std::vector<float> density = st.density, crust, iron, salt;
    std::vector<float> decay = st.decay, moisture = st.moisture;
    lat.fill_halo(density.data());
    lat.fill_halo(decay.data());
    lat.fill_halo(moisture.data());
    output_fractions(st, crust, iron, salt);

    EmbreeScene scene;
    scene.add_mesh(mesh);
    scene.commit();
    tbb::parallel_for(0, vol.ny * vol.nz, [&](int row) {
        const int j = row % vol.ny, k = row / vol.ny;
        // Inside test for the row: crossings of a ray along +x (parity).
        const V3d start = vol.centre(0, j, k) - V3d(h, 0, 0);
        const Imath::V3f o(float(start.x), float(start.y), float(start.z));
        std::vector<float> crossings;
        float t = 0.0f;
        for (int guard = 0; guard < 4096; ++guard) {
            auto hit = scene.intersect(o, Imath::V3f(1, 0, 0), t);
            if (!hit)
                break;
            crossings.push_back(hit->t);
            t = hit->t + float(1e-6 * longest);
        }
        for (int i = 0; i < vol.nx; ++i) {
            const size_t v = vol.index(i, j, k);
            const V3d p = vol.centre(i, j, k);
            if (auto at = lat.locator().locate(p, 1e-6)) {
                vol.density[v] = std::clamp(lat.sample(density.data(), *at), 0.0f, 1.0f);
                vol.crust[v] = std::clamp(lat.sample(crust.data(), *at), 0.0f, 1.0f);
                vol.iron[v] = std::clamp(lat.sample(iron.data(), *at), 0.0f, 1.0f);
                vol.salt[v] = std::clamp(lat.sample(salt.data(), *at), 0.0f, 1.0f);
                vol.decay[v] = std::max(lat.sample(decay.data(), *at), 0.0f);
                vol.moisture[v] = std::clamp(lat.sample(moisture.data(), *at), 0.0f, 1.0f);
                continue;
            }
            const float x = float(p.x - start.x);
            const size_t before = size_t(std::count_if(crossings.begin(), crossings.end(),
                                                       [&](float c) { return c < x; }));
            vol.density[v] = before % 2 == 1 ? 1.0f : 0.0f;
            if (quarry && vol.density[v] > 0.0f) // fresh stone: its minerals, no crust
                vol.iron[v] = std::clamp(float(quarry->at(p).mineral[kIron] /
                                               st.params.mineral_iron_scale),
                                         0.0f, 1.0f);
        }
    });
    return vol;
}

void write_world_volume(const fs::path& path, const WorldVolume& v, const Metadata& metadata)
{
    // The layout is formats/stone_volume/stone_volume.h's.
    formats::StoneVolume out;
    out.grid.min = {v.bounds.min.x, v.bounds.min.y, v.bounds.min.z};
    out.grid.max = {v.bounds.max.x, v.bounds.max.y, v.bounds.max.z};
    out.grid.n = {v.nx, v.ny, v.nz};
    out.voxels.resize(out.grid.voxels() * formats::kVolumeChannels.size());
    for (size_t i = 0; i < v.density.size(); ++i) {
        // Row k * ny + j, column i: exactly the index i + nx (j + ny k).
        float* voxel = &out.voxels[i * formats::kVolumeChannels.size()];
        voxel[formats::kDensityChannel] = v.density[i];
        voxel[formats::kCrustChannel] = v.crust[i];
        voxel[formats::kIronChannel] = v.iron[i];
        voxel[formats::kSaltChannel] = v.salt[i];
    }
    // Part 2: the simulation's own fields, when there are any.
    if (!v.decay.empty() || !v.moisture.empty()) {
        out.decay = v.decay.empty() ? std::vector<float>(out.grid.voxels(), 0.0f) : v.decay;
        out.moisture = v.moisture.empty() ? std::vector<float>(out.grid.voxels(), 0.0f) : v.moisture;
    }
    write_parts_atomic(path, formats::stone_volume_parts(out), metadata, "world volume");
}

WorldVolume read_world_volume(const fs::path& path)
{
    const formats::StoneVolume in = formats::read_stone_volume(ImagePixelReader(), path, true);
    const formats::VolumeGrid& grid = in.grid;
    WorldVolume v;
    v.bounds = Imath::Box3d(V3d(grid.min[0], grid.min[1], grid.min[2]),
                            V3d(grid.max[0], grid.max[1], grid.max[2]));
    v.nx = grid.n[0];
    v.ny = grid.n[1];
    v.nz = grid.n[2];
    const size_t n = grid.voxels(), k = formats::kVolumeChannels.size();
    for (auto* field : {&v.crust, &v.density, &v.iron, &v.salt})
        field->resize(n);
    for (size_t i = 0; i < n; ++i) {
        v.crust[i] = in.voxels[i * k + formats::kCrustChannel];
        v.density[i] = in.voxels[i * k + formats::kDensityChannel];
        v.iron[i] = in.voxels[i * k + formats::kIronChannel];
        v.salt[i] = in.voxels[i * k + formats::kSaltChannel];
    }
    v.decay = in.decay;
    v.moisture = in.moisture;
    return v;
}

void write_slab_volume(const fs::path& path, const StoneState& st, const Metadata& metadata)
{
    const SlabLattice& lat = *st.lattice;
    const SlabGrid& g = lat.grid();
    std::vector<float> crust, iron, salt;
    output_fractions(st, crust, iron, salt);
    constexpr int kChannels = 7;
    formats::Pixels voxels;
    voxels.name = "voxels";
    voxels.width = g.n_t;
    voxels.height = g.n_t * g.n_d * g.slab_count;
    voxels.channels = kChannels;
    voxels.channel_names = {"density", "porosity", "moisture", "decay", "crust", "iron", "salt"};
    Metadata header = {{"patina:n_t", g.n_t}, {"patina:n_d", g.n_d}, {"patina:slabs", g.slab_count}};
    header.insert(header.end(), metadata.begin(), metadata.end());
    std::vector<float>& px = voxels.values;
    px.resize(size_t(g.n_t) * g.n_t * g.n_d * g.slab_count * kChannels);
    tbb::parallel_for(0, g.slab_count, [&](int s) {
        for (int k = 0; k < g.n_d; ++k)
            for (int j = 0; j < g.n_t; ++j)
                for (int i = 0; i < g.n_t; ++i) {
                    const size_t c = g.index(s, i, j, k);
                    const size_t row = (size_t(s) * g.n_d + k) * g.n_t + j;
                    float* o = &px[(row * g.n_t + i) * kChannels];
                    o[0] = st.density[c];
                    o[1] = st.porosity[c];
                    o[2] = st.moisture[c];
                    o[3] = st.decay[c];
                    o[4] = crust[c];
                    o[5] = iron[c];
                    o[6] = salt[c];
                }
    });
    formats::Pixels corners;
    corners.name = "corners";
    corners.width = 8;
    corners.height = g.slab_count;
    corners.channels = 3;
    corners.channel_names = {"x", "y", "z"};
    corners.values.resize(size_t(8) * g.slab_count * 3);
    for (int s = 0; s < g.slab_count; ++s)
        for (int c = 0; c < 8; ++c)
            for (int a = 0; a < 3; ++a)
                corners.values[(size_t(s) * 8 + c) * 3 + a] = float(lat.slabs()[size_t(s)][c][a]);
    write_parts_atomic(path, {voxels, corners}, header, "slab volume");
}

} // namespace patina::texgen::stone
