#include "volume_file.h"

#include "slab_volume.h"

#include "formats/stone_volume.h"

#include <stdexcept>
#include <vector>

namespace patina::slab_volume {

namespace {

    /// Reads one part completely; false after the host (or we) reported why.
    bool read_part(const PatinaHost* host, const char* shader, const char* path, int part,
                   int dims[3], std::vector<float>* pixels)
    {
        if (!host->read_image(host, path, part, dims, nullptr, 0))
            return false;
        const double count = static_cast<double>(dims[0]) * dims[1] * dims[2];
        // A guard against absurd headers before the allocation (the format's checks follow).
        if (!(dims[0] > 0 && dims[1] > 0 && dims[2] > 0) ||
            count > 4.0 * formats::kMaxVolumeVoxels) {
            report_error(host, shader, "stone volume '%s': part %d has %d x %d pixels of %d channels",
                         path, part, dims[0], dims[1], dims[2]);
            return false;
        }
        try {
            pixels->assign(static_cast<size_t>(count), 0.0f);
        } catch (const std::bad_alloc&) {
            report_error(host, shader, "stone volume '%s': out of memory", path);
            return false;
        }
        return host->read_image(host, path, part, dims, pixels->data(), pixels->size()) != 0;
    }

} // namespace

bool read_volume_file(const PatinaHost* host, const char* shader, const char* path,
                      volume::VoxelGrid* grid)
{
    if (!PATINA_HOST_HAS_READ_IMAGE(host) || !host->read_image) {
        report_error(host, shader, "this host cannot read data files (needs ABI 1.1 read_image)");
        return false;
    }
    if (!path || !*path) {
        report_error(host, shader, "no slab volume file given (parameter 'file')");
        return false;
    }
    try {
        // The bounds first: they say how large the voxel part must be.
        int bdims[3] = {0, 0, 0};
        std::vector<float> bounds;
        if (!read_part(host, shader, path, formats::kBoundsPart, bdims, &bounds))
            return false;
        const formats::VolumeGrid g =
            formats::read_volume_bounds(path, bdims[0], bdims[1], bdims[2], bounds.data());

        int vdims[3] = {0, 0, 0};
        if (!host->read_image(host, path, formats::kVoxelPart, vdims, nullptr, 0))
            return false;
        formats::check_voxel_part(path, g, vdims[0], vdims[1], vdims[2]);
        std::vector<float> voxels;
        if (!read_part(host, shader, path, formats::kVoxelPart, vdims, &voxels))
            return false;
        formats::check_voxel_values(path, g, voxels.data());

        *grid = volume::VoxelGrid(g.n[0], g.n[1], g.n[2],
                                  shading::Vec3(float(g.min[0]), float(g.min[1]), float(g.min[2])),
                                  shading::Vec3(float(g.max[0]), float(g.max[1]), float(g.max[2])));
        for (int k = 0; k < g.n[2]; ++k)
            for (int j = 0; j < g.n[1]; ++j)
                for (int i = 0; i < g.n[0]; ++i) {
                    const float* v = &voxels[g.offset(i, j, k)];
                    grid->density_at(i, j, k) = v[formats::kDensityChannel];
                    auto& q = grid->composition_at(i, j, k);
                    q[volume::kCrust] = v[formats::kCrustChannel];
                    q[volume::kIron] = v[formats::kIronChannel];
                    q[volume::kSalt] = v[formats::kSaltChannel];
                }
        return true;
    } catch (const std::bad_alloc&) {
        report_error(host, shader, "stone volume '%s': out of memory", path);
    } catch (const std::exception& e) {
        report_error(host, shader, "%s", e.what());
    }
    return false;
}

} // namespace patina::slab_volume
