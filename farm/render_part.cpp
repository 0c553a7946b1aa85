#include "farm/render_part.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <stdexcept>

namespace patina::farm {

RenderPart read_render_part(const std::filesystem::path& file, bool pixels)
{
    auto in = OIIO::ImageInput::open(file.string());
    if (!in)
        throw std::runtime_error(fmt::format("part '{}': {}", file.string(), OIIO::geterror()));
    const OIIO::ImageSpec& spec = in->spec();
    RenderPart part;
    part.file = file;
    const Metadata header = metadata_of(spec);
    try {
        part.header = formats::read_render_header(header);
    } catch (const std::exception& e) {
        throw std::runtime_error(fmt::format("part '{}': {} (not a patina-render part, or one "
                                             "written before farm renders recorded it)",
                                             file.string(), e.what()));
    }
    part.full_width = spec.full_width;
    part.full_height = spec.full_height;
    part.x = spec.x;
    part.y = spec.y;
    part.width = spec.width;
    part.height = spec.height;
    part.channels.assign(spec.channelnames.begin(), spec.channelnames.end());
    part.format = spec.format;
    for (const auto& [name, value] : header)
        if (name.rfind("patina:", 0) == 0 || name == "oiio:ColorSpace")
            part.attributes.emplace_back(name, value);
    if (pixels) {
        part.pixels.resize(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, part.pixels.data()))
            throw std::runtime_error(fmt::format("part '{}': {}", file.string(), in->geterror()));
    }
    return part;
}

}  // namespace patina::farm
