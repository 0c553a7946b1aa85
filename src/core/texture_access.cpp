#include "core/texture_access.h"

#include "core/image_io.h"
#include "core/texture_conversion.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string_view>
#include <vector>
#include <stdexcept>

namespace patina {

namespace fs = std::filesystem;

namespace {

    constexpr std::string_view kUdimToken = "<UDIM>";

    /// The files of a UDIM pattern ("dir/name.<UDIM>.exr"): the existing "dir/name.NNNN.exr",
    /// NNNN from 1001, ascending.
    std::vector<fs::path> udim_tiles(const fs::path& pattern)
    {
        const std::string name = pattern.filename().string();
        const size_t at = name.find(kUdimToken);
        std::vector<fs::path> tiles;
        std::error_code ec;
        const fs::path dir = pattern.parent_path().empty() ? fs::path(".") : pattern.parent_path();
        for (const auto& entry : fs::directory_iterator(dir, ec)) {
            const std::string file = entry.path().filename().string();
            if (file.size() != name.size() - kUdimToken.size() + 4 ||
                file.compare(0, at, name, 0, at) != 0 ||
                file.compare(at + 4, std::string::npos, name, at + kUdimToken.size()) != 0)
                continue;
            const std::string digits = file.substr(at, 4);
            if (std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }) &&
                std::stoi(digits) >= 1001)
                tiles.push_back(pattern.parent_path() / file);
        }
        std::sort(tiles.begin(), tiles.end());
        return tiles;
    }

    /// For a file that does not exist: its UDIM pattern when tiles of it do
    /// ("dir/name.exr" -> "dir/name.<UDIM>.exr" with "dir/name.1001.exr" present), else "".
    std::string udim_pattern_of_missing(const fs::path& file)
    {
        const fs::path pattern =
            file.parent_path() / (file.stem().string() + "." + std::string(kUdimToken) +
                                  file.extension().string());
        return udim_tiles(pattern).empty() ? std::string() : pattern.string();
    }

}  // namespace

TextureAccess::TextureAccess(const ColorManager& colors, const Options& options)
    : colors_(&colors), options_(options)
{
    // shared=false: a private TextureSystem and ImageCache per TextureAccess.
    ts_ = OIIO::TextureSystem::create(false);
    if (!ts_)
        throw std::runtime_error("cannot create an OpenImageIO TextureSystem: " + OIIO::geterror());
    ts_->attribute("automip", 1);
    ts_->attribute("autotile", options_.autotile);
    ts_->attribute("max_memory_MB", options_.max_memory_mb);
    ts_->attribute("max_open_files", options_.max_open_files);
}

TextureAccess::~TextureAccess() { OIIO::TextureSystem::destroy(ts_); }

TextureAccess::Handle* TextureAccess::open(const std::filesystem::path& filename,
                                           std::string_view colorspace)
{
    auto key = std::make_pair(filename.string(), std::string(colorspace));
    std::lock_guard lock(mutex_);
    if (auto it = handles_.find(key); it != handles_.end())
        return it->second.get();

    const auto fail = [&](const std::string& why) {
        return std::runtime_error(fmt::format("texture '{}': {}", filename.string(), why));
    };
    const bool udim = filename.filename().string().find(kUdimToken) != std::string::npos;
    std::vector<fs::path> tiles{filename};
    std::error_code ec;
    if (udim) {
        tiles = udim_tiles(filename);
        if (tiles.empty())
            throw fail(fmt::format("file not found: no UDIM tile of it exists (the tiles are "
                                   "the pattern with {} a number from 1001)",
                                   kUdimToken));
    } else if (!std::filesystem::exists(filename, ec)) {
        const std::string pattern = udim_pattern_of_missing(filename);
        throw fail(pattern.empty()
                       ? std::string("file not found")
                       : fmt::format("file not found, but its UDIM tiles are: name them with "
                                     "the {} token, '{}'",
                                     kUdimToken, pattern));
    } else if (!std::filesystem::is_regular_file(filename, ec)) {
        throw fail("not a regular file");
    }

    auto handle = std::make_unique<Handle>();
    handle->filename = filename;
    handle->colorspace = std::string(colorspace);
    handle->udim = udim;
    fs::path file = filename;
    // A NaN or infinite texel is refused here, naming it, rather than rendering as black or
    // white speckles.
    for (const fs::path& tile : tiles)
        check_finite_texels(tile);
    try {
        handle->is_data = colors_->is_data(colorspace);
        if (udim && !handle->is_data &&
            !colors_->conversion(colorspace, colors_->working_space()).is_identity())
            throw fail(fmt::format("UDIM tiles in the colour space '{}' are not converted: "
                                   "declare them in the working space ({}) or as data, or "
                                   "convert the tiles",
                                   colorspace, colors_->working_space()));
        // Colour textures are converted once, at load, to a cached working-space texture;
        // lookups then filter linear working-space values and convert nothing.
        if (!handle->is_data &&
            !colors_->conversion(colorspace, colors_->working_space()).is_identity())
            file = converted_texture(filename, colorspace, *colors_);
    } catch (const std::exception& e) {
        const std::string what = e.what();
        throw what.rfind("texture '", 0) == 0 ? std::runtime_error(what) : fail(what);
    }

    // Resolve the handle and read the header now, so a bad file fails at open, not
    // silently (black) at the first lookup.
    OIIO::TextureSystem::Perthread* thread = ts_->get_perthread_info();
    handle->oiio = ts_->get_texture_handle(OIIO::ustring(file.string()), thread);
    // A UDIM pattern is a virtual file without a header of its own: the tiles have theirs.
    OIIO::TextureSystem::TextureHandle* header =
        udim ? ts_->get_texture_handle(OIIO::ustring(tiles.front().string()), thread)
             : handle->oiio;
    OIIO::ImageSpec spec;
    if (!handle->oiio || !header || !ts_->get_imagespec(header, thread, 0, spec) ||
        !ts_->good(handle->oiio)) {
        std::string why = ts_->geterror();
        throw fail(why.empty() ? std::string("OpenImageIO cannot read it") : why);
    }
    handle->channels = spec.nchannels;
    handle->width = spec.width;
    handle->height = spec.height;
    return handles_.emplace(std::move(key), std::move(handle)).first->second.get();
}

bool TextureAccess::lookup(const Handle* handle, float s, float t, float dsdx, float dtdx,
                           float dsdy, float dtdy, int first_channel, int nchannels,
                           float* out) const
{
    if (!out || nchannels <= 0)
        return false;
    const auto fail = [&] {
        std::fill(out, out + nchannels, 0.0f);
        return false;
    };
    if (!handle || !handle->oiio || first_channel < 0)
        return fail();

    OIIO::TextureOpt opt; // one per call: TextureOpt is per-lookup state
    opt.swrap = opt.twrap = options_.wrap;
    // Bilinear, not OIIO's default "smart bicubic": its B-spline is not interpolating, so a
    // magnified data map (thickness, exposure) would not return its texel values.
    opt.interpmode = OIIO::TextureOpt::InterpBilinear;
    OIIO::TextureSystem::Perthread* thread = ts_->get_perthread_info();
    if (handle->udim) {
        // OIIO picks a UDIM tile by floor(s) and floor(t), and reads t - floor(t) down the
        // tile's image. Mesh uvs (v = 1 - t, up) have their tile at floor(v) and their row at
        // 1 - (v - floor(v)) from its top.
        const float v = 1.0f - t;
        const float v0 = std::floor(v);
        t = v0 + std::min(1.0f - (v - v0), 0.99999994f);
    }

    // Only channels 0-2 (or a grey channel 0) carry colour; others pass through.
    const bool convert = !handle->to_working.is_identity() && first_channel < 3 &&
                         first_channel < handle->channels;
    if (!convert) {
        opt.firstchannel = first_channel;
        return ts_->texture(handle->oiio, thread, opt, s, t, dsdx, dtdx, dsdy, dtdy, nchannels,
                            out)
                   ? true
                   : fail();
    }

    // Converting needs the whole RGB triple: look up from channel 0, convert, then copy out
    // the requested range.
    const int end = first_channel + nchannels;
    const int span = std::max(end, std::min(3, handle->channels));
    if (span > kMaxConvertedChannels)
        return fail();
    float values[kMaxConvertedChannels];
    opt.firstchannel = 0;
    if (!ts_->texture(handle->oiio, thread, opt, s, t, dsdx, dtdx, dsdy, dtdy, span, values))
        return fail();
    if (handle->channels >= 3) {
        handle->to_working.apply(values, 1);
    } else {
        float grey[3] = {values[0], values[0], values[0]};
        handle->to_working.apply(grey, 1);
        values[0] = (grey[0] + grey[1] + grey[2]) / 3.0f;
    }
    std::copy(values + first_channel, values + end, out);
    return true;
}

std::string TextureAccess::last_error() const { return ts_->geterror(); }

}  // namespace patina
