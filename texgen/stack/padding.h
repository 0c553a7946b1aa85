// Padding across UV seams: the texels no triangle covers get plausible values pulled from
// the covered texels around them (OIIO's push-pull hole filling), so that the mip levels of
// a map, which average blocks of texels, do not blend the background into the surface.
#pragma once

#include <cstdint>
#include <vector>

namespace patina::texgen {

/// Chebyshev (chessboard) distance in texels from every texel to the nearest covered one:
/// max(|dx|, |dy|), 0 on covered texels, capped at `limit` (also the value when nothing is
/// covered). `covered` is per texel, row-major, width x height.
std::vector<int> distance_to_covered(const std::vector<uint8_t>& covered, int width, int height,
                                     int limit);

/// Fill the uncovered texels of `pixels` (width x height texels of `channels` interleaved
/// floats, row-major; all values finite) by push-pull (ImageBufAlgo::fillholes_pushpull on
/// the values with an alpha of 1 on covered texels and 0 elsewhere, so premultiplied values
/// are the values themselves and 0), then set back to 0 every texel farther than `margin`
/// texels from every covered texel, measured as the Chebyshev distance. `margin` = -1
/// keeps the whole fill; 0 only zeroes the uncovered texels. Covered texels keep their exact
/// bits.
///
/// Why Chebyshev: mip level k of a power-of-two map averages blocks of 2^k x 2^k texels, and
/// every texel of a block lies within Chebyshev distance 2^k - 1 of any other, so a margin
/// of m keeps the background out of every level with 2^k - 1 <= m along the seams.
void pad_texels(std::vector<float>& pixels, int width, int height, int channels,
                const std::vector<uint8_t>& covered, int margin);

}  // namespace patina::texgen
