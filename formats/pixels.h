// The pixels of a file as a format's reader and writer see them, whoever does the image
// I/O: texgen and the renderer read and write through OpenImageIO (core/pixel_io.h), a
// plugin reads through its host's read_image (formats/host_pixels.h). The format library
// lays out and resolves each file's channels once (fade_table.exr, dose.exr, volume.exr):
// no consumer indexes or spells them. Header-only.
#pragma once

#include <filesystem>
#include <span>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace patina::formats {

/// A header attribute as OpenEXR holds it (int, float or string), and a header's list.
using HeaderValue = std::variant<int, float, std::string>;
using Header = std::vector<std::pair<std::string, HeaderValue>>;

/// One image (one subimage of a file): scanlines from the top, channels interleaved.
struct Pixels {
    int width = 0, height = 0, channels = 0;
    /// The channels' names in the file's order; empty when the reader gives none (a plugin
    /// host's read_image): then the format's documented order holds.
    std::vector<std::string> channel_names;
    std::vector<float> values;
    /// Header attributes the format writes ("patina:map" = "fade_table", ...).
    Header attributes;
    /// The subimage's name (an OpenEXR part's: "voxels"), or empty.
    std::string name;

    float at(int x, int y, int c) const
    {
        return values[(static_cast<size_t>(y) * width + x) * channels + c];
    }
};

/// Reads the pixels of a file, for a format's reader.
class PixelReader {
public:
    virtual ~PixelReader() = default;
    /// Every channel of `subimage` of `file` as floats. Throws std::runtime_error naming
    /// the file when it is missing or unreadable.
    virtual Pixels read(const std::filesystem::path& file, int subimage = 0) const = 0;
    /// How many subimages (OpenEXR parts) `file` has, or -1 when the reader cannot tell.
    virtual int subimage_count(const std::filesystem::path&) const { return -1; }
};

/// The index of channel `name` in `pixels`: by name when the reader gave names, else its
/// position in `documented` (the channels as the format writes them, in the order OpenEXR
/// stores them). Throws "file: no channel 'name' (its channels: ...)".
inline int channel_index(const Pixels& pixels, std::string_view name,
                         std::span<const char* const> documented, const std::filesystem::path& file)
{
    if (!pixels.channel_names.empty()) {
        std::string list;
        for (size_t i = 0; i < pixels.channel_names.size(); ++i) {
            if (pixels.channel_names[i] == name)
                return static_cast<int>(i);
            list.append(i ? ", " : "").append(pixels.channel_names[i]);
        }
        throw std::runtime_error(file.string() + ": no channel '" + std::string(name) +
                                 "' (its channels: " + list + ")");
    }
    for (size_t i = 0; i < documented.size(); ++i)
        if (documented[i] == name) {
            if (static_cast<int>(i) >= pixels.channels)
                break;
            return static_cast<int>(i);
        }
    throw std::runtime_error(file.string() + ": no channel '" + std::string(name) + "' (" +
                             std::to_string(pixels.channels) + " unnamed channels)");
}

}  // namespace patina::formats
