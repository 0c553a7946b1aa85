#include "texgen/stack/surface_map.h"

#include "core/image_io.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace patina::texgen {

namespace fs = std::filesystem;

namespace {

    constexpr std::string_view kUdimToken = "<UDIM>";
    // How far outside a tile a uv may lie and still read it (uvs of exactly 1.0, rounding).
    constexpr float kEdgeTolerance = 1e-4f;

    // The files of a UDIM set "dir/prefix<UDIM>suffix": every existing tile, by UDIM number.
    std::map<int, fs::path> find_udim_files(const fs::path& pattern, const std::string& what)
    {
        const std::string name = pattern.filename().string();
        const size_t token = name.find(kUdimToken);
        if (token == std::string::npos)
            throw std::runtime_error(fmt::format("{} '{}': the <UDIM> token must be in the file "
                                                 "name, not in a folder",
                                                 what, pattern.string()));
        const std::string prefix = name.substr(0, token);
        const std::string suffix = name.substr(token + kUdimToken.size());
        const fs::path dir = pattern.has_parent_path() ? pattern.parent_path() : fs::path(".");
        std::map<int, fs::path> files;
        std::error_code ec;
        for (const fs::directory_entry& e : fs::directory_iterator(dir, ec)) {
            const std::string f = e.path().filename().string();
            if (f.size() != prefix.size() + 4 + suffix.size() ||
                f.compare(0, prefix.size(), prefix) ||
                f.compare(prefix.size() + 4, suffix.size(), suffix))
                continue;
            const std::string digits = f.substr(prefix.size(), 4);
            if (!std::all_of(digits.begin(), digits.end(),
                             [](char c) { return c >= '0' && c <= '9'; }))
                continue;
            const int udim = std::stoi(digits);
            if (udim >= 1001)
                files[udim] = e.path();
        }
        if (files.empty())
            throw std::runtime_error(fmt::format("{} '{}': no tile file matches the pattern{}",
                                                 what, pattern.string(),
                                                 ec ? " (" + ec.message() + ")" : std::string()));
        return files;
    }

} // namespace

SurfaceMap::SurfaceMap(const fs::path& path, const std::vector<std::string>& channels,
                       std::string what, const fs::path& ocio_config)
    : path_(path), what_(std::move(what))
{
    std::map<int, fs::path> files;
    if (path.string().find(kUdimToken) != std::string::npos)
        files = find_udim_files(path, what_);
    else
        files[1001] = path;

    colors_ = std::make_unique<ColorManager>(
        ocio_config.empty() ? ColorManager::default_config_path() : ocio_config);
    TextureAccess::Options options;
    // Texels past the map's edge repeat the edge (the padding already extends the map).
    options.wrap = OIIO::TextureOpt::WrapClamp;
    access_ = std::make_unique<TextureAccess>(*colors_, options);

    bool first = true;
    float maximum = -std::numeric_limits<float>::infinity();
    for (const auto& [udim, file] : files) {
        const auto fail = [&](const std::string& why) {
            return std::runtime_error(fmt::format("{} '{}': {}", what_, file.string(), why));
        };
        // The finest level, for the channel names and the maximum used to normalise.
        ImageData image;
        try {
            image = read_image(file);
        } catch (const std::exception& e) {
            throw fail(e.what());
        }
        int index = -1;
        for (const std::string& c : channels)
            if ((index = image.channel(c)) >= 0) {
                if (first)
                    channel_ = c;
                else if (c != channel_)
                    throw fail(fmt::format("holds channel '{}' where tile {} holds '{}'", c,
                                           files.begin()->first, channel_));
                break;
            }
        if (index < 0) {
            std::string have, want;
            for (const std::string& n : image.channel_names)
                have += (have.empty() ? "" : ", ") + n;
            for (const std::string& n : channels)
                want += (want.empty() ? "" : " or ") + ("'" + n + "'");
            throw fail(fmt::format("has no channel {} (it has: {})", want, have));
        }
        for (size_t i = static_cast<size_t>(index); i < image.pixels.size();
             i += static_cast<size_t>(image.channels))
            maximum = std::max(maximum, image.pixels[i]);
        Tile tile;
        tile.file = file;
        try {
            tile.handle = access_->open(file, "raw");
        } catch (const std::exception& e) {
            throw std::runtime_error(fmt::format("{} {}", what_, e.what()));
        }
        tile.channel_index = index;
        tiles_[udim] = tile;
        first = false;
    }
    maximum_ = std::isfinite(maximum) ? maximum : 0.0f;
}

SurfaceMap::~SurfaceMap() = default;

std::vector<int> SurfaceMap::udims() const
{
    std::vector<int> out;
    for (const auto& [udim, tile] : tiles_)
        out.push_back(udim);
    return out;
}

const SurfaceMap::Tile* SurfaceMap::tile_at(const Imath::V2f& uv, float* s, float* t) const
{
    const auto find = [&](int u0, int v0) -> const Tile* {
        if (u0 < 0 || u0 > 9 || v0 < 0)
            return nullptr;
        // UDIM numbering: 1001 + u0 + 10 v0.
        const auto it = tiles_.find(1001 + u0 + 10 * v0);
        if (it == tiles_.end())
            return nullptr;
        *s = std::clamp(uv.x - static_cast<float>(u0), 0.0f, 1.0f);
        // Row 0 of the image is the top of the tile (v = v0 + 1): OIIO's t = 1 - v.
        *t = 1.0f - std::clamp(uv.y - static_cast<float>(v0), 0.0f, 1.0f);
        return &it->second;
    };
    const int u0 = static_cast<int>(std::floor(uv.x));
    const int v0 = static_cast<int>(std::floor(uv.y));
    if (const Tile* tile = find(u0, v0))
        return tile;
    // On (or a rounding error past) a tile edge: the neighbouring tile it touches.
    const float fu = uv.x - static_cast<float>(u0);
    const float fv = uv.y - static_cast<float>(v0);
    const int du = fu < kEdgeTolerance ? -1 : (fu > 1.0f - kEdgeTolerance ? 1 : 0);
    const int dv = fv < kEdgeTolerance ? -1 : (fv > 1.0f - kEdgeTolerance ? 1 : 0);
    for (const auto& [a, b] : {std::pair{du, 0}, std::pair{0, dv}, std::pair{du, dv}})
        if ((a || b))
            if (const Tile* tile = find(u0 + a, v0 + b))
                return tile;
    return nullptr;
}

float SurfaceMap::at(const Imath::V2f& uv) const
{
    float s = 0.0f, t = 0.0f;
    const Tile* tile = tile_at(uv, &s, &t);
    if (!tile)
        throw std::runtime_error(fmt::format(
            "{} '{}': no tile covers uv ({}, {}) of the baked mesh (was the map baked on this "
            "mesh and UV layout?)",
            what_, path_.string(), uv.x, uv.y));
    float value = 0.0f;
    if (!access_->lookup(tile->handle, s, t, 0.0f, 0.0f, 0.0f, 0.0f, tile->channel_index, 1,
                         &value))
        throw std::runtime_error(fmt::format("{} '{}': lookup failed: {}", what_,
                                             tile->file.string(), access_->last_error()));
    return value;
}

} // namespace patina::texgen
