#include "texgen/export/png_encode.h"

#include <OpenImageIO/filesystem.h>
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <stdexcept>
#include <string>

namespace patina::texgen {

std::vector<unsigned char> encode_png(const float* pixels, int width, int height, int channels,
                                      int bits)
{
    if (bits != 8 && bits != 16)
        throw std::invalid_argument("encode_png: bits must be 8 or 16");
    const size_t count = static_cast<size_t>(width) * height * channels;
    // Quantise here (round to nearest), so the bytes do not depend on OIIO's own rounding.
    const double top = bits == 8 ? 255.0 : 65535.0;
    std::vector<uint16_t> wide;
    std::vector<uint8_t> narrow;
    if (bits == 8)
        narrow.resize(count);
    else
        wide.resize(count);
    for (size_t i = 0; i < count; ++i) {
        const double v = std::isfinite(pixels[i]) ? std::clamp<double>(pixels[i], 0.0, 1.0) : 0.0;
        const auto q = static_cast<uint32_t>(v * top + 0.5);  // v >= 0: round half up
        if (bits == 8)
            narrow[i] = static_cast<uint8_t>(q);
        else
            wide[i] = static_cast<uint16_t>(q);
    }

    std::vector<unsigned char> bytes;
    OIIO::Filesystem::IOVecOutput proxy(bytes);
    auto out = OIIO::ImageOutput::create("png");
    if (!out)
        throw std::runtime_error("cannot encode PNG: " + OIIO::geterror());
    const OIIO::TypeDesc type = bits == 8 ? OIIO::TypeDesc::UINT8 : OIIO::TypeDesc::UINT16;
    OIIO::ImageSpec spec(width, height, channels, type);
    // zlib level 3 with libpng's Sub filter on every row (16 = PNG_FILTER_SUB): on the urban
    // series at 2048² (bench/export_vs_grow.sh) 88.6 MB and 19 s, where level 6 with the
    // adaptive filter choice took 93.2 MB and 34 s, and level 3 adaptive 99.6 MB and 24 s.
    spec.attribute("png:compressionLevel", 3);
    // A fourth channel is data (a mask map's smoothness), not an alpha to premultiply by:
    // the values are written as they are.
    spec.attribute("oiio:UnassociatedAlpha", 1);
    spec.attribute("png:filter", 16);
    out->set_ioproxy(&proxy);
    const void* data = bits == 8 ? static_cast<const void*>(narrow.data()) : wide.data();
    if (!out->open("memory.png", spec) || !out->write_image(type, data) || !out->close())
        throw std::runtime_error("cannot encode PNG: " + out->geterror());
    return bytes;
}

}  // namespace patina::texgen
