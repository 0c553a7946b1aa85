// Each file's names have one home, the file-format library (docs/file-formats.md): no
// source outside formats/ spells a channel, map or header key of a file another component
// reads. A reader or writer that spelled one again would drift from the format's own.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace patina {
namespace {

namespace fs = std::filesystem;

/// The names, quoted as code would spell them, and the header that owns each.
const std::vector<std::pair<std::string, std::string>> kOwned = {
    {"\"R_bottom\"", "formats/fade_stack/fade_stack.h"},
    {"\"R_top\"", "formats/fade_stack/fade_stack.h"},
    {"\"R_total\"", "formats/fade_stack/fade_stack.h"},
    {"\"coordinate\"", "formats/fade_stack/fade_stack.h"},
    {"\"patina:scene_hash\"", "formats/render_part/render_part.h"},
    {"\"patina:sample_begin\"", "formats/render_part/render_part.h"},
    {"\"patina:sample_end\"", "formats/render_part/render_part.h"},
    {"\"patina:sums_layout\"", "formats/render_part/render_part.h"},
    {"\"patina:merged_parts\"", "formats/render_part/render_part.h"},
    {"\"patina:display\"", "formats/render_part/render_part.h"},
    {"\"gltf_base_color\"", "formats/texture_stack/texture_stack.h"},
    {"\"gltf_metallic_roughness\"", "formats/texture_stack/texture_stack.h"},
    {"\"gltf_clearcoat\"", "formats/texture_stack/texture_stack.h"},
    {"\"diffuse_albedo\"", "formats/texture_stack/texture_stack.h"},
};

TEST(OneHome, NoSourceOutsideTheFormatLibrarySpellsAFormatsNames)
{
    const fs::path root = PATINA_SOURCE_DIR;
    std::vector<std::string> found;
    size_t files = 0;
    for (const char* tree : {"src", "texgen", "plugins", "farm", "include"})
        for (const auto& entry : fs::recursive_directory_iterator(root / tree)) {
            const fs::path& p = entry.path();
            if (!entry.is_regular_file() || (p.extension() != ".cpp" && p.extension() != ".h"))
                continue;
            ++files;
            std::ifstream in(p);
            std::string line;
            for (int number = 1; std::getline(in, line); ++number) {
                const std::string code = line.substr(0, line.find("//"));
                for (const auto& [name, home] : kOwned)
                    if (code.find(name) != std::string::npos)
                        found.push_back(fs::relative(p, root).string() + ":" +
                                        std::to_string(number) + ": " + name + " belongs to " +
                                        home);
            }
        }
    EXPECT_GT(files, 300u) << "the source tree was not found at " << root;
    std::ostringstream list;
    for (const std::string& f : found)
        list << "\n  " << f;
    EXPECT_TRUE(found.empty()) << found.size() << " spelling(s) outside formats/:" << list.str();
}

}  // namespace
}  // namespace patina
