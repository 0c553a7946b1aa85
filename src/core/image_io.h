// Image files through OpenImageIO only: atomic writes (staged in the run's output transaction,
// output_transaction.h, so a failed or cancelled run never leaves a half-written file nor
// replaces a good one), tiled mip-mapped textures (ImageBufAlgo::make_texture) with the same
// rule, and plain reads.
#pragma once

#include "formats/pixels.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/typedesc.h>

#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace patina {

/// One header attribute, e.g. {"patina:bake", "accessibility"} or {"patina:samples", 256}.
using MetadataValue = formats::HeaderValue;
using Metadata = formats::Header;

/// Pixels as floats, scanline order from the top-left corner, channels interleaved.
/// OpenEXR stores channels sorted by name (OIIO restores R, G, B, A order only), so a map
/// written as (thickness, exposure) reads back as (exposure, thickness): use `channel()`.
struct ImageData {
    int width = 0;
    int height = 0;
    int channels = 0;
    std::vector<float> pixels;
    std::vector<std::string> channel_names;
    /// Every header attribute, as OIIO prints it (`key`, value as text).
    std::vector<std::pair<std::string, std::string>> metadata;

    /// Index of the channel called `name`, or -1.
    int channel(std::string_view name) const
    {
        for (size_t i = 0; i < channel_names.size(); ++i)
            if (channel_names[i] == name)
                return static_cast<int>(i);
        return -1;
    }
    float at(int x, int y, int c) const
    {
        return pixels[(static_cast<size_t>(y) * width + x) * channels + c];
    }
};

/// Where the pixels sit in a larger frame (OpenEXR data window inside the display window):
/// a crop or a farm tile of a `full_width` x `full_height` image, starting at pixel (x, y).
/// Formats without data windows (PNG) store just the pixels.
struct ImageWindow {
    int x = 0, y = 0;
    int full_width = 0, full_height = 0;
};

/// Every entry of `metadata` as a header attribute of `spec`, typed as it is.
void add_metadata(OIIO::ImageSpec& spec, const Metadata& metadata);
/// The header attributes of `spec` (ints, floats and strings; others as text).
Metadata metadata_of(const OIIO::ImageSpec& spec);

/// Write the concatenation of `parts` to `path` as bytes (a text manifest, a PLY), staged in
/// the current output transaction (or one of its own, committed at once): a failed write
/// or run leaves `path` as it was. Throws
/// std::runtime_error "cannot write <what> '<path>': ...".
void write_file_atomic(const std::filesystem::path& path,
                       std::initializer_list<std::string_view> parts, std::string_view what);

/// Write `width` x `height` pixels of `channels` interleaved floats to `path`. The file
/// format follows the extension (.exr, .png, .tif, ...); `format` is the pixel type in the
/// file: TypeDesc::HALF, FLOAT or UINT8 (UINT8 maps [0,1] to [0,255], clamped).
/// `channel_names` may be empty (R, G, B, A, then channelN) or name every channel (an
/// OpenEXR file keeps them sorted by name; readers must look channels up by name).
/// Staged like write_file_atomic: on any failure `path` is untouched and std::runtime_error
/// names the file with OIIO's error text.
/// A second part of an OpenEXR file written by write_image_atomic: `name`, the first
/// part's size and window, channels of 32-bit unsigned ints (`channels` per pixel,
/// interleaved): exact bits, e.g. a double as two of them.
struct UintPart {
    std::string name;
    std::vector<std::string> channels;
    const uint32_t* pixels = nullptr;
};

void write_image_atomic(const std::filesystem::path& path, const float* pixels, int width,
                        int height, int channels,
                        const std::vector<std::string>& channel_names,
                        OIIO::TypeDesc format, const Metadata& metadata = {},
                        const ImageWindow* window = nullptr, const UintPart* second = nullptr);

/// How make_texture_atomic builds a texture.
struct TextureOptions {
    OIIO::TypeDesc format = OIIO::TypeDesc::HALF; ///< HALF or FLOAT (linear data)
    int tile_size = 64;
    std::string wrap = "periodic";     ///< OIIO wrap mode name, both directions
    std::string compression = "zip";
    /// Mip-level filter ("" = OIIO's default box/bilinear; "lanczos3" sharper, rings).
    std::string mip_filter;
    Metadata metadata;                 ///< written into the header (bake parameters)
    /// Commit this file at once, outside the current output transaction (a cache that the
    /// run reads back by its final name).
    bool outside_the_run = false;
};

/// Turn `image` into a tiled, mip-mapped OpenEXR texture at `path`
/// (ImageBufAlgo::make_texture), staged and reported as write_image_atomic.
void make_texture_atomic(const std::filesystem::path& path, const OIIO::ImageBuf& image,
                         const TextureOptions& options = {});
/// The same from interleaved float pixels.
void make_texture_atomic(const std::filesystem::path& path, const float* pixels, int width,
                         int height, int channels,
                         const std::vector<std::string>& channel_names,
                         const TextureOptions& options = {});

/// Throw std::runtime_error "<what> '<file>': texel (x, y) channel c is NaN (n non-finite
/// values)" when the top level of `path` holds a NaN or an infinity; a bad texel must not
/// turn into a plausible-looking render.
void check_finite_texels(const std::filesystem::path& path, const char* what = "texture");

/// Read a subimage (an OpenEXR part; the first by default), top mip level, of any
/// OIIO-readable file as floats. Throws std::runtime_error naming the file when it is
/// missing or unreadable, or has no such subimage.
ImageData read_image(const std::filesystem::path& path, int subimage = 0);
/// An image file held in memory (e.g. embedded in a mesh file): `format` is its extension
/// ("png", "jpg"), `name` names it in errors.
ImageData read_image(std::span<const unsigned char> bytes, const std::string& format,
                     const std::string& name);

}  // namespace patina
