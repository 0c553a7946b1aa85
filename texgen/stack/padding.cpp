#include "texgen/stack/padding.h"

#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>
#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace patina::texgen {

std::vector<int> distance_to_covered(const std::vector<uint8_t>& covered, int width, int height,
                                     int limit)
{
    const size_t n = static_cast<size_t>(width) * height;
    if (covered.size() != n)
        throw std::runtime_error(
            fmt::format("distance_to_covered: {} coverage flags for {}x{} texels", covered.size(),
                        width, height));
    std::vector<int> d(n);
    for (size_t i = 0; i < n; ++i)
        d[i] = covered[i] ? 0 : limit;
    // Two-pass chamfer transform with unit weights on all 8 neighbours, which is exact for
    // the chessboard metric (Rosenfeld & Pfaltz 1966). The forward pass looks at the
    // neighbours already visited (up-left, up, up-right, left), the backward pass at the rest.
    auto at = [&](int x, int y) -> int& { return d[static_cast<size_t>(y) * width + x]; };
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) {
            int v = at(x, y);
            if (x > 0)
                v = std::min(v, at(x - 1, y) + 1);
            if (y > 0) {
                v = std::min(v, at(x, y - 1) + 1);
                if (x > 0)
                    v = std::min(v, at(x - 1, y - 1) + 1);
                if (x + 1 < width)
                    v = std::min(v, at(x + 1, y - 1) + 1);
            }
            at(x, y) = v;
        }
    for (int y = height - 1; y >= 0; --y)
        for (int x = width - 1; x >= 0; --x) {
            int v = at(x, y);
            if (x + 1 < width)
                v = std::min(v, at(x + 1, y) + 1);
            if (y + 1 < height) {
                v = std::min(v, at(x, y + 1) + 1);
                if (x + 1 < width)
                    v = std::min(v, at(x + 1, y + 1) + 1);
                if (x > 0)
                    v = std::min(v, at(x - 1, y + 1) + 1);
            }
            at(x, y) = std::min(v, limit);
        }
    return d;
}

void pad_texels(std::vector<float>& pixels, int width, int height, int channels,
                const std::vector<uint8_t>& covered, int margin)
{
    if (width <= 0 || height <= 0 || channels <= 0)
        throw std::runtime_error(fmt::format("pad_texels: invalid size {}x{} with {} channels",
                                             width, height, channels));
    const size_t n = static_cast<size_t>(width) * height;
    const size_t nc = static_cast<size_t>(channels);
    if (pixels.size() != n * nc || covered.size() != n)
        throw std::runtime_error(fmt::format(
            "pad_texels: {} values and {} coverage flags for {}x{} texels of {} channels",
            pixels.size(), covered.size(), width, height, channels));
    if (margin < -1)
        throw std::runtime_error(
            fmt::format("padding margin {} must be -1 (fill all) or >= 0", margin));

    // A tile the surface covers entirely (a flat strip) has no hole to fill.
    if (std::all_of(covered.begin(), covered.end(), [](uint8_t c) { return c != 0; }))
        return;
    const bool any_covered =
        std::any_of(covered.begin(), covered.end(), [](uint8_t c) { return c != 0; });
    if (margin == 0 || !any_covered) {
        // Nothing to pull from, or no padding asked for: the background is 0.
        for (size_t t = 0; t < n; ++t)
            if (!covered[t])
                std::fill_n(pixels.begin() + static_cast<std::ptrdiff_t>(t * nc), nc, 0.0f);
        return;
    }

    // Premultiplied values with alpha as the last channel: alpha 1 keeps a texel, alpha 0 is
    // a hole (fillholes_pushpull fills every alpha < 1).
    OIIO::ImageSpec spec(width, height, channels + 1, OIIO::TypeDesc::FLOAT);
    spec.alpha_channel = channels;
    OIIO::ImageBuf src(spec);
    std::vector<float> rgba(n * (nc + 1));
    for (size_t t = 0; t < n; ++t) {
        float* px = &rgba[t * (nc + 1)];
        const bool in = covered[t] != 0;
        for (size_t c = 0; c < nc; ++c)
            px[c] = in ? pixels[t * nc + c] : 0.0f;
        px[nc] = in ? 1.0f : 0.0f;
    }
    if (!src.set_pixels(src.roi(), OIIO::TypeDesc::FLOAT, rgba.data()))
        throw std::runtime_error(fmt::format("padding: {}", src.geterror()));
    OIIO::ImageBuf filled;
    if (!OIIO::ImageBufAlgo::fillholes_pushpull(filled, src))
        throw std::runtime_error(
            fmt::format("padding: push-pull fill failed: {}", filled.geterror()));
    if (!filled.get_pixels(filled.roi(), OIIO::TypeDesc::FLOAT, rgba.data()))
        throw std::runtime_error(fmt::format("padding: {}", filled.geterror()));

    // Keep the fill within the margin; covered texels are copied back untouched (the
    // compositing inside push-pull computes v + 0 * fill, which need not give v's bits).
    const std::vector<int> distance =
        margin < 0 ? std::vector<int>() : distance_to_covered(covered, width, height, margin + 1);
    for (size_t t = 0; t < n; ++t) {
        if (covered[t])
            continue;
        const bool keep = margin < 0 || distance[t] <= margin;
        for (size_t c = 0; c < nc; ++c)
            pixels[t * nc + c] = keep ? rgba[t * (nc + 1) + c] : 0.0f;
    }
}

}  // namespace patina::texgen
