// Filtered texture lookups through one OpenImageIO TextureSystem, with the conversion from
// each texture's declared colour space to the working space. Backs the ABI's
// PatinaHostServices::texture_lookup.
#pragma once

#include "core/color_management.h"

#include <OpenImageIO/texture.h>

#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <string_view>
#include <utility>

namespace patina {

/// Owns a TextureSystem (not OIIO's process-wide shared one, so independent users and tests
/// do not see each other's cache) and the textures opened through it.
///
/// Colour: a texture declares its colour space when opened. One in a colour space other
/// than the working space is converted once, at open, into a cached working-space texture
/// (core/texture_conversion.h), so lookups filter and mip-map linear working-space values.
/// Data maps declare "raw" (any `isdata` space) and are never converted.
///
/// UDIM: a file name holding `<UDIM>` (e.g. "maps/thickness.<UDIM>.exr") names the tiles
/// "maps/thickness.1001.exr", "...1002.exr", ...; a lookup at (u, v) reads the tile
/// 1001 + floor(u) + 10 floor(v) (none: 0). Its tiles are data or already in the working space.
///
/// Channels 0-2 of a texture are its RGB; a 1- or 2-channel texture in a colour space
/// holds a grey in channel 0. Other channels (alpha, extra data) are never converted.
class TextureAccess {
public:
    struct Options {
        float max_memory_mb = 1024.0f; ///< tile cache size
        int max_open_files = 200;
        int autotile = 64;             ///< tile size for untiled files read lazily
        OIIO::TextureOpt::Wrap wrap = OIIO::TextureOpt::WrapPeriodic;
    };

    /// An opened texture; stays valid as long as the TextureAccess.
    struct Handle {
        std::filesystem::path filename;
        std::string colorspace;        ///< as declared (name, alias or role)
        int channels = 0;
        int width = 0, height = 0;
        bool is_data = false;          ///< declared colour space is data: no conversion
        bool udim = false;             ///< a `<UDIM>` pattern: width and height are a tile's
        ColorConversion to_working;    ///< identity for data or working-space textures
        OIIO::TextureSystem::TextureHandle* oiio = nullptr;
    };

    /// The most channels a converted lookup may span (first_channel + nchannels).
    static constexpr int kMaxConvertedChannels = 16;

    /// `colors` converts to its working space and must outlive this object.
    explicit TextureAccess(const ColorManager& colors) : TextureAccess(colors, Options{}) {}
    TextureAccess(const ColorManager& colors, const Options& options);
    ~TextureAccess();
    TextureAccess(const TextureAccess&) = delete;
    TextureAccess& operator=(const TextureAccess&) = delete;

    /// Open `filename` declared in `colorspace` (a name, alias or role of the OCIO config).
    /// Checks now that the file exists and OIIO can read it (for a `<UDIM>` pattern: that a
    /// tile exists and every tile can be read); throws std::runtime_error
    /// "texture '<file>': <reason>" otherwise, or for an unknown colour space. A file that is
    /// not found but whose UDIM tiles are is named with the `<UDIM>` pattern to use. Opening the
    /// same file with the same colour space again returns the same handle. Thread-safe.
    Handle* open(const std::filesystem::path& filename, std::string_view colorspace);

    /// Filtered, mip-mapped lookup at (s, t) with screen-space derivatives (all zero = point
    /// sample, bilinear on the finest level). OIIO convention: s = 0 at the left, t = 0 at
    /// the top row of the image (a mesh's v, 0 at the bottom, becomes t = 1 - v). Writes channels [first_channel,
    /// first_channel + nchannels) to `out`, converted to the working space; channels past
    /// the texture's count are 0. Returns false (out zeroed) on failure or bad arguments.
    /// Thread-safe; allocation-free.
    bool lookup(const Handle* handle, float s, float t, float dsdx, float dtdx, float dsdy,
                float dtdy, int first_channel, int nchannels, float* out) const;

    /// The last error of the TextureSystem (for messages after a failed lookup).
    std::string last_error() const;

    OIIO::TextureSystem& texture_system() const { return *ts_; }

private:
    const ColorManager* colors_;
    Options options_;
    OIIO::TextureSystem* ts_ = nullptr;
    std::mutex mutex_;
    std::map<std::pair<std::string, std::string>, std::unique_ptr<Handle>> handles_;
};

}  // namespace patina
