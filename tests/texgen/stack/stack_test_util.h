// Test data for the stack tests: texel grids whose coverage is a set of rectangles (a UV
// atlas made by hand), scratch folders, and the texels of one mip level of a written map.
#pragma once

#include "texgen/texels/texel_grid.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

namespace patina::texgen::test {

/// Texels [x0, x1) x [y0, y1) of a grid.
struct TexelRect {
    int x0, y0, x1, y1;
    bool contains(int x, int y) const { return x >= x0 && x < x1 && y >= y0 && y < y1; }
};

/// A width x height grid covering `rects`; each covered texel is its own group (in scan
/// order) holding one sample at its texel centre (z = 0).
inline TexelGrid rect_grid(int width, int height, const std::vector<TexelRect>& rects,
                           int udim = 1001)
{
    TexelGrid grid;
    grid.udim = udim;
    grid.width = width;
    grid.height = height;
    grid.group_of_texel.assign(grid.texel_count(), -1);
    grid.coverage.assign(grid.texel_count(), 0.0f);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            bool in = false;
            for (const TexelRect& r : rects)
                in = in || r.contains(x, y);
            if (!in)
                continue;
            const size_t t = static_cast<size_t>(y) * width + x;
            grid.group_of_texel[t] = static_cast<int32_t>(grid.groups.group_count());
            grid.coverage[t] = 1.0f;
            SurfaceSample s;
            s.P = Imath::V3f(x + 0.5f, y + 0.5f, 0.0f);
            s.N = s.Ng = Imath::V3f(0, 0, 1);
            s.uv = Imath::V2f((x + 0.5f) / width, 1.0f - (y + 0.5f) / height);
            grid.groups.add_group({s});
        }
    return grid;
}

/// An empty scratch folder for one test, inside the test build tree.
inline std::filesystem::path scratch_dir(const std::string& name)
{
    const std::filesystem::path dir =
        std::filesystem::path(PATINA_TEST_BUILD_DIR) / "texgen_stack" / name;
    std::filesystem::remove_all(dir);
    std::filesystem::create_directories(dir);
    return dir;
}

/// One mip level of a texture file, as floats.
struct MipLevel {
    int width = 0, height = 0, channels = 0;
    std::vector<float> pixels;
    float at(int x, int y, int c = 0) const
    {
        return pixels[(static_cast<size_t>(y) * width + x) * channels + c];
    }
};

/// Read mip level `level` of subimage 0 of `path`; fails the test if it does not exist.
inline MipLevel read_mip_level(const std::filesystem::path& path, int level)
{
    MipLevel mip;
    auto in = OIIO::ImageInput::open(path.string());
    EXPECT_TRUE(in) << OIIO::geterror();
    if (!in)
        return mip;
    EXPECT_TRUE(in->seek_subimage(0, level)) << path << " has no mip level " << level;
    const OIIO::ImageSpec& spec = in->spec();
    mip.width = spec.width;
    mip.height = spec.height;
    mip.channels = spec.nchannels;
    mip.pixels.resize(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
    EXPECT_TRUE(
        in->read_image(0, level, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, mip.pixels.data()))
        << in->geterror();
    return mip;
}

}  // namespace patina::texgen::test
