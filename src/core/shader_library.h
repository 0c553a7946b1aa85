// Where the shader library's files are: the TOML files of one folder of `shaders/` (patina
// materials, fading materials), searched along $PATINA_SHADER_PATH and then beside the
// executable (<exe>/../share/patina/shaders, the build and install trees alike).
#pragma once

#include <filesystem>
#include <string_view>
#include <vector>

namespace patina {

/// Every `*.toml` in `<dir>/<folder>` for each directory of $PATINA_SHADER_PATH (colon
/// separated, in order), then in `<exe>/../share/patina/shaders/<folder>`; sorted by name
/// within a directory. Missing directories are skipped.
std::vector<std::filesystem::path> shader_library_files(std::string_view folder);

}  // namespace patina
