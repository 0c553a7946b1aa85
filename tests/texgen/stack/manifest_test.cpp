#include "texgen/stack/manifest.h"
#include "texgen/stack/map_output.h"

#include "stack_test_util.h"
#include "test_util.h"

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <fstream>
#include <sstream>

namespace patina::texgen {
namespace {

    namespace fs = std::filesystem;
    using test::rect_grid;
    using test::scratch_dir;

    MapDescription ao_map()
    {
        MapDescription map;
        map.name = "ao";
        map.channels = {"ao"};
        map.units = "1";
        map.description = "fraction of the cosine-weighted hemisphere that is unoccluded";
        map.baker = "ao";
        map.parameters = {{"samples", 64}, {"max_distance", 0.1f}, {"seed", std::string("7")}};
        return map;
    }

    std::string file_text(const fs::path& p)
    {
        std::ifstream in(p, std::ios::binary);
        std::stringstream s;
        s << in.rdbuf();
        return s.str();
    }

    TEST(Manifest, FileNames)
    {
        EXPECT_EQ(manifest_path("out"), fs::path("out") / "stack.toml");
        EXPECT_EQ(map_file_name("ao", 1001, true), "ao.exr");
        EXPECT_EQ(map_file_name("ao", 1001, false), "ao.1001.exr");
        EXPECT_EQ(map_file_name("ao", 1012, false), "ao.1012.exr");
        EXPECT_EQ(map_file_pattern("ao"), "ao.<UDIM>.exr");
    }

    TEST(Manifest, LoneTileEntryHoldsEveryField)
    {
        const fs::path dir = scratch_dir("manifest_lone");
        const std::vector<TexelGrid> tiles = {rect_grid(64, 32, {{0, 0, 4, 4}})};
        record_in_manifest(dir, ao_map(), {dir / "ao.exr"}, tiles);

        const toml::table root = toml::parse_file((dir / "stack.toml").string());
        EXPECT_EQ(root["stack"]["format"].value<int64_t>(), kStackFormatVersion);
        EXPECT_EQ(
            root["stack"]["generator"].value<std::string>().value_or("").rfind("patina-texgen ", 0),
            0u);
        const toml::node_view<const toml::node> ao = root["maps"]["ao"];
        EXPECT_EQ(ao["file"].value<std::string>(), "ao.exr");
        EXPECT_FALSE(ao["pattern"]);
        EXPECT_FALSE(ao["tiles"]);
        EXPECT_EQ(ao["domain"].value<std::string>(), "texel");
        EXPECT_EQ(ao["channels"][0].value<std::string>(), "ao");
        EXPECT_EQ(ao["channels"][1].value<std::string>(), kCoverageChannel);
        EXPECT_EQ(ao["channels"].as_array()->size(), 2u);
        EXPECT_EQ(ao["coverage"].value<std::string>(), kCoverageChannel);
        EXPECT_EQ(ao["units"].value<std::string>(), "1");
        EXPECT_EQ(ao["colorspace"].value<std::string>(), "raw");
        EXPECT_EQ(ao["baker"].value<std::string>(), "ao");
        EXPECT_EQ(ao["description"].value<std::string>(), ao_map().description);
        EXPECT_EQ(ao["resolution"][0].value<int64_t>(), 64);
        EXPECT_EQ(ao["resolution"][1].value<int64_t>(), 32);
        EXPECT_EQ(ao["parameters"]["samples"].value<int64_t>(), 64);
        // 0.1f is recorded as the decimal it was typed as, not 0.10000000149011612.
        EXPECT_EQ(ao["parameters"]["max_distance"].value<double>(), 0.1);
        EXPECT_EQ(ao["parameters"]["seed"].value<std::string>(), "7");
        for (const auto& entry : fs::directory_iterator(dir))
            EXPECT_EQ(entry.path().filename(), "stack.toml") << "left behind: " << entry.path();
    }

    TEST(Manifest, UdimEntryHasPatternAndTiles)
    {
        const fs::path dir = scratch_dir("manifest_udim");
        const std::vector<TexelGrid> tiles = {rect_grid(16, 16, {{0, 0, 4, 4}}, 1001),
                                              rect_grid(16, 16, {{0, 0, 4, 4}}, 1012)};
        record_in_manifest(dir, ao_map(), {dir / "ao.1001.exr", dir / "ao.1012.exr"}, tiles);
        const toml::table root = toml::parse_file((dir / "stack.toml").string());
        EXPECT_EQ(root["maps"]["ao"]["pattern"].value<std::string>(), "ao.<UDIM>.exr");
        EXPECT_FALSE(root["maps"]["ao"]["file"]);
        const toml::array* udims = root["maps"]["ao"]["tiles"].as_array();
        ASSERT_TRUE(udims);
        ASSERT_EQ(udims->size(), 2u);
        EXPECT_EQ((*udims)[0].value<int64_t>(), 1001);
        EXPECT_EQ((*udims)[1].value<int64_t>(), 1012);

        // Files that do not follow the pattern would send renderers to the wrong names.
        const std::string message = patina::test::message_of([&] {
            record_in_manifest(dir, ao_map(), {dir / "ao.1001.exr", dir / "other.exr"}, tiles);
        });
        EXPECT_NE(message.find("should be 'ao.1012.exr' for tile 1012"), std::string::npos)
            << message;
    }

    TEST(Manifest, MergeKeepsEarlierEntriesAndReplacesTheSameName)
    {
        const fs::path dir = scratch_dir("manifest_merge");
        {
            // A table some other tool added is kept too.
            std::ofstream out(dir / "stack.toml", std::ios::binary);
            out << "[notes]\nauthor = 'lookdev'\n";
        }
        const std::vector<TexelGrid> tiles = {rect_grid(8, 8, {{0, 0, 4, 4}})};
        record_in_manifest(dir, ao_map(), {dir / "ao.exr"}, tiles);
        MapDescription exposure = ao_map();
        exposure.name = "exposure";
        exposure.channels = {"radiant_exposure"};
        exposure.units = "J/m^2";
        exposure.baker = "exposure";
        record_in_manifest(dir, exposure, {dir / "exposure.exr"}, tiles);
        MapDescription ao2 = ao_map();
        ao2.parameters = {{"samples", 256}};
        record_in_manifest(dir, ao2, {dir / "ao.exr"}, tiles);

        const toml::table root = toml::parse_file((dir / "stack.toml").string());
        EXPECT_EQ(root["maps"].as_table()->size(), 2u);
        EXPECT_EQ(root["maps"]["exposure"]["units"].value<std::string>(), "J/m^2");
        EXPECT_EQ(root["maps"]["exposure"]["file"].value<std::string>(), "exposure.exr");
        EXPECT_EQ(root["maps"]["ao"]["parameters"]["samples"].value<int64_t>(), 256);
        // The replaced entry's old parameters are gone, not merged.
        EXPECT_FALSE(root["maps"]["ao"]["parameters"]["max_distance"]);
        EXPECT_EQ(root["notes"]["author"].value<std::string>(), "lookdev");
        EXPECT_EQ(root["stack"]["format"].value<int64_t>(), kStackFormatVersion);
    }

    TEST(Manifest, BrokenManifestIsReportedWithItsLineAndLeftAlone)
    {
        const fs::path dir = scratch_dir("manifest_broken");
        const std::string broken = "[stack]\nformat = 1\n\n[maps.ao\nfile = \"ao.exr\"\n";
        {
            std::ofstream out(dir / "stack.toml", std::ios::binary);
            out << broken;
        }
        const std::vector<TexelGrid> tiles = {rect_grid(8, 8, {{0, 0, 4, 4}})};
        const std::string message = patina::test::message_of(
            [&] { record_in_manifest(dir, ao_map(), {dir / "ao.exr"}, tiles); });
        EXPECT_NE(message.find((dir / "stack.toml").string() + ":4:"), std::string::npos)
            << message;
        EXPECT_NE(message.find("left unchanged"), std::string::npos) << message;
        EXPECT_EQ(file_text(dir / "stack.toml"), broken);
    }

    TEST(Manifest, WrongStructureOrNewerFormatIsRefused)
    {
        const fs::path dir = scratch_dir("manifest_structure");
        const std::vector<TexelGrid> tiles = {rect_grid(8, 8, {{0, 0, 4, 4}})};
        for (const auto& [text, expected] :
             {std::pair<std::string, std::string>{"maps = 3\n", ":1:8: 'maps' must be a table"},
              {"[stack]\nformat = 2\n", ":2:10: stack format 2 is newer"}}) {
            {
                std::ofstream out(dir / "stack.toml", std::ios::binary);
                out << text;
            }
            const std::string message = patina::test::message_of(
                [&] { record_in_manifest(dir, ao_map(), {dir / "ao.exr"}, tiles); });
            EXPECT_NE(message.find(expected), std::string::npos) << message;
            EXPECT_EQ(file_text(dir / "stack.toml"), text);
        }
    }

    TEST(Manifest, PerVertexEntry)
    {
        const fs::path dir = scratch_dir("manifest_vertex");
        record_in_manifest(dir, ao_map(), {dir / "statue_ao.ply"}, {});
        const toml::table root = toml::parse_file((dir / "stack.toml").string());
        EXPECT_EQ(root["maps"]["ao"]["file"].value<std::string>(), "statue_ao.ply");
        EXPECT_EQ(root["maps"]["ao"]["domain"].value<std::string>(), "vertex");
        EXPECT_FALSE(root["maps"]["ao"]["resolution"]);
    }

}  // namespace
}  // namespace patina::texgen
