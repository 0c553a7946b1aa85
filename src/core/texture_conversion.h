// Textures in a colour space other than the working space are converted once, at load, into
// a cached working-space texture (like maketx / txmake), so that filtering and mip-mapping
// happen on linear working-space values.
#pragma once

#include "core/color_management.h"

#include <filesystem>
#include <string_view>

namespace patina {

/// Folder of converted textures: $PATINA_TEXTURE_CACHE, else $XDG_CACHE_HOME/patina/textures,
/// else $HOME/.cache/patina/textures, else <temp>/patina-textures.
std::filesystem::path texture_cache_dir();

/// The working-space version of `file` declared in `colorspace`: a tiled, mip-mapped float
/// EXR in texture_cache_dir(), named by a hash of the file's path, size, modification time,
/// the colour space, the working space and the OCIO config, made on first use (written under
/// a temporary name, then renamed, so concurrent renders on a farm share it safely).
/// Channels 0-2 (or a grey channel 0, as R = G = B) are converted; others are copied.
/// Throws std::runtime_error naming the file.
std::filesystem::path converted_texture(const std::filesystem::path& file,
                                        std::string_view colorspace, const ColorManager& colors);

}  // namespace patina
