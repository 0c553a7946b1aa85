#include "formats/stone_volume/stone_volume.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace patina::formats {

std::string stone_snapshot_folder(int cycle, int last)
{
    const int digits = std::max(4, static_cast<int>(std::to_string(last).size()));
    char name[64];
    std::snprintf(name, sizeof name, "cycle_%0*d", digits, cycle);
    return name;
}

namespace {

    [[noreturn]] void fail(const std::string& file, const std::string& what)
    {
        throw std::runtime_error("stone volume '" + file + "': " + what);
    }

    /// A voxel count as stored (a float), or 0 when it is not a positive integer.
    int count_of(float v)
    {
        return (v >= 1.0f && v <= 65536.0f && v == std::floor(v)) ? static_cast<int>(v) : 0;
    }

    std::string number(double v)
    {
        char text[32];
        std::snprintf(text, sizeof text, "%g", v);
        return text;
    }

}  // namespace

std::vector<float> volume_bounds_pixels(const VolumeGrid& g)
{
    return {float(g.min[0]), float(g.min[1]), float(g.min[2]),
            float(g.max[0]), float(g.max[1]), float(g.max[2]),
            float(g.n[0]),   float(g.n[1]),   float(g.n[2]),
            float(g.format), 0.0f,            0.0f};
}

VolumeGrid read_volume_bounds(const std::string& file, int width, int height, int channels,
                              const float* b)
{
    if (width != 3 || (height != 3 && height != 4) || channels != 1)
        fail(file, "the bounds part (1) must be 3 x 4 pixels of 1 channel, not " +
                       std::to_string(width) + " x " + std::to_string(height) + " of " +
                       std::to_string(channels));
    VolumeGrid g;
    g.format = height == 3 ? 1 : count_of(b[9]);
    if (g.format == 0)
        fail(file, "format " + number(b[9]) + " is not a positive integer");
    if (g.format > kVolumeFormatVersion)
        fail(file, "format " + std::to_string(g.format) + " is newer than the " +
                       std::to_string(kVolumeFormatVersion) +
                       " this Patina reads (the volume was written by a newer Patina)");
    for (int a = 0; a < 3; ++a) {
        g.min[a] = b[a];
        g.max[a] = b[3 + a];
        g.n[a] = count_of(b[6 + a]);
        if (!(std::isfinite(g.min[a]) && std::isfinite(g.max[a]) && g.min[a] < g.max[a]))
            fail(file, "bounds min " + number(g.min[a]) + " must be below max " +
                           number(g.max[a]) + " on axis " + "xyz"[a]);
        if (g.n[a] == 0)
            fail(file, "voxel count " + number(b[6 + a]) + " on axis " + "xyz"[a] +
                           " is not a positive integer");
    }
    if (static_cast<double>(g.n[0]) * g.n[1] * g.n[2] > kMaxVolumeVoxels)
        fail(file, std::to_string(g.n[0]) + " x " + std::to_string(g.n[1]) + " x " +
                       std::to_string(g.n[2]) + " voxels is more than the 512^3 a volume may hold");
    return g;
}

void check_voxel_part(const std::string& file, const VolumeGrid& g, int width, int height,
                      int channels)
{
    if (width != g.n[0] || height != g.n[1] * g.n[2] ||
        channels != static_cast<int>(kVolumeChannels.size()))
        fail(file, "the voxel part (0) is " + std::to_string(width) + " x " +
                       std::to_string(height) + " pixels of " + std::to_string(channels) +
                       " channels; the bounds say " + std::to_string(g.n[0]) + " x " +
                       std::to_string(g.n[1]) + " x " + std::to_string(g.n[2]) +
                       " voxels, so it must be " + std::to_string(g.n[0]) + " x " +
                       std::to_string(g.n[1] * g.n[2]) + " of 4 (crust, density, iron, salt)");
}

void check_voxel_values(const std::string& file, const VolumeGrid& g, const float* pixels)
{
    for (int k = 0; k < g.n[2]; ++k)
        for (int j = 0; j < g.n[1]; ++j)
            for (int i = 0; i < g.n[0]; ++i) {
                const float* v = pixels + g.offset(i, j, k);
                for (size_t c = 0; c < kVolumeChannels.size(); ++c)
                    if (!(v[c] >= 0.0f && v[c] <= 1.0f))
                        fail(file, "voxel (" + std::to_string(i) + ", " + std::to_string(j) +
                                       ", " + std::to_string(k) + ") has " + kVolumeChannels[c] +
                                       " = " + number(v[c]) + ", outside [0, 1]");
            }
}

std::vector<Pixels> stone_volume_parts(const StoneVolume& v)
{
    const VolumeGrid& g = v.grid;
    const int width = g.n[0], height = g.n[1] * g.n[2];
    std::vector<Pixels> parts(v.decay.empty() ? 2 : 3);
    Pixels& voxels = parts[kVoxelPart];
    voxels.name = "voxels";
    voxels.width = width;
    voxels.height = height;
    voxels.channels = static_cast<int>(kVolumeChannels.size());
    voxels.channel_names.assign(kVolumeChannels.begin(), kVolumeChannels.end());
    voxels.values = v.voxels;
    Pixels& bounds = parts[kBoundsPart];
    bounds.name = "bounds";
    bounds.width = 3;
    bounds.height = 4;
    bounds.channels = 1;
    bounds.channel_names = {"value"};
    bounds.values = volume_bounds_pixels(g);
    if (!v.decay.empty()) {
        Pixels& fields = parts[kFieldsPart];
        fields.name = "fields";
        fields.width = width;
        fields.height = height;
        fields.channels = static_cast<int>(kFieldChannels.size());
        fields.channel_names.assign(kFieldChannels.begin(), kFieldChannels.end());
        fields.values.resize(2 * g.voxels());
        for (size_t i = 0; i < g.voxels(); ++i) {
            fields.values[2 * i] = v.decay[i];
            fields.values[2 * i + 1] = v.moisture[i];
        }
    }
    return parts;
}

StoneVolume read_stone_volume(const PixelReader& reader, const std::filesystem::path& file,
                              bool fields)
{
    const std::string name = file.string();
    StoneVolume v;
    const Pixels bounds = reader.read(file, kBoundsPart);
    if (bounds.values.size() > 64)
        fail(name, "part 'bounds' is too large");
    v.grid = read_volume_bounds(name, bounds.width, bounds.height, bounds.channels,
                                bounds.values.data());
    const Pixels voxels = reader.read(file, kVoxelPart);
    check_voxel_part(name, v.grid, voxels.width, voxels.height, voxels.channels);
    // Channels by name when the reader knows them (in the stored order, interleaved).
    std::array<int, kVolumeChannels.size()> at{};
    for (size_t c = 0; c < kVolumeChannels.size(); ++c)
        at[c] = channel_index(voxels, kVolumeChannels[c], kVolumeChannels, file);
    const size_t n = v.grid.voxels(), k = kVolumeChannels.size();
    v.voxels.resize(n * k);
    for (size_t i = 0; i < n; ++i)
        for (size_t c = 0; c < k; ++c)
            v.voxels[i * k + c] = voxels.values[i * voxels.channels + at[c]];
    check_voxel_values(name, v.grid, v.voxels.data());
    if (fields && reader.subimage_count(file) > kFieldsPart) {
        const Pixels f = reader.read(file, kFieldsPart);
        if (f.width != voxels.width || f.height != voxels.height)
            fail(name, "part 'fields' must be " + std::to_string(voxels.width) + "x" +
                           std::to_string(voxels.height) + " pixels of channels decay, moisture");
        const int decay = channel_index(f, kFieldChannels[0], kFieldChannels, file);
        const int moisture = channel_index(f, kFieldChannels[1], kFieldChannels, file);
        v.decay.resize(n);
        v.moisture.resize(n);
        for (size_t i = 0; i < n; ++i) {
            v.decay[i] = f.values[i * f.channels + decay];
            v.moisture[i] = f.values[i * f.channels + moisture];
            if (!std::isfinite(v.decay[i]) || !std::isfinite(v.moisture[i]))
                fail(name, "part 'fields': voxel " + std::to_string(i) + " is not finite");
        }
    }
    return v;
}

}  // namespace patina::formats
