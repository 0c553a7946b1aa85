// The render header (formats/render_part/render_part.h): what patina-render writes, --resume
// and the farm's merge read back, round-tripped, and the refusals.
#include "formats/render_part/render_part.h"

#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>

namespace patina::formats {
namespace {

RenderHeader example()
{
    RenderHeader h;
    h.scene = "/shots/a/scene.toml";
    h.spp = 64;
    h.sample_begin = 64;
    h.sample_end = 128;
    h.scene_hash = "0123456789abcdef";
    h.plugins = "basic 0.1.0 ABI 1.1 0000";
    h.sums_layout = "xyz albedo";
    h.seed = 7;
    h.wavelengths = 4;
    h.max_depth = 5;
    h.colorspace = "ACEScg";
    return h;
}

TEST(RenderHeaderFormat, RoundTripsEveryKeyInAnyOrder)
{
    Header attributes = render_header_attributes(example());
    std::reverse(attributes.begin(), attributes.end());
    attributes.emplace_back("oiio:Software", std::string("OpenImageIO"));  // others are ignored
    const RenderHeader back = read_render_header(attributes);
    const RenderHeader h = example();
    EXPECT_EQ(back.scene, h.scene);
    EXPECT_EQ(back.spp, h.spp);
    EXPECT_EQ(back.sample_begin, h.sample_begin);
    EXPECT_EQ(back.sample_end, h.sample_end);
    EXPECT_EQ(back.scene_hash, h.scene_hash);
    EXPECT_EQ(back.plugins, h.plugins);
    EXPECT_EQ(back.sums_layout, h.sums_layout);
    EXPECT_EQ(back.seed, h.seed);
    EXPECT_EQ(back.wavelengths, h.wavelengths);
    EXPECT_EQ(back.max_depth, h.max_depth);
    EXPECT_EQ(back.colorspace, h.colorspace);
    EXPECT_EQ(back.merged_parts, 0);
    EXPECT_EQ(back.display, "");  // no display image: no keys
    RenderHeader merged = h;
    merged.merged_parts = 3;
    merged.display = "sRGB";
    merged.view = "ACES 1.0 - SDR Video";
    const RenderHeader again = read_render_header(render_header_attributes(merged));
    EXPECT_EQ(again.merged_parts, 3);
    EXPECT_EQ(again.display, "sRGB");
    EXPECT_EQ(again.view, "ACES 1.0 - SDR Video");
}

TEST(RenderHeaderFormat, RefusesMissingMistypedKeysAndAnEmptyRange)
{
    Header attributes = render_header_attributes(example());
    Header without;
    for (const auto& a : attributes)
        if (a.first != "patina:scene_hash")
            without.push_back(a);
    std::string m = test::message_of([&] { read_render_header(without); });
    EXPECT_NE(m.find("no patina:scene_hash in its header"), std::string::npos) << m;
    Header mistyped = attributes;
    for (auto& a : mistyped)
        if (a.first == "patina:seed")
            a.second = std::string("seven");
    m = test::message_of([&] { read_render_header(mistyped); });
    EXPECT_NE(m.find("patina:seed is not an integer"), std::string::npos) << m;
    RenderHeader empty = example();
    empty.sample_end = empty.sample_begin;
    m = test::message_of([&] { read_render_header(render_header_attributes(empty)); });
    EXPECT_NE(m.find("sample range 64-64 is empty"), std::string::npos) << m;
}

}  // namespace
}  // namespace patina::formats
