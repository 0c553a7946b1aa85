// The stone volume's layout (formats/stone_volume/stone_volume.h): the bounds part round trip, the
// format row, and the refusals every reader makes.
#include "formats/stone_volume/stone_volume.h"

#include "test_util.h"

#include <gtest/gtest.h>

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

}  // namespace
}  // namespace patina::formats
