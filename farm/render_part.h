// One part of a render as a farm returns it: an EXR patina-render wrote for a tile, a crop
// or a sample range of a frame (render/film_output.cpp), with the header fields a merge
// checks. The one reader of those EXRs' farm fields.
#pragma once

#include "core/image_io.h"
#include "formats/render_part/render_part.h"

#include <OpenImageIO/typedesc.h>

#include <filesystem>
#include <string>
#include <vector>

namespace patina::farm {

struct RenderPart {
    std::filesystem::path file;
    formats::RenderHeader header;    ///< its render header (formats/render_part/render_part.h)
    int full_width = 0, full_height = 0;   ///< the frame (the display window)
    int x = 0, y = 0, width = 0, height = 0;  ///< the pixels it holds (the data window)
    std::vector<std::string> channels;  ///< in the file's order
    std::vector<float> pixels;          ///< width x height x channels, row 0 at y
    OIIO::TypeDesc format;              ///< the pixel type in the file (float or half)
    /// The header's patina:* attributes and its colour space, copied into the merged file.
    Metadata attributes;

    int samples() const { return header.samples(); }
};

/// Read `file`'s header (and its pixels when `pixels`). Throws std::runtime_error naming
/// the file when it is unreadable or its render header lacks a field a merge needs (a
/// render written before the fields existed: patina:scene_hash, patina:sample_begin,
/// patina:sample_end).
RenderPart read_render_part(const std::filesystem::path& file, bool pixels = true);

}  // namespace patina::farm
