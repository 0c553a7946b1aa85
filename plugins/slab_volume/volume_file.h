// Reading a world-grid stone volume (the file `patina-texgen stone` writes) into a
// VoxelGrid, through the host's read_image service (abi.h 1.1).
//
// The file is a two-part OpenEXR:
//   part 0 "voxels": width nx, height ny·nz (z slice k in rows k·ny .. k·ny + ny − 1, row j
//                    the y index j, from the min corner), four float channels: density
//                    (stone volume fraction), crust, iron, salt (fractions in [0, 1]).
//                    OpenEXR keeps channels sorted by name, so they read back as
//                    crust, density, iron, salt whatever order they were written in.
//   part 1 "bounds": 3 × 3, one channel: row 0 the min corner xyz (metres), row 1 the max
//                    corner, row 2 (nx, ny, nz).
#pragma once

#include <patina/abi.h>
#include <patina/volume/voxel_grid.h>

namespace patina::slab_volume {

/// Reads `path` into *grid. On any problem (missing file or part, wrong dimensions or
/// channel count, bad bounds, values that are not finite or outside [0, 1]) reports an
/// error naming the file through host->error on behalf of `shader` and returns false.
bool read_volume_file(const PatinaHost* host, const char* shader, const char* path,
                      volume::VoxelGrid* grid);

} // namespace patina::slab_volume
