// The stone volume (docs/file-formats.md "Stone volume"): the world-grid voxels
// `patina-texgen stone` writes (texgen/stone_export/volume_export.cpp) and the slab_volume medium
// reads (plugins/slab_volume). A two-part OpenEXR:
//
//   part 0 "voxels"  width nx, height ny·nz (z slice k in rows k·ny .. k·ny + ny − 1, row j
//                    the y index j, from the min corner), float channels kVolumeChannels in
//                    OpenEXR's sorted order (the order every reader gets them in): the black
//                    crust fraction, the stone volume fraction after erosion (density), the
//                    iron oxide and the salt fractions, all in [0, 1]
//   part 1 "bounds"  width 3, height 4, one channel "value": row 0 the min corner xyz (m),
//                    row 1 the max corner, row 2 (nx, ny, nz), row 3 (format, 0, 0). A file
//                    of 3 rows is format 1 (written before the row existed).
//   part 2 "fields"  optional (files written before it have none; the medium does not read
//                    it): part 0's layout, float channels kFieldChannels, the simulation's
//                    decay index and moisture (saturation, 0 dry, 1 saturated) sampled like
//                    the voxels, 0 outside the weathered shell.
//
// Voxel (i, j, k) has its centre at min + (i + 1/2, j + 1/2, k + 1/2) (max − min) / n. The
// parts are read through a PixelReader (OIIO in texgen, the host's read_image in the
// plugin): this holds the layout, its reader and its checks, not the file access.
#pragma once

#include "formats/pixels.h"

#include <array>
#include <cstddef>
#include <filesystem>
#include <string>
#include <utility>
#include <vector>

namespace patina::formats {

/// The layout this build writes and reads; a newer file is refused.
inline constexpr int kVolumeFormatVersion = 1;
inline constexpr int kVoxelPart = 0, kBoundsPart = 1, kFieldsPart = 2;
inline constexpr std::array<const char*, 2> kFieldChannels = {"decay", "moisture"};
inline constexpr std::array<const char*, 4> kVolumeChannels = {"crust", "density", "iron",
                                                               "salt"};
inline constexpr int kCrustChannel = 0, kDensityChannel = 1, kIronChannel = 2, kSaltChannel = 3;
/// The most voxels a volume may hold (nx·ny·nz): what a renderer loads, 2.5 GiB of floats.
inline constexpr double kMaxVolumeVoxels = 512.0 * 512.0 * 512.0;

/// The folder of the snapshot at `cycle` of a stone series that ends at `last`
/// ("cycle_0050"): `patina-texgen stone --steps` writes one per snapshot.
std::string stone_snapshot_folder(int cycle, int last);

/// Where the voxels sit: the part "bounds".
struct VolumeGrid {
    std::array<double, 3> min{}, max{};
    std::array<int, 3> n{};
    int format = kVolumeFormatVersion;

    size_t voxels() const { return size_t(n[0]) * size_t(n[1]) * size_t(n[2]); }
    /// The first of voxel (i, j, k)'s channels in part 0's interleaved pixels.
    size_t offset(int i, int j, int k) const
    {
        return ((size_t(k) * size_t(n[1]) + size_t(j)) * size_t(n[0]) + size_t(i)) *
               kVolumeChannels.size();
    }
};

/// Part 1's pixels (3 wide, 4 high, one channel) for `grid`.
std::vector<float> volume_bounds_pixels(const VolumeGrid& grid);

/// The grid that part 1 (`width` x `height` pixels of `channels`, `pixels`) describes.
/// Throws std::runtime_error naming `file` for another size, a newer format, bounds whose
/// min is not below max, voxel counts that are not positive integers, or more than
/// kMaxVolumeVoxels voxels.
VolumeGrid read_volume_bounds(const std::string& file, int width, int height, int channels,
                              const float* pixels);

/// Throws naming `file` when part 0's size is not the one `grid` implies.
void check_voxel_part(const std::string& file, const VolumeGrid& grid, int width, int height,
                      int channels);

/// Throws naming `file`, the voxel and the channel for a value outside [0, 1] (or NaN).
void check_voxel_values(const std::string& file, const VolumeGrid& grid, const float* pixels);

/// A whole stone volume.
struct StoneVolume {
    VolumeGrid grid;
    /// Part 0: per voxel (VolumeGrid::offset), the kVolumeChannels, interleaved.
    std::vector<float> voxels;
    /// Part 2, per voxel: the decay index and moisture; empty when the file has none (or
    /// they were not asked for).
    std::vector<float> decay, moisture;
};

/// The parts of `volume`'s file (part 2 only when it has fields), named "voxels",
/// "bounds", "fields".
std::vector<Pixels> stone_volume_parts(const StoneVolume& volume);

/// The volume in `file`, read through `reader`: its bounds first (they say the voxel part's
/// size), the voxels (channels found by name when the reader gives names, else in
/// kVolumeChannels' order), and with `fields` part 2 when the reader sees one. Throws
/// "stone volume 'file': what" for any part of another size, a missing channel, a value
/// outside [0, 1] or a field that is not finite.
StoneVolume read_stone_volume(const PixelReader& reader, const std::filesystem::path& file,
                              bool fields);

}  // namespace patina::formats
