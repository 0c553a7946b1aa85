// Texture files for other renderers, encoded in memory: PNG (8 or 16 bits per channel,
// values in [0, 1] quantised with rounding) through OpenImageIO's PNG writer.
#pragma once

#include <vector>

namespace patina::texgen {

/// The PNG file of `width` x `height` pixels of `channels` interleaved floats (row 0 at the
/// top), each clamped to [0, 1] and stored in `bits` (8 or 16) bits. Throws
/// std::runtime_error with OIIO's message when encoding fails.
std::vector<unsigned char> encode_png(const float* pixels, int width, int height, int channels,
                                      int bits);

}  // namespace patina::texgen
