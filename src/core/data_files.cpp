#include "core/data_files.h"

#include <algorithm>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <system_error>
#include <vector>

namespace fs = std::filesystem;

namespace patina {

std::vector<fs::path> search_path_from_env(const char* name)
{
    std::vector<fs::path> dirs;
    if (const char* env = std::getenv(name); env && *env) {
        const std::string s(env);
        size_t start = 0;
        while (start <= s.size()) {
            const size_t end = std::min(s.find(':', start), s.size());
            if (end > start)
                dirs.emplace_back(s.substr(start, end - start));
            start = end + 1;
        }
    }
    return dirs;
}

fs::path find_data_file(std::string_view relative)
{
    std::vector<fs::path> dirs = search_path_from_env("PATINA_DATA_PATH");
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec)
        dirs.push_back((exe.parent_path() / ".." / "share" / "patina" / "data").lexically_normal());
    std::string searched;
    for (const fs::path& dir : dirs) {
        const fs::path candidate = dir / relative;
        if (fs::is_regular_file(candidate, ec))
            return candidate;
        searched += (searched.empty() ? "" : ", ") + dir.string();
    }
    throw std::runtime_error("data file '" + std::string(relative) + "' not found (searched " +
                             (searched.empty() ? std::string("nothing") : searched) +
                             "; set PATINA_DATA_PATH to the folder holding Patina's data/)");
}

}  // namespace patina
