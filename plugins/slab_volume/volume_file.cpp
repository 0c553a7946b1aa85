#include "volume_file.h"

#include "slab_volume.h"

#include <cmath>
#include <vector>

namespace patina::slab_volume {

namespace {

    /// Channel order of part 0 as read: OpenEXR sorts channel names.
    constexpr int kCrustChannel = 0, kDensityChannel = 1, kIronChannel = 2, kSaltChannel = 3;
    constexpr int kVoxelChannels = 4;
    /// A guard against absurd headers: 2^31 floats would not fit a render host anyway.
    constexpr double kMaxVoxels = 512.0 * 512.0 * 512.0;

    /// Reads one part completely; false after the host (or we) reported why.
    bool read_part(const PatinaHost* host, const char* shader, const char* path, int part,
                   int dims[3], std::vector<float>* pixels)
    {
        if (!host->read_image(host, path, part, dims, nullptr, 0))
            return false;
        const double count = static_cast<double>(dims[0]) * dims[1] * dims[2];
        if (!(dims[0] > 0 && dims[1] > 0 && dims[2] > 0) || count > 4.0 * kMaxVoxels) {
            report_error(host, shader, "slab volume '%s': part %d has %d x %d pixels of %d channels",
                         path, part, dims[0], dims[1], dims[2]);
            return false;
        }
        try {
            pixels->assign(static_cast<size_t>(count), 0.0f);
        } catch (const std::bad_alloc&) {
            report_error(host, shader, "slab volume '%s': out of memory", path);
            return false;
        }
        return host->read_image(host, path, part, dims, pixels->data(), pixels->size()) != 0;
    }

    /// A value of the bounds part as a positive integer voxel count, or 0.
    int voxel_count(float v)
    {
        return (v >= 1.0f && v <= 65536.0f && v == std::floor(v)) ? static_cast<int>(v) : 0;
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

    // Part 1, the bounds: min corner, max corner, voxel counts
    int bdims[3] = {0, 0, 0};
    std::vector<float> bounds;
    if (!read_part(host, shader, path, 1, bdims, &bounds))
        return false;
    if (bdims[0] != 3 || bdims[1] != 3 || bdims[2] != 1) {
        report_error(host, shader,
                     "slab volume '%s': the bounds part (1) must be 3 x 3 pixels of 1 channel, "
                     "not %d x %d of %d",
                     path, bdims[0], bdims[1], bdims[2]);
        return false;
    }
    const shading::Vec3 lo(bounds[0], bounds[1], bounds[2]);
    const shading::Vec3 hi(bounds[3], bounds[4], bounds[5]);
    const int n[3] = {voxel_count(bounds[6]), voxel_count(bounds[7]), voxel_count(bounds[8])};
    for (int a = 0; a < 3; ++a) {
        if (!(std::isfinite(lo[a]) && std::isfinite(hi[a]) && lo[a] < hi[a])) {
            report_error(host, shader,
                         "slab volume '%s': bounds min %g must be below max %g on axis %c", path,
                         lo[a], hi[a], "xyz"[a]);
            return false;
        }
        if (n[a] == 0) {
            report_error(host, shader,
                         "slab volume '%s': voxel count %g on axis %c is not a positive integer",
                         path, bounds[6 + a], "xyz"[a]);
            return false;
        }
    }
    if (static_cast<double>(n[0]) * n[1] * n[2] > kMaxVoxels) {
        report_error(host, shader, "slab volume '%s': %d x %d x %d voxels is too many", path, n[0],
                     n[1], n[2]);
        return false;
    }

    // Part 0, the voxels: nx wide, ny·nz high, four channels
    int vdims[3] = {0, 0, 0};
    std::vector<float> voxels;
    if (!host->read_image(host, path, 0, vdims, nullptr, 0))
        return false;
    if (vdims[0] != n[0] || vdims[1] != n[1] * n[2] || vdims[2] != kVoxelChannels) {
        report_error(host, shader,
                     "slab volume '%s': the voxel part (0) is %d x %d pixels of %d channels; the "
                     "bounds say %d x %d x %d voxels, so it must be %d x %d of 4 "
                     "(density, crust, iron, salt)",
                     path, vdims[0], vdims[1], vdims[2], n[0], n[1], n[2], n[0], n[1] * n[2]);
        return false;
    }
    if (!read_part(host, shader, path, 0, vdims, &voxels))
        return false;

    try {
        *grid = volume::VoxelGrid(n[0], n[1], n[2], lo, hi);
    } catch (const std::bad_alloc&) {
        report_error(host, shader, "slab volume '%s': out of memory", path);
        return false;
    }
    for (int k = 0; k < n[2]; ++k)
        for (int j = 0; j < n[1]; ++j)
            for (int i = 0; i < n[0]; ++i) {
                // Row k·ny + j of the image holds slice k, row j
                const float* v =
                    &voxels[((static_cast<size_t>(k) * n[1] + j) * n[0] + i) * kVoxelChannels];
                for (int c = 0; c < kVoxelChannels; ++c)
                    if (!(v[c] >= 0.0f && v[c] <= 1.0f)) {
                        static const char* const kNames[] = {"crust", "density", "iron", "salt"};
                        report_error(host, shader,
                                     "slab volume '%s': voxel (%d, %d, %d) has %s = %g, outside "
                                     "[0, 1]",
                                     path, i, j, k, kNames[c], v[c]);
                        return false;
                    }
                grid->density_at(i, j, k) = v[kDensityChannel];
                auto& q = grid->composition_at(i, j, k);
                q[volume::kCrust] = v[kCrustChannel];
                q[volume::kIron] = v[kIronChannel];
                q[volume::kSalt] = v[kSaltChannel];
            }
    return true;
}

} // namespace patina::slab_volume
