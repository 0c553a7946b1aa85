#include "core/image_io.h"

#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include "test_util.h"

#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace patina {
namespace {

    std::filesystem::path scratch(const std::string& name)
    {
        const std::filesystem::path dir = std::filesystem::path(PATINA_TEST_BUILD_DIR) / "image_io_test";
        std::filesystem::create_directories(dir);
        return dir / name;
    }

    std::vector<float> gradient(int w, int h, int c)
    {
        std::vector<float> p(static_cast<size_t>(w) * h * c);
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x)
                for (int k = 0; k < c; ++k)
                    p[(static_cast<size_t>(y) * w + x) * c + k] =
                        (x + 2.0f * y + 0.25f * k) / (w + 2.0f * h);
        return p;
    }

    /// Left-over staging folders (".patina-staging-*") or old-style temporaries in `dir`.
    int temporaries_in(const std::filesystem::path& dir)
    {
        int n = 0;
        for (const auto& e : std::filesystem::directory_iterator(dir)) {
            const std::string name = e.path().filename().string();
            n += name.find(".tmp-") != std::string::npos || name.starts_with(".patina-staging-");
        }
        return n;
    }

    using patina::test::message_of;

}  // namespace

TEST(ImageIo, ExrFloatRoundTripIsExactWithMetadata)
{
    const auto path = scratch("float.exr");
    const auto pixels = gradient(17, 9, 3);
    write_image_atomic(path, pixels.data(), 17, 9, 3, {"thickness", "exposure", "wetness"},
                       OIIO::TypeDesc::FLOAT,
                       {{"patina:bake", std::string("accessibility")}, {"patina:samples", 256},
                        {"patina:radius_m", 0.5f}});
    const ImageData img = read_image(path);
    ASSERT_EQ(img.width, 17);
    ASSERT_EQ(img.height, 9);
    ASSERT_EQ(img.channels, 3);
    // OpenEXR keeps channels sorted by name: find them by name, not position.
    const int thickness = img.channel("thickness"), exposure = img.channel("exposure"),
              wetness = img.channel("wetness");
    ASSERT_GE(thickness, 0);
    ASSERT_GE(exposure, 0);
    ASSERT_GE(wetness, 0);
    EXPECT_EQ(img.channel("albedo"), -1);
    for (int y = 0; y < 9; ++y)
        for (int x = 0; x < 17; ++x) {
            const size_t i = (static_cast<size_t>(y) * 17 + x) * 3;
            EXPECT_EQ(img.at(x, y, thickness), pixels[i]);
            EXPECT_EQ(img.at(x, y, exposure), pixels[i + 1]);
            EXPECT_EQ(img.at(x, y, wetness), pixels[i + 2]);
        }
    auto meta = [&](const std::string& key) {
        for (const auto& [k, v] : img.metadata)
            if (k == key)
                return v;
        return std::string("(missing)");
    };
    EXPECT_EQ(meta("patina:bake"), "accessibility");
    EXPECT_EQ(meta("patina:samples"), "256");
    EXPECT_EQ(meta("patina:radius_m"), "0.5");
    EXPECT_EQ(temporaries_in(path.parent_path()), 0);
}

TEST(ImageIo, ExrHalfRoundTripWithinHalfPrecision)
{
    const auto path = scratch("half.exr");
    const auto pixels = gradient(8, 8, 4);
    write_image_atomic(path, pixels.data(), 8, 8, 4, {}, OIIO::TypeDesc::HALF);
    const ImageData img = read_image(path);
    ASSERT_EQ(img.channels, 4);
    EXPECT_EQ(img.channel_names, (std::vector<std::string>{"R", "G", "B", "A"}));
    for (size_t i = 0; i < pixels.size(); ++i)
        EXPECT_NEAR(img.pixels[i], pixels[i], 1e-3f * std::max(1.0f, pixels[i])) << i;
}

TEST(ImageIo, PngUint8RoundTripWithinOneCode)
{
    const auto path = scratch("review.png");
    const auto pixels = gradient(13, 7, 3);
    write_image_atomic(path, pixels.data(), 13, 7, 3, {}, OIIO::TypeDesc::UINT8);
    const ImageData img = read_image(path);
    ASSERT_EQ(img.width, 13);
    ASSERT_EQ(img.channels, 3);
    for (size_t i = 0; i < pixels.size(); ++i)
        EXPECT_NEAR(img.pixels[i], pixels[i], 0.5f / 255.0f + 1e-6f) << i;
}

TEST(ImageIo, UnwritableFolderThrowsNamingFileAndLeavesNothing)
{
    const auto dir = scratch("locked");
    std::filesystem::create_directories(dir);
    const auto pixels = gradient(4, 4, 3);
    // A folder that is a file cannot be written by anyone, root included (a missing folder
    // is made when the output moves into place).
    { std::ofstream(dir / "not_a_folder") << "x"; }
    const auto missing = dir / "not_a_folder" / "out.exr";
    const std::string msg = message_of(
        [&] { write_image_atomic(missing, pixels.data(), 4, 4, 3, {}, OIIO::TypeDesc::HALF); });
    EXPECT_NE(msg.find(missing.string()), std::string::npos) << msg;
    EXPECT_FALSE(std::filesystem::exists(missing));
    EXPECT_EQ(temporaries_in(dir), 0);

    // A read-only folder (only meaningful when not running as root, who may write anyway).
    if (::geteuid() != 0) {
        std::filesystem::permissions(dir, std::filesystem::perms::owner_read |
                                              std::filesystem::perms::owner_exec);
        const auto locked = dir / "out.exr";
        EXPECT_THROW(write_image_atomic(locked, pixels.data(), 4, 4, 3, {}, OIIO::TypeDesc::HALF),
                     std::runtime_error);
        std::filesystem::permissions(dir, std::filesystem::perms::owner_all);
        EXPECT_FALSE(std::filesystem::exists(locked));
        EXPECT_EQ(temporaries_in(dir), 0);
    }
}

TEST(ImageIo, FailedWriteKeepsTheGoodFileAndRemovesTheTemporary)
{
    const auto path = scratch("good.exr");
    const auto good = gradient(6, 5, 3);
    write_image_atomic(path, good.data(), 6, 5, 3, {}, OIIO::TypeDesc::FLOAT);
    const auto before = std::filesystem::file_size(path);

    // Rename fails after the temporary is complete: the target is a non-empty folder.
    const auto blocked = scratch("blocked.exr");
    std::filesystem::create_directories(blocked / "keep");
    const auto other = gradient(6, 5, 3);
    EXPECT_THROW(write_image_atomic(blocked, other.data(), 6, 5, 3, {}, OIIO::TypeDesc::FLOAT),
                 std::runtime_error);
    EXPECT_TRUE(std::filesystem::is_directory(blocked / "keep"));

    // OIIO refuses the write (PNG cannot hold 7 channels, or the spec is inconsistent):
    // the good file stays byte-identical.
    std::vector<float> bad(6 * 5 * 3, 9.0f);
    EXPECT_THROW(write_image_atomic(path, bad.data(), 6, 5, 3, {"a", "b"}, OIIO::TypeDesc::FLOAT),
                 std::runtime_error);
    EXPECT_THROW(write_image_atomic(path, bad.data(), 6, 5, 3, {}, OIIO::TypeDesc::INT32),
                 std::runtime_error);
    // OIIO itself refuses: PNG holds at most 4 channels.
    const auto png = scratch("good.png");
    write_image_atomic(png, good.data(), 6, 5, 3, {}, OIIO::TypeDesc::UINT8);
    const auto png_size = std::filesystem::file_size(png);
    std::vector<float> seven(6 * 5 * 7, 0.5f);
    const std::string msg = message_of(
        [&] { write_image_atomic(png, seven.data(), 6, 5, 7, {}, OIIO::TypeDesc::UINT8); });
    EXPECT_NE(msg.find(png.string()), std::string::npos) << msg;
    EXPECT_EQ(std::filesystem::file_size(png), png_size);

    EXPECT_EQ(std::filesystem::file_size(path), before);
    EXPECT_EQ(read_image(path).pixels, good);
    EXPECT_EQ(temporaries_in(path.parent_path()), 0);
}

TEST(ImageIo, UnknownFormatAndMissingFileNameTheFile)
{
    const auto pixels = gradient(2, 2, 3);
    const auto odd = scratch("out.notaformat");
    const std::string w = message_of(
        [&] { write_image_atomic(odd, pixels.data(), 2, 2, 3, {}, OIIO::TypeDesc::FLOAT); });
    EXPECT_NE(w.find(odd.string()), std::string::npos) << w;
    EXPECT_FALSE(std::filesystem::exists(odd));

    const std::string r = message_of([] { (void)read_image("/nonexistent/bake.exr"); });
    EXPECT_NE(r.find("/nonexistent/bake.exr"), std::string::npos) << r;
    EXPECT_NE(r.find("not found"), std::string::npos) << r;

    const auto garbage = scratch("garbage.exr");
    std::ofstream(garbage) << "this is not an OpenEXR file";
    const std::string g = message_of([&] { (void)read_image(garbage); });
    EXPECT_NE(g.find(garbage.string()), std::string::npos) << g;
}

TEST(ImageIo, AnImageHeldInMemoryReadsWhateverItsFormatHintSays)
{
    // The bytes of a PNG (as a mesh file embeds them), read with the right hint, a wrong
    // one (OIIO then asks its other readers) and none.
    const auto path = scratch("embedded.png");
    const auto pixels = gradient(5, 3, 3);
    write_image_atomic(path, pixels.data(), 5, 3, 3, {}, OIIO::TypeDesc::UINT8);
    const std::string text = patina::test::read_text(path);
    const std::vector<unsigned char> bytes(text.begin(), text.end());
    for (const char* hint : {"png", "jpg", ""}) {
        const ImageData image = read_image(bytes, hint, "tread.png");
        ASSERT_EQ(image.width, 5) << hint;
        ASSERT_EQ(image.height, 3) << hint;
        for (size_t i = 0; i < pixels.size(); ++i)
            EXPECT_NEAR(image.pixels[i], pixels[i], 0.5f / 255.0f + 1e-6f) << hint << " " << i;
    }
    const std::vector<unsigned char> garbage{'n', 'o', 't', ' ', 'a', 'n', ' ', 'i', 'm', 'g'};
    const std::string g = message_of([&] { (void)read_image(garbage, "png", "tread.png"); });
    EXPECT_NE(g.find("cannot read image 'tread.png'"), std::string::npos) << g;
}

TEST(ImageIo, MakeTextureWritesTiledMipmappedExr)
{
    const auto path = scratch("tex.exr");
    const auto pixels = gradient(64, 32, 1);
    TextureOptions opt;
    opt.tile_size = 16;
    opt.metadata = {{"patina:map", std::string("thickness_um")}};
    make_texture_atomic(path, pixels.data(), 64, 32, 1, {"thickness_um"}, opt);
    EXPECT_EQ(temporaries_in(path.parent_path()), 0);

    auto in = OIIO::ImageInput::open(path.string());
    ASSERT_TRUE(in) << OIIO::geterror();
    EXPECT_EQ(in->format_name(), std::string("openexr"));
    EXPECT_EQ(in->spec().tile_width, 16);
    EXPECT_EQ(in->spec().channelnames[0], "thickness_um");
    EXPECT_EQ(in->spec().get_string_attribute("patina:map"), "thickness_um");
    EXPECT_EQ(in->spec().get_string_attribute("wrapmodes"), "periodic,periodic");
    int levels = 0;
    while (in->seek_subimage(0, levels))
        ++levels;
    EXPECT_EQ(levels, 7); // 64x32, 32x16, ..., 1x1
    in->close();

    // A failed make_texture keeps the existing texture.
    const auto before = std::filesystem::file_size(path);
    opt.format = OIIO::TypeDesc::UINT8;
    EXPECT_THROW(make_texture_atomic(path, pixels.data(), 64, 32, 1, {}, opt), std::runtime_error);
    EXPECT_EQ(std::filesystem::file_size(path), before);

    // make_texture succeeds but the rename cannot: the temporary is removed.
    const auto blocked = scratch("blocked_tex.exr");
    std::filesystem::create_directories(blocked / "keep");
    opt.format = OIIO::TypeDesc::HALF;
    EXPECT_THROW(make_texture_atomic(blocked, pixels.data(), 64, 32, 1, {}, opt), std::runtime_error);
    EXPECT_EQ(temporaries_in(path.parent_path()), 0);
}

}  // namespace patina
