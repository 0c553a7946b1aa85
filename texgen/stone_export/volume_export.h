// The simulation's output volumes.
//
// World-grid volume (the contract with the slab_volume medium plugin): a two-part OpenEXR.
//   part 0 "voxels": width nx, height ny * nz (z slice k occupies rows k*ny .. k*ny + ny - 1,
//     row j = y index j, from the min corner), float channels "density" (stone volume
//     fraction after erosion), "crust" (black crust fraction), "iron" (iron oxide, yellowing)
//     and "salt" (efflorescence), all in [0, 1];
//   part 1 "bounds": width 3, height 3, channel "value": row 0 the min corner xyz (m), row 1
//     the max corner, row 2 nx, ny, nz; its display window is part 0's;
//   part 2 "fields": part 0's layout, channels "decay" and "moisture" (formats/stone_volume/stone_volume.h).
//   Voxel (i, j, k) has its centre at min + (i + 1/2, j + 1/2, k + 1/2) (max - min) / n.
// Slab volume (the simulation's own lattice, for inspection or a slab-aware renderer): a
// two-part OpenEXR.
//   part 0 "voxels": width n_t, height n_t * n_d * slabs; row (s n_d + k) n_t + j holds voxel
//     (i, j, k) of slab s in column i; float channels density, porosity, moisture, decay,
//     crust, iron, salt (the last three as in the world grid);
//   part 1 "corners": width 8, height slabs, channels x, y, z: the corners of slab s in row
//     s, corner iu + 2 iv + 4 iw (iw = 0 the outer face); header patina:n_t, patina:n_d.
// Both are written under a temporary name and renamed when complete.
#pragma once

#include "core/image_io.h"
#include "core/mesh.h"
#include "texgen/stone/stone_state.h"

#include <Imath/ImathBox.h>

#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen::stone {

/// A world-aligned voxel grid of the four output channels.
struct WorldVolume {
    Imath::Box3d bounds;
    int nx = 0, ny = 0, nz = 0;
    /// Per voxel (i + nx (j + ny k)): density, crust, iron, salt.
    std::vector<float> density, crust, iron, salt;
    /// Per voxel, the simulation's decay index and moisture (0 outside the slabs); empty
    /// for a volume read from a file without them (formats/stone_volume/stone_volume.h part 2).
    std::vector<float> decay, moisture;

    size_t index(int i, int j, int k) const { return size_t(i) + size_t(nx) * (size_t(j) + size_t(ny) * k); }
    Imath::V3d centre(int i, int j, int k) const;
};

/// Crust, iron and salt fractions per cell ([0, 1], the output scales of the parameters);
/// iron counts the iron crust and the solid iron-bearing minerals (mineral_iron_scale).
void output_fractions(const StoneState& st, std::vector<float>& crust, std::vector<float>& iron,
                      std::vector<float>& salt);

/// Resample the state onto a world grid of `resolution` voxels along the longest side of
/// `mesh`'s bounds (padded by a voxel): inside a slab the trilinear sample of its voxels,
/// elsewhere 1 inside the mesh (fresh stone below the shell) and 0 outside. With `quarry`
/// (the one the state was made from), the fresh stone below the shell carries the quarry's
/// iron minerals too, so veins and bedding planes run on through the whole volume.
WorldVolume resample_to_world(const StoneState& st, const TriangleMesh& mesh, int resolution,
                              const Quarry* quarry = nullptr);

/// Throws, naming `option`, when the world volume resample_to_world makes for `mesh` at
/// `resolution`, and its file's pixels, would not fit in this machine's memory.
void check_world_volume_memory(const TriangleMesh& mesh, int resolution, const char* option);

void write_world_volume(const std::filesystem::path& path, const WorldVolume& volume,
                        const Metadata& metadata = {});
/// Throws std::runtime_error naming the file for a missing part, channel or bad bounds.
WorldVolume read_world_volume(const std::filesystem::path& path);

void write_slab_volume(const std::filesystem::path& path, const StoneState& st,
                       const Metadata& metadata = {});

} // namespace patina::texgen::stone
