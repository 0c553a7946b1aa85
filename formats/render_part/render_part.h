// The header of a render (docs/file-formats.md "Render output"): what patina-render writes
// into every EXR it makes (src/render/film_output.cpp), what --resume reads back from a
// checkpoint, and what the farm's merge checks across the parts of a frame
// (farm/render_part.cpp): the scene and its hash, the seed, the sample range, the plugins
// and the layout of the exact sums. One writer and one reader of those keys.
#pragma once

#include "formats/pixels.h"

#include <string>

namespace patina::formats {

struct RenderHeader {
    std::string scene;        ///< patina:scene, the scene file (absolute)
    int spp = 0;              ///< patina:spp
    int sample_begin = 0;     ///< patina:sample_begin: samples [begin, end) of every pixel
    int sample_end = 0;       ///< patina:sample_end
    std::string scene_hash;   ///< patina:scene_hash (core/file_fingerprint.h)
    std::string plugins;      ///< patina:plugins (render/plugin_setup.h), or ""
    std::string sums_layout;  ///< patina:sums_layout: "xyz[ albedo][ normal][ depth]", or ""
    int seed = 0;             ///< patina:seed
    int wavelengths = 0;      ///< patina:wavelengths (hero wavelengths per path)
    int max_depth = 0;        ///< patina:max_depth
    std::string colorspace;   ///< patina:colorspace and oiio:ColorSpace: the working space
    int merged_parts = 0;     ///< patina:merged_parts: a farm's merge of that many parts (0: none)
    /// patina:display, patina:view: the OCIO display and view of the display image written
    /// beside the file (<stem>.png); empty: none was written.
    std::string display, view;

    int samples() const { return sample_end - sample_begin; }
};

/// The header's attributes in the order patina-render writes them (patina:display and
/// patina:view when there is a display image, patina:merged_parts last, when there is one).
Header render_header_attributes(const RenderHeader& header);

/// The render header in `attributes` (a file's header, any order, other keys ignored).
/// Throws std::runtime_error "no patina:<key> in its header" for a missing key a merge or a
/// resume needs (scene_hash, seed, sample_begin, sample_end), "patina:<key> is not a/an
/// <type>" for a mistyped one, and for an empty or negative sample range.
RenderHeader read_render_header(const Header& attributes);

}  // namespace patina::formats
