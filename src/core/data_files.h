// Where Patina's shipped reference tables are (lamp spectra, measured reflectances): the
// repository's `data/` folder, copied to <exe>/../share/patina/data in the build and install
// trees alike, searched after the directories of $PATINA_DATA_PATH.
#pragma once

#include <filesystem>
#include <string_view>

#include <vector>

namespace patina {

/// The directories of a colon-separated search path in the environment variable `name`
/// (empty entries skipped; none when it is unset).
std::vector<std::filesystem::path> search_path_from_env(const char* name);

/// The first existing `<dir>/<relative>` for each directory of $PATINA_DATA_PATH (colon
/// separated, in order), then `<exe>/../share/patina/data/<relative>`. Throws
/// std::runtime_error naming the file and the places searched when there is none.
std::filesystem::path find_data_file(std::string_view relative);

}  // namespace patina
