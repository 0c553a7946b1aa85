// The stack's multi-channel thickness map (texgen/patina/stack_writer.h): thickness.exr holds
// one channel per layer in layer order, stack.toml's layers name it with their `channel`,
// and the readers (flatten's stack reader) resolve the channel as the layered shader does.
#include "texgen/flatten/patina_stack_files.h"
#include "texgen/patina/material_library.h"
#include "texgen/patina/patina_domain.h"
#include "texgen/patina/stack_writer.h"
#include "texgen/stack/map_output.h"
#include "shipped_materials.h"

#include "core/image_io.h"

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <algorithm>
#include <cstring>
#include <filesystem>

namespace fs = std::filesystem;
using patina::ColorManager;
using namespace patina::texgen;

namespace {

const ColorManager& colors() { return test::repository_colors(); }
const MaterialLibrary& shipped() { return test::shipped_copper_library(); }

/// Three layers whose thickness differs per texel and per layer (layer l, texel t:
/// 0.25 (l + 1) + t / 64 µm, exact in float).
PatinaStep three_layers(size_t texels)
{
    PatinaStep step;
    step.time_years = 12;
    step.base = &shipped().at("copper");
    const char* names[3] = {"tarnish", "cuprite", "tarnish"};
    step.total_um.assign(texels, 0.0f);
    for (size_t l = 0; l < 3; ++l) {
        std::vector<float> t(texels);
        for (size_t i = 0; i < texels; ++i) {
            t[i] = 0.25f * static_cast<float>(l + 1) + static_cast<float>(i) / 64.0f;
            step.total_um[i] += t[i];
        }
        step.layers.push_back({&shipped().at(names[l]), "coat", std::move(t)});
    }
    return step;
}

}  // namespace

TEST(StackThickness, ChannelNamesSortInLayerOrder)
{
    // OpenEXR stores channels sorted by name (strcmp): the names must sort as the layers do,
    // also past 99 layers.
    const PatinaMaterial& m = shipped().at("tarnish");
    EXPECT_EQ(layer_channel_name(1, 5, m), "layer01_tarnish");
    EXPECT_EQ(layer_channel_name(1, 5, m), layer_map_name(1, m));
    for (size_t count : {5u, 99u, 120u, 1000u}) {
        std::vector<std::string> names;
        for (size_t l = 1; l <= count; ++l)
            names.push_back(layer_channel_name(l, count, m));
        EXPECT_TRUE(std::is_sorted(names.begin(), names.end(), [](const auto& a, const auto& b) {
            return std::strcmp(a.c_str(), b.c_str()) < 0;
        })) << count << " layers";
    }
}

TEST(StackThickness, OneMapHoldsEveryLayerInOrder)
{
    const int side = 8;
    const PatinaDomain domain = make_strip_domain(side, side, 0.1);
    const PatinaStep step = three_layers(domain.size());
    PatinaOutputOptions options;
    options.preview = false;
    options.script = "test.patina";
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "stack_thickness" / "stack";
    fs::remove_all(dir);
    write_patina_step(dir, step, domain, options, colors());

    const toml::table root = toml::parse_file((dir / "stack.toml").string());
    const toml::array* layers = root["patina"]["layers"].as_array();
    ASSERT_NE(layers, nullptr);
    ASSERT_EQ(layers->size(), 3u);
    const toml::array* channels = root["maps"]["thickness"]["channels"].as_array();
    ASSERT_NE(channels, nullptr);
    // The three layers, then the coverage channel every texel map ends with.
    ASSERT_EQ(channels->size(), 4u);
    EXPECT_EQ(channels->get(3)->value<std::string>(), patina::texgen::kCoverageChannel);
    EXPECT_EQ(root["maps"]["thickness"]["coverage"].value<std::string>(),
              patina::texgen::kCoverageChannel);
    EXPECT_EQ(root["maps"]["thickness"]["file"].value<std::string>(), "thickness.exr");

    // The file's channels in file order are the manifest's list, and channel l holds layer
    // l's thickness, as its own one-channel map does.
    const patina::ImageData image = patina::read_image(dir / "thickness.exr");
    ASSERT_EQ(image.channels, 4);
    EXPECT_EQ(image.channel_names[3], patina::texgen::kCoverageChannel);
    for (size_t l = 0; l < 3; ++l) {
        const toml::table& layer = *layers->get(l)->as_table();
        const std::string channel = *layer["channel"].value<std::string>();
        EXPECT_EQ(layer["map"].value<std::string>(), "thickness");
        EXPECT_EQ(channels->get(l)->value<std::string>(), channel);
        EXPECT_EQ(image.channel_names[l], channel);
        const std::string single = *layer["layer_map"].value<std::string>();
        const patina::ImageData own = patina::read_image(dir / (single + ".exr"));
        ASSERT_EQ(own.width * own.height, image.width * image.height);
        for (int y = 0; y < side; ++y)
            for (int x = 0; x < side; ++x) {
                // Texel (x, y) of the strip is node y * side + x, image row y from the top
                // or the bottom: compare against the layer's own map, which the same writer
                // orients, and against the node values as a set of exact floats.
                EXPECT_EQ(image.at(x, y, static_cast<int>(l)), own.at(x, y, 0))
                    << l << " " << x << " " << y;
            }
        std::vector<float> got, want = step.layers[l].thickness_um;
        for (size_t p = 0; p < want.size(); ++p)
            got.push_back(image.pixels[p * 4 + l]);
        std::sort(got.begin(), got.end());
        std::sort(want.begin(), want.end());
        EXPECT_EQ(got, want) << "layer " << l;
    }

    // flatten's reader resolves the layers' channels and files as the layered shader does.
    const PatinaStackFiles files = read_patina_stack(dir);
    ASSERT_EQ(files.layers.size(), 3u);
    for (size_t l = 0; l < 3; ++l) {
        EXPECT_EQ(files.layers[l].map, "thickness");
        EXPECT_EQ(files.layers[l].channel, image.channel_names[l]);
        ASSERT_EQ(files.layers[l].files.size(), 1u);
        EXPECT_EQ(files.layers[l].files[0].filename(), "thickness.exr");
    }
}

TEST(StackThickness, FlattenReaderTakesAChannelIndex)
{
    const PatinaDomain domain = make_strip_domain(4, 4, 0.1);
    PatinaOutputOptions options;
    options.preview = false;
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "stack_thickness" / "index";
    fs::remove_all(dir);
    write_patina_step(dir, three_layers(domain.size()), domain, options, colors());
    // Rewrite the layers' channels as indices into [maps.thickness].channels.
    toml::table root = toml::parse_file((dir / "stack.toml").string());
    toml::array& layers = *root["patina"]["layers"].as_array();
    for (size_t l = 0; l < layers.size(); ++l)
        layers.get(l)->as_table()->insert_or_assign("channel", static_cast<int64_t>(l));
    std::ofstream(dir / "stack.toml") << root << "\n";
    const PatinaStackFiles files = read_patina_stack(dir);
    ASSERT_EQ(files.layers.size(), 3u);
    EXPECT_EQ(files.layers[2].channel, layer_channel_name(3, 3, shipped().at("tarnish")));

    layers.get(1)->as_table()->insert_or_assign("channel", static_cast<int64_t>(7));
    std::ofstream(dir / "stack.toml") << root << "\n";
    try {
        read_patina_stack(dir);
        ADD_FAILURE() << "an index past the map's channels was accepted";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("layer 2: 'channel' 7 is not an index"), std::string::npos)
            << e.what();
    }
}
