#include "texgen/patina/stack_preview.h"

#include "core/image_io.h"
#include "texgen/flatten/flat_texel.h"

#include <tbb/parallel_for.h>

#include <stdexcept>

namespace patina::texgen {

std::vector<Imath::V3f> stack_diffuse_color(const BandStack& stack,
                                            std::span<const std::vector<float>> thickness_um,
                                            size_t texels, const BandsToRgb& to_rgb)
{
    if (thickness_um.size() != stack.layers.size())
        throw std::invalid_argument("stack_diffuse_color: one thickness map per layer");
    for (const std::vector<float>& layer : thickness_um)
        if (layer.size() != texels)
            throw std::invalid_argument("stack_diffuse_color: one thickness per texel");
    std::vector<Imath::V3f> out(texels);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, texels, 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
        std::vector<float> d(stack.layers.size());
        for (size_t i = range.begin(); i != range.end(); ++i) {
            for (size_t l = 0; l < d.size(); ++l)
                d[l] = thickness_um[l][i];
            out[i] = to_rgb(stack_diffuse(stack, d, /*keep_metal_reflection=*/true));
        }
    });
    return out;
}

void write_preview_png(const std::filesystem::path& path, std::span<const Imath::V3f> colors,
                       int width, int height, std::span<const uint8_t> covered,
                       const ColorManager& color_manager)
{
    const size_t n = static_cast<size_t>(width) * height;
    if (colors.size() != n || (!covered.empty() && covered.size() != n))
        throw std::invalid_argument("write_preview_png: sizes do not match the image");
    std::vector<float> pixels(3 * n);
    for (size_t i = 0; i < n; ++i) {
        // Mid grey (display 0.5 after encoding) where no surface is.
        const Imath::V3f c = covered.empty() || covered[i] ? colors[i] : Imath::V3f(0.214f);
        pixels[3 * i] = c.x;
        pixels[3 * i + 1] = c.y;
        pixels[3 * i + 2] = c.z;
    }
    color_manager.convert("lin_rec709", "srgb_texture", pixels.data(), n);
    write_image_atomic(path, pixels.data(), width, height, 3, {}, OIIO::TypeDesc::UINT8);
}

}  // namespace patina::texgen
