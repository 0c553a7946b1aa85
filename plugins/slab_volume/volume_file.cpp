#include "volume_file.h"

#include "slab_volume.h"

#include "formats/host_pixels.h"
#include "formats/stone_volume/stone_volume.h"

#include <stdexcept>
#include <vector>

namespace patina::slab_volume {

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
        // The format's one reader, through the host's read_image; no part may hold more
        // than four floats per voxel of the largest volume (checked before allocating).
        const formats::StoneVolume v = formats::read_stone_volume(
            formats::HostPixelReader(host, 4.0 * formats::kMaxVolumeVoxels), path, false);
        const formats::VolumeGrid& g = v.grid;
        *grid = volume::VoxelGrid(g.n[0], g.n[1], g.n[2],
                                  shading::Vec3(float(g.min[0]), float(g.min[1]), float(g.min[2])),
                                  shading::Vec3(float(g.max[0]), float(g.max[1]), float(g.max[2])));
        for (int k = 0; k < g.n[2]; ++k)
            for (int j = 0; j < g.n[1]; ++j)
                for (int i = 0; i < g.n[0]; ++i) {
                    const float* voxel = &v.voxels[g.offset(i, j, k)];
                    grid->density_at(i, j, k) = voxel[formats::kDensityChannel];
                    auto& q = grid->composition_at(i, j, k);
                    q[volume::kCrust] = voxel[formats::kCrustChannel];
                    q[volume::kIron] = voxel[formats::kIronChannel];
                    q[volume::kSalt] = voxel[formats::kSaltChannel];
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
