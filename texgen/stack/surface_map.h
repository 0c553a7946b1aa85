// A baked map read back at a surface sample's uv: the input side of the bakers that combine
// earlier bakes (wetness dried by an exposure map, deposit from an accessibility map).
// Lookups go through core's TextureAccess (OIIO TextureSystem, bilinear on the finest level,
// declared "raw": data maps are never colour converted).
#pragma once

#include "core/color_management.h"
#include "core/texture_access.h"

#include <Imath/ImathVec.h>

#include <filesystem>
#include <map>
#include <memory>
#include <string>
#include <vector>

namespace patina::texgen {

class SurfaceMap {
public:
    /// Open `path`: one file (the UDIM tile 1001, uv in [0,1]^2), or a UDIM set written as
    /// a path holding the token "<UDIM>" (e.g. "maps/exposure.<UDIM>.exr"; every existing
    /// tile is opened). The value read is the first channel of `channels` the map has (e.g.
    /// {"exposure", "irradiance"}); `what` names the map in messages ("exposure map").
    /// `ocio_config` empty: ColorManager::default_config_path(). Throws std::runtime_error
    /// naming the file when it is missing, unreadable, holds a NaN, or lacks the channels
    /// (the message lists the channels it has).
    SurfaceMap(const std::filesystem::path& path, const std::vector<std::string>& channels,
               std::string what, const std::filesystem::path& ocio_config = {});
    ~SurfaceMap();
    SurfaceMap(const SurfaceMap&) = delete;
    SurfaceMap& operator=(const SurfaceMap&) = delete;

    /// The channel's value at `uv` (bilinear between texel centres, image row 0 at v = 1 of
    /// the tile). A uv within 1e-4 of a tile edge whose neighbour tile is missing reads the
    /// tile it touches; a uv in no tile of the map throws std::runtime_error naming the file
    /// and the uv (the map was baked on another mesh or UV layout). Thread-safe.
    float at(const Imath::V2f& uv) const;

    /// The largest value of the channel on the finest level over every tile.
    float maximum() const { return maximum_; }
    /// The channel read.
    const std::string& channel() const { return channel_; }
    const std::filesystem::path& path() const { return path_; }
    /// UDIM numbers of the tiles opened, ascending.
    std::vector<int> udims() const;

private:
    struct Tile {
        std::filesystem::path file;
        const TextureAccess::Handle* handle = nullptr;
        int channel_index = 0;
    };
    const Tile* tile_at(const Imath::V2f& uv, float* s, float* t) const;

    std::filesystem::path path_;
    std::string what_;
    std::string channel_;
    float maximum_ = 0.0f;
    std::unique_ptr<ColorManager> colors_;
    std::unique_ptr<TextureAccess> access_;
    std::map<int, Tile> tiles_; ///< by UDIM number
};

} // namespace patina::texgen
