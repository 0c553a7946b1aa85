#include "core/shader_library.h"

#include "core/data_files.h"

#include <algorithm>
#include <cstdlib>
#include <string>
#include <system_error>

namespace fs = std::filesystem;

namespace patina {

std::vector<fs::path> shader_library_files(std::string_view folder)
{
    std::vector<fs::path> dirs;
    for (const fs::path& dir : search_path_from_env("PATINA_SHADER_PATH"))
        dirs.push_back(dir / folder);
    std::error_code ec;
    const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
    if (!ec)
        dirs.push_back(
            (exe.parent_path() / ".." / "share" / "patina" / "shaders" / folder).lexically_normal());
    std::vector<fs::path> files;
    for (const fs::path& dir : dirs) {
        if (!fs::is_directory(dir, ec))
            continue;
        std::vector<fs::path> here;
        for (const auto& entry : fs::directory_iterator(dir, ec))
            if (entry.path().extension() == ".toml")
                here.push_back(entry.path());
        std::sort(here.begin(), here.end());
        files.insert(files.end(), here.begin(), here.end());
    }
    return files;
}

}  // namespace patina
