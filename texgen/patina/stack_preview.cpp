#include "texgen/patina/stack_preview.h"

#include "core/image_io.h"

#include <patina/shading/layer_stack.h>

#include <tbb/parallel_for.h>

#include <stdexcept>

namespace patina::texgen {

std::vector<Imath::V3f> stack_diffuse_color(const PatinaMaterial& base,
                                            std::span<const PreviewLayer> bottom_to_top,
                                            size_t texels)
{
    for (const PreviewLayer& layer : bottom_to_top)
        if (!layer.material || layer.thickness_um.size() != texels)
            throw std::invalid_argument("stack_diffuse_color: every layer needs a material "
                                        "and one thickness per texel");
    std::vector<Imath::V3f> out(texels);
    using shading::simd::V4;
    auto lanes = [](const Imath::V3f& v) { return V4{v.x, v.y, v.z, 0.0f}; };
    tbb::parallel_for(tbb::blocked_range<size_t>(0, texels, 4096),
                      [&](const tbb::blocked_range<size_t>& range) {
        for (size_t i = range.begin(); i != range.end(); ++i) {
            // The stack's model (patina/shading/layer_stack.h), walked from the top down in
            // linear Rec.709 lanes; the whole reflectance over the base, a metal's included:
            // a preview shows what the surface looks like.
            shading::LayersAbove<V4> above;
            for (size_t l = bottom_to_top.size(); l-- > 0;) {
                const PreviewLayer& layer = bottom_to_top[l];
                above.add(lanes(layer.material->absorption), lanes(layer.material->scattering),
                          layer.thickness_um[i]);
            }
            const V4 r = above.diffuse_over(lanes(base.color), false);
            out[i] = Imath::V3f(r[0], r[1], r[2]);
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
