#include "core/image_io.h"

#include "core/output_transaction.h"

#include <fstream>

#include <OpenImageIO/imagebufalgo.h>
#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <cmath>

#include <sstream>
#include <stdexcept>

namespace patina {

namespace {

    std::string oiio_error(const std::string& from_object)
    {
        std::string text = from_object.empty() ? OIIO::geterror() : from_object;
        while (!text.empty() && (text.back() == '\n' || text.back() == ' '))
            text.pop_back();
        return text.empty() ? std::string("unknown OpenImageIO error") : text;
    }

    void check_format(const std::filesystem::path& path, OIIO::TypeDesc format)
    {
        if (format != OIIO::TypeDesc::HALF && format != OIIO::TypeDesc::FLOAT &&
            format != OIIO::TypeDesc::UINT8 && format != OIIO::TypeDesc::UINT16)
            throw std::runtime_error(fmt::format(
                "cannot write image '{}': pixel format {} is not one of half, float, uint8, uint16",
                path.string(), format.c_str()));
    }

    OIIO::ImageSpec make_spec(const std::filesystem::path& path, int width, int height,
                              int channels, const std::vector<std::string>& channel_names,
                              OIIO::TypeDesc format)
    {
        if (width <= 0 || height <= 0 || channels <= 0)
            throw std::runtime_error(fmt::format("cannot write image '{}': invalid size {}x{} with {} channels",
                                                 path.string(), width, height, channels));
        if (!channel_names.empty() && static_cast<int>(channel_names.size()) != channels)
            throw std::runtime_error(fmt::format("cannot write image '{}': {} channel names for {} channels",
                                                 path.string(), channel_names.size(), channels));
        OIIO::ImageSpec spec(width, height, channels, format);
        if (!channel_names.empty())
            spec.channelnames = channel_names;
        return spec;
    }

}  // namespace

void add_metadata(OIIO::ImageSpec& spec, const Metadata& metadata)
{
    for (const auto& [key, value] : metadata)
        std::visit([&, &k = key](const auto& v) { spec.attribute(k, v); }, value);
}

Metadata metadata_of(const OIIO::ImageSpec& spec)
{
    Metadata out;
    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        const std::string name = p.name().string();
        if (p.type() == OIIO::TypeInt)
            out.emplace_back(name, p.get_int());
        else if (p.type() == OIIO::TypeFloat)
            out.emplace_back(name, p.get_float());
        else
            out.emplace_back(name, p.get_string());
    }
    return out;
}

void write_file_atomic(const std::filesystem::path& path,
                       std::initializer_list<std::string_view> parts, std::string_view what)
{
    StagedOutput staged(path);
    bool ok = false;
    {
        std::ofstream out(staged.path(), std::ios::binary | std::ios::trunc);
        if (out) {
            for (const std::string_view part : parts)
                out.write(part.data(), static_cast<std::streamsize>(part.size()));
            out.flush();
            ok = static_cast<bool>(out);
        }
    }
    if (!ok)
        throw std::runtime_error(fmt::format("cannot write {} '{}': write failed", what, path.string()));
    staged.done();
}

void write_image_atomic(const std::filesystem::path& path, const float* pixels, int width,
                        int height, int channels,
                        const std::vector<std::string>& channel_names,
                        OIIO::TypeDesc format, const Metadata& metadata,
                        const ImageWindow* window, const UintPart* second)
{
    check_format(path, format);
    if (!pixels)
        throw std::runtime_error(fmt::format("cannot write image '{}': no pixels", path.string()));
    OIIO::ImageSpec spec = make_spec(path, width, height, channels, channel_names, format);
    add_metadata(spec, metadata);
    if (channels == 4 && channel_names.empty())
        spec.alpha_channel = 3;
    if (window) {
        spec.x = window->x;
        spec.y = window->y;
        spec.full_x = spec.full_y = 0;
        spec.full_width = window->full_width;
        spec.full_height = window->full_height;
    }

    // The writer is chosen from the final name: the temporary name has no image extension.
    auto out = OIIO::ImageOutput::create(path.string());
    if (!out)
        throw std::runtime_error(fmt::format("cannot write image '{}': {}", path.string(), oiio_error("")));
    StagedOutput staged(path);
    bool ok = false;
    if (!second) {
        ok = out->open(staged.path().string(), spec) &&
             out->write_image(OIIO::TypeDesc::FLOAT, pixels);
    } else {
        if (!out->supports("multiimage") || !second->pixels)
            throw std::runtime_error(fmt::format("cannot write image '{}': a second part needs "
                                                 "OpenEXR", path.string()));
        OIIO::ImageSpec part(spec.width, spec.height, static_cast<int>(second->channels.size()),
                             OIIO::TypeDesc::UINT32);
        part.channelnames = second->channels;
        part.x = spec.x;
        part.y = spec.y;
        part.full_x = spec.full_x;
        part.full_y = spec.full_y;
        part.full_width = spec.full_width;
        part.full_height = spec.full_height;
        part.attribute("name", second->name);
        part.attribute("compression", "zip");
        if (spec.get_string_attribute("name").empty())
            spec.attribute("name", "rgba");
        const OIIO::ImageSpec specs[2] = {spec, part};
        ok = out->open(staged.path().string(), 2, specs) &&
             out->write_image(OIIO::TypeDesc::FLOAT, pixels) &&
             out->open(staged.path().string(), specs[1], OIIO::ImageOutput::AppendSubimage) &&
             out->write_image(OIIO::TypeDesc::UINT32, second->pixels);
    }
    ok = out->close() && ok;
    if (!ok)
        throw std::runtime_error(fmt::format("cannot write image '{}': {}", path.string(),
                                             oiio_error(out->geterror())));
    out.reset();
    staged.done();
}

void make_texture_atomic(const std::filesystem::path& path, const OIIO::ImageBuf& image,
                         const TextureOptions& options)
{
    if (options.format != OIIO::TypeDesc::HALF && options.format != OIIO::TypeDesc::FLOAT)
        throw std::runtime_error(fmt::format("cannot make texture '{}': format must be half or float, not {}",
                                             path.string(), options.format.c_str()));
    if (options.tile_size <= 0)
        throw std::runtime_error(fmt::format("cannot make texture '{}': tile size {} must be positive",
                                             path.string(), options.tile_size));
    if (image.has_error() || image.spec().width <= 0)
        throw std::runtime_error(fmt::format("cannot make texture '{}': invalid input image: {}",
                                             path.string(), image.geterror()));

    OIIO::ImageSpec config;
    config.format = options.format;
    config.tile_width = config.tile_height = options.tile_size;
    config.tile_depth = 1;
    config.attribute("compression", options.compression);
    config.attribute("wrapmodes", options.wrap + "," + options.wrap);
    // The temporary name has no .exr extension: name the format explicitly.
    config.attribute("maketx:fileformatname", "openexr");
    if (!options.mip_filter.empty())
        config.attribute("maketx:filtername", options.mip_filter);
    add_metadata(config, options.metadata);

    StagedOutput staged(path, options.outside_the_run);
    std::ostringstream log;
    if (!OIIO::ImageBufAlgo::make_texture(OIIO::ImageBufAlgo::MakeTxTexture, image,
                                          staged.path().string(), config, &log)) {
        std::string text = oiio_error("");
        if (text == "unknown OpenImageIO error" && !log.str().empty())
            text = log.str();
        throw std::runtime_error(fmt::format("cannot make texture '{}': {}", path.string(), text));
    }
    staged.done();
}

void make_texture_atomic(const std::filesystem::path& path, const float* pixels, int width,
                         int height, int channels,
                         const std::vector<std::string>& channel_names,
                         const TextureOptions& options)
{
    if (!pixels)
        throw std::runtime_error(fmt::format("cannot make texture '{}': no pixels", path.string()));
    const OIIO::ImageSpec spec =
        make_spec(path, width, height, channels, channel_names, OIIO::TypeDesc::FLOAT);
    OIIO::ImageBuf buf(spec);
    if (!buf.set_pixels(buf.roi(), OIIO::TypeDesc::FLOAT, pixels))
        throw std::runtime_error(fmt::format("cannot make texture '{}': {}", path.string(), buf.geterror()));
    make_texture_atomic(path, buf, options);
}

namespace {

    /// Every pixel of the current subimage of `in` as float; errors begin with `what`.
    ImageData read_all(OIIO::ImageInput& in, const std::string& what)
    {
        const OIIO::ImageSpec& spec = in.spec();
        ImageData image;
        image.width = spec.width;
        image.height = spec.height;
        image.channels = spec.nchannels;
        image.channel_names = spec.channelnames;
        for (const OIIO::ParamValue& p : spec.extra_attribs)
            image.metadata.emplace_back(p.name().string(), p.get_string());
        image.pixels.resize(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
        if (!in.read_image(in.current_subimage(), 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT,
                           image.pixels.data()))
            throw std::runtime_error(fmt::format("{}: {}", what, oiio_error(in.geterror())));
        return image;
    }

}  // namespace

ImageData read_image(const std::filesystem::path& path, int subimage)
{
    std::error_code ec;
    if (!std::filesystem::exists(path, ec))
        throw std::runtime_error(fmt::format("cannot read image '{}': file not found", path.string()));
    auto in = OIIO::ImageInput::open(path.string());
    if (!in)
        throw std::runtime_error(fmt::format("cannot read image '{}': {}", path.string(), oiio_error("")));
    if (subimage != 0 && !in->seek_subimage(subimage, 0))
        throw std::runtime_error(fmt::format("cannot read part {} of '{}': the file has no such part",
                                             subimage, path.string()));
    return read_all(*in, fmt::format("cannot read image '{}'", path.string()));
}

ImageData read_image(std::span<const unsigned char> bytes, const std::string& format,
                     const std::string& name)
{
    const std::string what = fmt::format("cannot read image '{}'", name);
    OIIO::Filesystem::IOMemReader proxy(bytes.data(), bytes.size());
    // OIIO picks the reader by the name's extension and, when that one does not know the
    // bytes, asks the others (ImageInput::create): an empty or wrong hint still reads.
    auto in = OIIO::ImageInput::open("embedded." + (format.empty() ? std::string("png") : format),
                                     nullptr, &proxy);
    if (!in)
        throw std::runtime_error(fmt::format("{} ({} bytes, format '{}'): {}", what, bytes.size(),
                                             format, oiio_error("")));
    return read_all(*in, what);
}

void check_finite_texels(const std::filesystem::path& path, const char* what)
{
    OIIO::ImageBuf buf(path.string());
    if (!buf.read(0, 0, true, OIIO::TypeDesc::FLOAT))
        throw std::runtime_error(fmt::format("{} '{}': {}", what, path.string(), buf.geterror()));
    const OIIO::ImageBufAlgo::PixelStats stats = OIIO::ImageBufAlgo::computePixelStats(buf);
    uint64_t bad = 0;
    for (size_t c = 0; c < stats.nancount.size(); ++c)
        bad += stats.nancount[c] + stats.infcount[c];
    if (bad == 0)
        return;
    // Name the first bad texel (top-left origin, as image viewers show it).
    const OIIO::ImageSpec& spec = buf.spec();
    std::vector<float> px(static_cast<size_t>(spec.nchannels));
    for (int y = spec.y; y < spec.y + spec.height; ++y)
        for (int x = spec.x; x < spec.x + spec.width; ++x) {
            buf.getpixel(x, y, px.data(), spec.nchannels);
            for (int c = 0; c < spec.nchannels; ++c)
                if (!std::isfinite(px[static_cast<size_t>(c)]))
                    throw std::runtime_error(fmt::format(
                        "{} '{}': texel ({}, {}) channel {} is {} ({} non-finite values)", what,
                        path.string(), x, y, spec.channel_name(c),
                        std::isnan(px[static_cast<size_t>(c)]) ? "NaN" : "infinite", bad));
        }
    throw std::runtime_error(fmt::format("{} '{}': {} non-finite values", what, path.string(), bad));
}

}  // namespace patina
