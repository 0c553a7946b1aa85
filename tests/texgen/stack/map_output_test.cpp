#include "texgen/stack/map_output.h"

#include "stack_test_util.h"
#include "test_util.h"
#include "texgen/texgen_meshes.h"

#include "core/cancel.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace patina::texgen {
namespace {

    namespace fs = std::filesystem;
    using test::MipLevel;
    using test::read_mip_level;
    using test::rect_grid;
    using test::scratch_dir;
    using test::TexelRect;

    MapDescription thickness_map()
    {
        MapDescription map;
        map.name = "patina";
        map.channels = {"thickness", "exposure"};
        map.units = "m";
        map.description = "layer thickness and the exposure that grew it";
        map.baker = "test";
        map.parameters = {{"samples", 64}, {"max_distance", 2.5f}, {"sky", std::string("clear")}};
        return map;
    }

    /// Values of every group: channel c of group g is g + c / 4 (distinct per texel).
    std::vector<float> ramp_values(const TexelGrid& grid, size_t channels, float offset = 0.0f)
    {
        std::vector<float> v(grid.groups.group_count() * channels);
        for (size_t g = 0; g < grid.groups.group_count(); ++g)
            for (size_t c = 0; c < channels; ++c)
                v[g * channels + c] =
                    offset + static_cast<float>(g) + 0.25f * static_cast<float>(c);
        return v;
    }

    std::string attribute(const OIIO::ImageSpec& spec, const char* name)
    {
        return spec.get_string_attribute(name, "(missing)");
    }

    TEST(WriteTexelMap, HeaderAttributesChannelsAndCoveredValuesRoundTrip)
    {
        const fs::path dir = scratch_dir("header");
        const TexelGrid grid = rect_grid(64, 32, {{3, 4, 20, 30}, {40, 0, 64, 9}});
        const MapDescription map = thickness_map();
        const std::vector<float> values = ramp_values(grid, 2);
        MapOutputOptions options;
        options.padding = 3;
        options.tile_size = 16;
        const std::vector<fs::path> files = write_texel_map(dir, map, {grid}, {values}, options);
        ASSERT_EQ(files.size(), 1u);
        EXPECT_EQ(files[0], dir / "patina.exr");

        auto in = OIIO::ImageInput::open(files[0].string());
        ASSERT_TRUE(in) << OIIO::geterror();
        const OIIO::ImageSpec& spec = in->spec();
        EXPECT_EQ(spec.width, 64);
        EXPECT_EQ(spec.height, 32);
        EXPECT_EQ(spec.tile_width, 16);
        EXPECT_EQ(spec.format, OIIO::TypeDesc::FLOAT);
        EXPECT_EQ(attribute(spec, "patina:map"), "patina");
        EXPECT_EQ(attribute(spec, "patina:baker"), "test");
        EXPECT_EQ(attribute(spec, "patina:units"), "m");
        EXPECT_EQ(attribute(spec, "patina:description"), map.description);
        EXPECT_EQ(spec.get_int_attribute("patina:udim"), 1001);
        EXPECT_EQ(spec.get_int_attribute("patina:padding", -99), 3);
        // OpenEXR has no colour-space attribute and OIIO 2.4 neither writes oiio:ColorSpace
        // to EXR nor reads it back (it reports "Linear"): our own attribute says raw.
        EXPECT_EQ(attribute(spec, "patina:colorspace"), "raw");
        EXPECT_EQ(spec.get_int_attribute("patina:samples"), 64);
        EXPECT_EQ(spec.get_float_attribute("patina:max_distance"), 2.5f);
        EXPECT_EQ(attribute(spec, "patina:sky"), "clear");
        // A mip-mapped texture: levels down to 1 x 1 (64 x 32 -> 6 more levels).
        int levels = 1;
        while (in->seek_subimage(0, levels))
            ++levels;
        EXPECT_EQ(levels, 7);
        in.reset();

        // Covered texels hold exactly the baked values (FLOAT), looked up by channel name
        // (OpenEXR sorts channels by name).
        const ImageData image = read_image(files[0]);
        const int thickness = image.channel("thickness"), exposure = image.channel("exposure");
        ASSERT_GE(thickness, 0);
        ASSERT_GE(exposure, 0);
        int checked = 0;
        for (int y = 0; y < grid.height; ++y)
            for (int x = 0; x < grid.width; ++x) {
                const int32_t g = grid.group_of_texel[static_cast<size_t>(y) * grid.width + x];
                if (g < 0)
                    continue;
                ASSERT_EQ(image.at(x, y, thickness), values[static_cast<size_t>(g) * 2]);
                ASSERT_EQ(image.at(x, y, exposure), values[static_cast<size_t>(g) * 2 + 1]);
                ++checked;
            }
        EXPECT_EQ(checked, grid.covered_count());
        // Beyond the margin the background is 0.
        EXPECT_EQ(image.at(30, 20, thickness), 0.0f);
    }

    TEST(WriteTexelMap, HalfFormat)
    {
        const fs::path dir = scratch_dir("half");
        const TexelGrid grid = rect_grid(16, 16, {{0, 0, 8, 8}});
        MapDescription map = thickness_map();
        MapOutputOptions options;
        options.format = OIIO::TypeDesc::HALF;
        const auto files = write_texel_map(dir, map, {grid}, {ramp_values(grid, 2)}, options);
        auto in = OIIO::ImageInput::open(files.at(0).string());
        ASSERT_TRUE(in);
        EXPECT_EQ(in->spec().format, OIIO::TypeDesc::HALF);
    }

    TEST(WriteTexelMap, UdimTilesGetOneFileEachNamedByTile)
    {
        const fs::path dir = scratch_dir("udim");
        MapDescription map = thickness_map();
        map.name = "ao";
        map.channels = {"ao"};
        std::vector<TexelGrid> tiles = {rect_grid(16, 16, {{0, 0, 16, 16}}, 1001),
                                        rect_grid(16, 16, {{0, 0, 16, 16}}, 1002)};
        const std::vector<std::vector<float>> values = {ramp_values(tiles[0], 1, 0.0f),
                                                        ramp_values(tiles[1], 1, 1000.0f)};
        const auto files = write_texel_map(dir, map, tiles, values, {});
        ASSERT_EQ(files.size(), 2u);
        EXPECT_EQ(files[0], dir / "ao.1001.exr");
        EXPECT_EQ(files[1], dir / "ao.1002.exr");
        EXPECT_FALSE(fs::exists(dir / "ao.exr"));
        for (size_t i = 0; i < 2; ++i) {
            const ImageData image = read_image(files[i]);
            EXPECT_EQ(image.at(5, 3, 0), values[i][3 * 16 + 5]) << files[i];
            auto in = OIIO::ImageInput::open(files[i].string());
            ASSERT_TRUE(in);
            EXPECT_EQ(in->spec().get_int_attribute("patina:udim"), tiles[i].udim);
        }

        // A lone tile other than 1001 keeps its number in the name.
        const auto lone = write_texel_map(dir, map, {tiles[1]}, {values[1]}, {});
        EXPECT_EQ(lone.at(0), dir / "ao.1002.exr");
        // No staging folders or temporary files are left behind.
        for (const auto& entry : fs::directory_iterator(dir)) {
            EXPECT_EQ(entry.path().string().find(".tmp-"), std::string::npos) << entry.path();
            EXPECT_EQ(entry.path().string().find(".patina-staging-"), std::string::npos)
                << entry.path();
        }
    }

    TEST(WriteTexelMap, NonFiniteValueIsRefusedNamingMapAndTexel)
    {
        const fs::path dir = scratch_dir("nan");
        const TexelGrid grid = rect_grid(8, 8, {{2, 3, 6, 7}});
        MapDescription map = thickness_map();
        std::vector<float> values = ramp_values(grid, 2);
        // Group 5 is texel (3, 4): row 3 holds groups 0..3 at x = 2..5, row 4 starts at 4.
        values[5 * 2 + 1] = std::numeric_limits<float>::quiet_NaN();
        const std::string message =
            patina::test::message_of([&] { write_texel_map(dir, map, {grid}, {values}, {}); });
        EXPECT_NE(message.find("map 'patina'"), std::string::npos) << message;
        EXPECT_NE(message.find("texel (3, 4)"), std::string::npos) << message;
        EXPECT_NE(message.find("channel 'exposure'"), std::string::npos) << message;
        EXPECT_NE(message.find("NaN"), std::string::npos) << message;
        EXPECT_FALSE(fs::exists(dir / "patina.exr"));
    }

    TEST(WriteTexelMap, CancelledBeforeWritingLeavesNoFile)
    {
        const fs::path dir = scratch_dir("cancel");
        const TexelGrid grid = rect_grid(8, 8, {{0, 0, 4, 4}});
        request_cancel();
        EXPECT_THROW(write_texel_map(dir, thickness_map(), {grid}, {ramp_values(grid, 2)}, {}),
                     Cancelled);
        reset_cancel();
        EXPECT_TRUE(fs::is_empty(dir));
    }

    TEST(WriteTexelMap, MismatchedSizesAreErrors)
    {
        const fs::path dir = scratch_dir("sizes");
        const TexelGrid grid = rect_grid(8, 8, {{0, 0, 4, 4}});
        MapDescription map = thickness_map();
        std::vector<float> values = ramp_values(grid, 2);
        values.pop_back();
        EXPECT_NE(patina::test::message_of([&] {
                      write_texel_map(dir, map, {grid}, {values}, {});
                  }).find("31 values for 16 texel groups x 2 channels"),
                  std::string::npos);
        EXPECT_NE(patina::test::message_of([&] {
                      write_texel_map(dir, map, {grid, grid}, {values}, {});
                  }).find("values for 1 tiles, but 2 tiles"),
                  std::string::npos);
        map.parameters.emplace_back("udim", 3);
        EXPECT_NE(patina::test::message_of([&] {
                      write_texel_map(dir, map, {grid}, {ramp_values(grid, 2)}, {});
                  }).find("clashes with the header attribute patina:udim"),
                  std::string::npos);
    }

    /// Seam check of the issue: write a map whose covered value is 1 (background 0) with
    /// `margin` texels of padding and return, per mip level, the smallest value among the
    /// texels whose footprint holds a covered texel (what a lookup on the surface can read),
    /// and how many such texels straddle a seam (footprint partly uncovered).
    struct SeamResult {
        std::vector<float> min_on_surface;
        std::vector<int> seam_texels;
        float min_inside = 1.0f;  ///< over texels fully inside an island, all levels
    };

    SeamResult seam_check(const fs::path& dir, const TexelGrid& grid, int margin, int levels)
    {
        MapDescription map;
        map.name = "ones";
        map.channels = {"value"};
        map.units = "1";
        map.baker = "test";
        const std::vector<float> ones(grid.groups.group_count(), 1.0f);
        MapOutputOptions options;
        options.padding = margin;
        options.tile_size = 32;
        const auto files = write_texel_map(dir, map, {grid}, {ones}, options);
        SeamResult result;
        for (int level = 0; level < levels; ++level) {
            const MipLevel mip = read_mip_level(files.at(0), level);
            const int block = 1 << level;
            EXPECT_EQ(mip.width, grid.width / block);
            float lowest = 1.0f;
            int seam = 0;
            for (int y = 0; y < mip.height; ++y)
                for (int x = 0; x < mip.width; ++x) {
                    int covered = 0;
                    for (int j = 0; j < block; ++j)
                        for (int i = 0; i < block; ++i)
                            covered += grid.group_of_texel[static_cast<size_t>(y * block + j) *
                                                               grid.width +
                                                           x * block + i] >= 0;
                    if (covered == 0)
                        continue;
                    lowest = std::min(lowest, mip.at(x, y));
                    if (covered < block * block)
                        ++seam;
                    else
                        result.min_inside = std::min(result.min_inside, mip.at(x, y));
                }
            result.min_on_surface.push_back(lowest);
            result.seam_texels.push_back(seam);
        }
        return result;
    }

    /// The cube of the issue: six face islands with gaps, rasterised at 120 x 120 so that
    /// island edges (at multiples of 1/64 in uv) cut through texels and mip blocks: levels
    /// 1 to 3 halve exactly (120, 60, 30, 15) and each has texels straddling the seams.
    TexelGrid atlas_cube_grid()
    {
        RasterOptions raster;
        raster.width = raster.height = 120;
        std::vector<TexelGrid> tiles = rasterize_uv(patina::test::make_atlas_cube(), raster);
        EXPECT_EQ(tiles.size(), 1u);
        return std::move(tiles.at(0));
    }

    TEST(Padding, CubeAtlasMipLevelsWithinTheMarginShowNoBackgroundAlongSeams)
    {
        const fs::path dir = scratch_dir("cube_seams");
        const TexelGrid grid = atlas_cube_grid();
        const int margin = 4;
        const SeamResult r = seam_check(dir, grid, margin, 4);
        // Levels 0..2 have 2^level <= margin: every texel touching the surface stays within
        // 1e-3 of 1, seam texels included (and there are seam texels to check).
        EXPECT_EQ(r.min_on_surface[0], 1.0f);  // covered texels keep their exact value
        for (int level = 1; level <= 2; ++level) {
            EXPECT_GT(r.seam_texels[level], 0) << "level " << level;
            EXPECT_NEAR(r.min_on_surface[level], 1.0f, 1e-3f) << "level " << level;
        }
        EXPECT_NEAR(r.min_inside, 1.0f, 1e-3f);
        // Level 3 averages 8 x 8 blocks, wider than the margin protects (2^3 - 1 > 4): the
        // background shows there, so the margin is what keeps levels 1 and 2 clean.
        EXPECT_LT(r.min_on_surface[3], 0.99f);
    }

    TEST(Padding, CubeAtlasWithoutPaddingBleedsAtTheFirstMipLevel)
    {
        // The control: without padding the background darkens seam texels, so the test
        // above can fail.
        const fs::path dir = scratch_dir("cube_seams_control");
        const SeamResult r = seam_check(dir, atlas_cube_grid(), 0, 3);
        EXPECT_EQ(r.min_on_surface[0], 1.0f);  // level 0 has no averaging
        EXPECT_LT(r.min_on_surface[1], 0.9f);
        EXPECT_LT(r.min_on_surface[2], 0.9f);
    }

    TEST(Padding, HandMadeAtlasFullFillKeepsEveryLevelClean)
    {
        // Islands at odd offsets so that seams cut through mip blocks at every level; with
        // margin -1 (fill all) no level sees the background.
        const fs::path dir = scratch_dir("rect_seams");
        const TexelGrid grid = rect_grid(64, 64,
                                         {{1, 3, 20, 28},
                                          {23, 3, 41, 28},
                                          {45, 5, 63, 30},
                                          {1, 35, 20, 61},
                                          {23, 37, 41, 62},
                                          {45, 35, 62, 60}});
        const SeamResult full = seam_check(dir, grid, -1, 7);
        for (size_t level = 0; level < full.min_on_surface.size(); ++level)
            EXPECT_NEAR(full.min_on_surface[level], 1.0f, 1e-3f) << "level " << level;
        // Margin 1 protects level 1 (2^1 <= 1 + 1, see padding.h) but not level 3.
        const SeamResult narrow = seam_check(dir, grid, 1, 4);
        EXPECT_NEAR(narrow.min_on_surface[1], 1.0f, 1e-3f);
        EXPECT_LT(narrow.min_on_surface[3], 0.99f);
    }

    TEST(WriteTexelMap, CoverageChannelFollowsTheRasterAndIsNotPadded)
    {
        // The cube atlas at 120 x 120: island borders cut through texels. A map of zeros
        // ("fully occluded" for ao) padded over everything: without the coverage channel
        // the baked zeros and the empty texels would be the same.
        const fs::path dir = scratch_dir("coverage");
        const TexelGrid grid = atlas_cube_grid();
        MapDescription map = thickness_map();
        map.name = "ao";
        map.channels = {"ao"};
        std::vector<float> values(grid.groups.group_count(), 0.0f);
        MapOutputOptions options;
        options.padding = -1;
        const auto files = write_texel_map(dir, map, {grid}, {values}, options);
        const ImageData image = read_image(files.at(0));
        ASSERT_EQ(image.channels, 2);
        EXPECT_EQ(image.channel_names[0], "ao");  // the map's own channel keeps its index
        const int a = image.channel(kCoverageChannel);
        ASSERT_EQ(a, 1);
        int partial = 0, empty = 0;
        for (int y = 0; y < grid.height; ++y) {
            for (int x = 0; x < grid.width; ++x) {
                const size_t t = static_cast<size_t>(y) * grid.width + x;
                const float alpha = image.at(x, y, a);
                if (grid.group_of_texel[t] < 0) {
                    EXPECT_EQ(alpha, 0.0f) << x << ", " << y;  // padding fills colour only
                    ++empty;
                } else {
                    EXPECT_EQ(alpha, grid.coverage[t]) << x << ", " << y;
                    EXPECT_GT(alpha, 0.0f);
                    partial += alpha < 1.0f;
                }
            }
        }
        // Both kinds of texel are there to check: island borders and the gaps between.
        EXPECT_GT(partial, 0);
        EXPECT_GT(empty, 0);
    }

    TEST(WriteTexelMap, PaddedColourChannelsAndUnpaddedCoverage)
    {
        // Padding still spreads the map's values into the gaps (mip levels stay clean),
        // while the coverage there stays 0.
        const fs::path dir = scratch_dir("coverage_padding");
        const TexelGrid grid = rect_grid(16, 16, {{2, 2, 6, 6}});
        MapDescription map = thickness_map();
        map.channels = {"thickness"};
        std::vector<float> values(grid.groups.group_count(), 5.0f);
        MapOutputOptions options;
        options.padding = 2;
        const auto files = write_texel_map(dir, map, {grid}, {values}, options);
        const ImageData image = read_image(files.at(0));
        const int a = image.channel(kCoverageChannel);
        ASSERT_GE(a, 0);
        EXPECT_EQ(image.at(3, 3, 0), 5.0f);
        EXPECT_EQ(image.at(3, 3, a), 1.0f);
        EXPECT_EQ(image.at(7, 3, 0), 5.0f);  // padded, one texel out
        EXPECT_EQ(image.at(7, 3, a), 0.0f);
        EXPECT_EQ(image.at(12, 12, 0), 0.0f);  // beyond the margin
        EXPECT_EQ(image.at(12, 12, a), 0.0f);
        // A map may not name a channel after the coverage channel.
        map.channels = {"thickness", kCoverageChannel};
        EXPECT_THROW(write_texel_map(dir, map, {grid}, {{}}, options), std::runtime_error);
    }

}  // namespace
}  // namespace patina::texgen
