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
    auto need = [&](const char* key) {
        const OIIO::ParamValue* p = spec.find_attribute(key);
        if (!p)
            throw std::runtime_error(fmt::format(
                "part '{}': no {} in its header (not a patina-render part, or one written "
                "before farm renders recorded it)", file.string(), key));
        return p;
    };
    part.scene_hash = need("patina:scene_hash")->get_string();
    part.seed = need("patina:seed")->get_int();
    if (const OIIO::ParamValue* p = spec.find_attribute("patina:plugins"))
        part.plugins = p->get_string();
    part.sample_begin = need("patina:sample_begin")->get_int();
    part.sample_end = need("patina:sample_end")->get_int();
    part.full_width = spec.full_width;
    part.full_height = spec.full_height;
    part.x = spec.x;
    part.y = spec.y;
    part.width = spec.width;
    part.height = spec.height;
    part.channels.assign(spec.channelnames.begin(), spec.channelnames.end());
    part.format = spec.format;
    for (const OIIO::ParamValue& p : spec.extra_attribs) {
        const std::string name = p.name().string();
        if (name.rfind("patina:", 0) != 0 && name != "oiio:ColorSpace")
            continue;
        if (p.type() == OIIO::TypeInt)
            part.attributes.emplace_back(name, p.get_int());
        else if (p.type() == OIIO::TypeFloat)
            part.attributes.emplace_back(name, p.get_float());
        else
            part.attributes.emplace_back(name, p.get_string());
    }
    if (part.sample_end <= part.sample_begin || part.sample_begin < 0)
        throw std::runtime_error(fmt::format("part '{}': sample range {}-{} is empty",
                                             file.string(), part.sample_begin, part.sample_end));
    if (pixels) {
        part.pixels.resize(static_cast<size_t>(spec.width) * spec.height * spec.nchannels);
        if (!in->read_image(0, 0, 0, spec.nchannels, OIIO::TypeDesc::FLOAT, part.pixels.data()))
            throw std::runtime_error(fmt::format("part '{}': {}", file.string(), in->geterror()));
    }
    return part;
}

}  // namespace patina::farm
