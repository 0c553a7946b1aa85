// A file format's pixels (formats/pixels.h) read and written through OpenImageIO: what
// texgen and the renderer give a format's reader and writer.
#pragma once

#include "core/image_io.h"
#include "formats/pixels.h"

namespace patina {

/// formats::PixelReader through read_image (channel names as the file has them).
class ImagePixelReader final : public formats::PixelReader {
public:
    formats::Pixels read(const std::filesystem::path& file, int subimage = 0) const override;
    int subimage_count(const std::filesystem::path& file) const override;
};

/// `pixels` written as a plain image (write_image_atomic: staged, then renamed), each
/// channel as `format`, its attributes in the header.
void write_pixels_atomic(const std::filesystem::path& path, const formats::Pixels& pixels,
                         OIIO::TypeDesc format);

/// `parts` written as one multi-part OpenEXR (each part named by its `name`, float, zip,
/// with part 0's display window), staged and renamed as write_image_atomic; `metadata`
/// joins part 0's header. `what` names the file in errors ("world volume").
void write_parts_atomic(const std::filesystem::path& path, const std::vector<formats::Pixels>& parts,
                        const Metadata& metadata, const char* what);

/// `pixels` written as a tiled, mip-mapped texture (make_texture_atomic); its attributes
/// join `options.metadata`.
void make_texture_atomic(const std::filesystem::path& path, const formats::Pixels& pixels,
                         TextureOptions options);

}  // namespace patina
