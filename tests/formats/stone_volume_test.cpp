// The stone volume's layout (formats/stone_volume/stone_volume.h): the bounds part round trip, the
// format row, and the refusals every reader makes.
#include "formats/stone_volume/stone_volume.h"

#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <stdexcept>
#include <string>
#include <vector>

namespace patina::formats {
namespace {

VolumeGrid example()
{
    VolumeGrid g;
    g.min = {-0.5, 0.0, -0.25};
    g.max = {0.5, 2.0, 0.25};
    g.n = {16, 64, 8};
    return g;
}

TEST(StoneVolumeFormat, BoundsRoundTrip)
{
    const VolumeGrid g = example();
    const std::vector<float> px = volume_bounds_pixels(g);
    ASSERT_EQ(px.size(), 12u);  // 3 x 4, one channel
    const VolumeGrid r = read_volume_bounds("v.exr", 3, 4, 1, px.data());
    EXPECT_EQ(r.min, g.min);
    EXPECT_EQ(r.max, g.max);
    EXPECT_EQ(r.n, g.n);
    EXPECT_EQ(r.format, kVolumeFormatVersion);
    EXPECT_EQ(r.voxels(), 16u * 64u * 8u);
    // Voxel (i, j, k) sits in row k·ny + j, column i, channels interleaved.
    EXPECT_EQ(r.offset(3, 2, 1), ((1u * 64u + 2u) * 16u + 3u) * 4u);
    // A file written before the format row (3 rows) reads as format 1.
    EXPECT_EQ(read_volume_bounds("v.exr", 3, 3, 1, px.data()).format, 1);
}

TEST(StoneVolumeFormat, RefusesNewerFormatsAndBadGrids)
{
    std::vector<float> px = volume_bounds_pixels(example());
    px[9] = 2.0f;
    std::string m = test::message_of([&] { read_volume_bounds("v.exr", 3, 4, 1, px.data()); });
    EXPECT_NE(m.find("stone volume 'v.exr': format 2 is newer than the 1"), std::string::npos)
        << m;
    px = volume_bounds_pixels(example());
    px[4] = -1.0f;  // max y below min y
    m = test::message_of([&] { read_volume_bounds("v.exr", 3, 4, 1, px.data()); });
    EXPECT_NE(m.find("bounds min 0 must be below max -1 on axis y"), std::string::npos) << m;
    px = volume_bounds_pixels(example());
    px[7] = 2.5f;
    m = test::message_of([&] { read_volume_bounds("v.exr", 3, 4, 1, px.data()); });
    EXPECT_NE(m.find("voxel count 2.5 on axis y is not a positive integer"), std::string::npos)
        << m;
    px = volume_bounds_pixels(example());
    px[6] = px[7] = px[8] = 1024.0f;
    m = test::message_of([&] { read_volume_bounds("v.exr", 3, 4, 1, px.data()); });
    EXPECT_NE(m.find("more than the 512^3"), std::string::npos) << m;
    m = test::message_of([&] { read_volume_bounds("v.exr", 3, 2, 1, px.data()); });
    EXPECT_NE(m.find("must be 3 x 4 pixels of 1 channel"), std::string::npos) << m;

    const VolumeGrid g = example();
    m = test::message_of([&] { check_voxel_part("v.exr", g, 16, 64, 4); });
    EXPECT_NE(m.find("so it must be 16 x 512 of 4"), std::string::npos) << m;
    std::vector<float> voxels(g.voxels() * 4, 0.5f);
    EXPECT_NO_THROW(check_voxel_values("v.exr", g, voxels.data()));
    voxels[g.offset(1, 2, 3) + kIronChannel] = 1.5f;
    m = test::message_of([&] { check_voxel_values("v.exr", g, voxels.data()); });
    EXPECT_NE(m.find("voxel (1, 2, 3) has iron = 1.5, outside [0, 1]"), std::string::npos) << m;
}

/// The parts of one file, served from memory by index, with or without channel names.
class MemoryParts final : public PixelReader {
public:
    MemoryParts(std::vector<Pixels> parts, bool names) : parts_(std::move(parts))
    {
        if (!names)
            for (Pixels& p : parts_)
                p.channel_names.clear();
    }
    Pixels read(const std::filesystem::path& file, int subimage) const override
    {
        if (subimage < 0 || subimage >= static_cast<int>(parts_.size()))
            throw std::runtime_error(file.string() + ": no part " + std::to_string(subimage));
        return parts_[static_cast<size_t>(subimage)];
    }
    int subimage_count(const std::filesystem::path&) const override
    {
        return static_cast<int>(parts_.size());
    }

private:
    std::vector<Pixels> parts_;
};

StoneVolume small_volume(bool fields)
{
    StoneVolume v;
    v.grid.min = {0.0, 0.0, 0.0};
    v.grid.max = {1.0, 2.0, 3.0};
    v.grid.n = {2, 3, 4};
    for (size_t i = 0; i < v.grid.voxels(); ++i) {
        // crust, density, iron, salt of voxel i
        v.voxels.insert(v.voxels.end(), {0.01f * i, 1.0f - 0.02f * i, 0.5f, 0.25f});
        if (fields) {
            v.decay.push_back(0.1f * i);
            v.moisture.push_back(0.03f * i);
        }
    }
    return v;
}

TEST(StoneVolumeFormat, TheWholeVolumeRoundTripsByNameAndInTheDocumentedOrder)
{
    for (const bool fields : {false, true})
        for (const bool names : {true, false}) {
            const StoneVolume v = small_volume(fields);
            const std::vector<Pixels> parts = stone_volume_parts(v);
            ASSERT_EQ(parts.size(), fields ? 3u : 2u);
            EXPECT_EQ(parts[kVoxelPart].name, "voxels");
            EXPECT_EQ(parts[kBoundsPart].name, "bounds");
            const StoneVolume back = read_stone_volume(MemoryParts(parts, names), "v.exr", true);
            EXPECT_EQ(back.grid.n, v.grid.n);
            EXPECT_EQ(back.grid.max, v.grid.max);
            EXPECT_EQ(back.voxels, v.voxels);
            EXPECT_EQ(back.decay, v.decay);
            EXPECT_EQ(back.moisture, v.moisture);
        }
    // Channels stored in another order are found by name.
    std::vector<Pixels> parts = stone_volume_parts(small_volume(false));
    Pixels& voxels = parts[kVoxelPart];
    voxels.channel_names = {"salt", "iron", "density", "crust"};
    for (size_t i = 0; i < small_volume(false).grid.voxels(); ++i)
        std::reverse(voxels.values.begin() + 4 * i, voxels.values.begin() + 4 * i + 4);
    EXPECT_EQ(read_stone_volume(MemoryParts(parts, true), "v.exr", false).voxels,
              small_volume(false).voxels);
    // A value outside [0, 1] is named with its voxel and channel.
    parts = stone_volume_parts(small_volume(false));
    parts[kVoxelPart].values[4 * 5 + 1] = 1.5f;  // voxel 5 = (1, 2, 0): density
    const std::string m =
        test::message_of([&] { read_stone_volume(MemoryParts(parts, true), "v.exr", false); });
    EXPECT_NE(m.find("voxel (1, 2, 0) has density = 1.5"), std::string::npos) << m;
}

}  // namespace
}  // namespace patina::formats
