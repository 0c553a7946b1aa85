#include "core/pixel_io.h"

#include "core/output_transaction.h"

#include <OpenImageIO/imageio.h>
#include <fmt/format.h>

#include <stdexcept>

namespace patina {

formats::Pixels ImagePixelReader::read(const std::filesystem::path& file, int subimage) const
{
    ImageData image = read_image(file, subimage);
    formats::Pixels p;
    p.width = image.width;
    p.height = image.height;
    p.channels = image.channels;
    p.channel_names = std::move(image.channel_names);
    p.values = std::move(image.pixels);
    return p;
}

void write_pixels_atomic(const std::filesystem::path& path, const formats::Pixels& pixels,
                         OIIO::TypeDesc format)
{
    write_image_atomic(path, pixels.values.data(), pixels.width, pixels.height, pixels.channels,
                       pixels.channel_names, format, pixels.attributes);
}

void write_parts_atomic(const std::filesystem::path& path, const std::vector<formats::Pixels>& parts,
                        const Metadata& metadata, const char* what)
{
    StagedOutput staged(path);
    const std::string tmp = staged.path().string();
    auto fail = [&](const std::string& msg) {
        throw std::runtime_error(fmt::format("cannot write {} '{}': {}", what, path.string(), msg));
    };
    std::vector<OIIO::ImageSpec> specs;
    for (const formats::Pixels& p : parts) {
        OIIO::ImageSpec spec(p.width, p.height, p.channels, OIIO::TypeDesc::FLOAT);
        spec.channelnames = p.channel_names;
        if (!p.name.empty())
            spec.attribute("name", p.name);
        spec.attribute("compression", "zip");
        add_metadata(spec, p.attributes);
        if (!specs.empty()) {
            spec.full_x = specs[0].full_x;
            spec.full_y = specs[0].full_y;
            spec.full_width = specs[0].full_width;
            spec.full_height = specs[0].full_height;
        } else {
            add_metadata(spec, metadata);
        }
        specs.push_back(std::move(spec));
    }
    auto out = OIIO::ImageOutput::create("openexr");
    if (!out)
        fail(OIIO::geterror());
    if (!out->supports("multiimage"))
        fail("the EXR writer does not support multi-part files");
    if (!out->open(tmp, static_cast<int>(specs.size()), specs.data()))
        fail(out->geterror());
    for (size_t p = 0; p < specs.size(); ++p) {
        if (p > 0 && !out->open(tmp, specs[p], OIIO::ImageOutput::AppendSubimage))
            fail(out->geterror());
        if (!out->write_image(OIIO::TypeDesc::FLOAT, parts[p].values.data()))
            fail(out->geterror());
    }
    if (!out->close())
        fail(out->geterror());
    staged.done();
}

int ImagePixelReader::subimage_count(const std::filesystem::path& file) const
{
    auto in = OIIO::ImageInput::open(file.string());
    if (!in)
        return 0;
    int count = 0;
    while (in->seek_subimage(count, 0))
        ++count;
    return count;
}

void make_texture_atomic(const std::filesystem::path& path, const formats::Pixels& pixels,
                         TextureOptions options)
{
    for (const auto& entry : pixels.attributes)
        options.metadata.push_back(entry);
    make_texture_atomic(path, pixels.values.data(), pixels.width, pixels.height, pixels.channels,
                        pixels.channel_names, options);
}

}  // namespace patina
