// A file's fingerprint: FNV-1a 64 of its bytes (Fowler, Noll, Vo), as 16 hex digits. It
// tells different files apart (a farm's parts of different scenes, plugins built
// differently); it is no defence against anyone.
#pragma once

#include <filesystem>
#include <string>
#include <string_view>

namespace patina {

/// Throws std::runtime_error naming `file` when it cannot be read.
std::string file_fingerprint(const std::filesystem::path& file);

/// The same fingerprint of `bytes` (a text that names a run's inputs, a file's contents).
std::string bytes_fingerprint(std::string_view bytes);

}  // namespace patina
