// Reading a world-grid stone volume (the file `patina-texgen stone` writes) into a
// VoxelGrid, through the host's read_image service (abi.h 1.1).
//
// Its layout and checks are formats/stone_volume/stone_volume.h (docs/file-formats.md "Stone volume").
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
