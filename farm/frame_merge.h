// `patina-farm merge`: the parts a farm returns for one frame — tiles or crops (disjoint
// pixels) and sample ranges (disjoint samples of the same pixels) — checked against each
// other and merged into one EXR: tiles bitwise as they were rendered, sample ranges as the
// mean of their means weighted by their sample counts.
#pragma once

#include "farm/render_part.h"

#include <filesystem>
#include <vector>

namespace patina::farm {

struct MergeResult {
    size_t parts = 0;
    int sample_begin = 0, sample_end = 0;   ///< the merged samples [begin, end)
    int x = 0, y = 0, width = 0, height = 0;  ///< the merged pixels inside the frame
};

/// Merges `parts` into `output` (written under a temporary name and renamed; its header
/// holds the total sample count as patina:spp and the range as patina:sample_begin/end).
/// Refuses, naming the files: parts of different scenes (patina:scene_hash), seeds,
/// plugins (patina:plugins), frame sizes or channels; sample ranges with a gap or an overlap; two parts of one sample range
/// sharing a pixel; a sample range that lacks pixels the others have; pixels that leave a
/// hole in the merged rectangle.
MergeResult merge_render_parts(const std::vector<std::filesystem::path>& parts,
                               const std::filesystem::path& output);

}  // namespace patina::farm
