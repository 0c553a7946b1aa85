// The reflectance plot: a PNG of the asked size whose curves land where their values say.
#include "core/image_io.h"
#include "test_util.h"
#include "texgen/fade/fade_plot.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace patina::test {
namespace {

namespace fs = std::filesystem;
using namespace texgen::fade;

TEST(FadePlot, DrawsCurvesAxesAndLegend)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "fade_plot";
    fs::create_directories(dir);
    const fs::path file = dir / "plot.png";
    fs::remove(file);
    // Two flat curves: pure red at 0.25, pure blue at 0.75, over 400-700 nm
    PlotCurve low{"0h", {400.0, 700.0}, {0.25, 0.25}, {1.0f, 0.0f, 0.0f}};
    PlotCurve high{"7d", {400.0, 550.0, 700.0}, {0.75, 0.75, 0.75}, {0.0f, 0.0f, 1.0f}};
    PlotOptions o;
    o.width = 600;
    o.height = 400;
    o.title = "test";
    write_reflectance_plot(file, {low, high}, o);
    const ImageData image = read_image(file);
    ASSERT_EQ(image.width, 600);
    ASSERT_EQ(image.height, 400);

    // Plot area as fade_plot.cpp lays it out: x 90..450, y 50..330, y range [0, 1]
    const int x = (90 + 450) / 2;
    auto row_of = [](double value) { return static_cast<int>(330 - value * (330 - 50) + 0.5); };
    auto is_color = [&](int px, int py, int channel) {
        for (int dy = -2; dy <= 2; ++dy) {
            const float r = image.at(px, py + dy, 0), g = image.at(px, py + dy, 1),
                        b = image.at(px, py + dy, 2);
            const float c[3] = {r, g, b};
            if (c[channel] > 0.8f && c[(channel + 1) % 3] < 0.2f && c[(channel + 2) % 3] < 0.2f)
                return true;
        }
        return false;
    };
    EXPECT_TRUE(is_color(x, row_of(0.25), 0)) << "red curve at 0.25";
    EXPECT_TRUE(is_color(x, row_of(0.75), 2)) << "blue curve at 0.75";
    EXPECT_FALSE(is_color(x, row_of(0.5), 0));
    // The axes are dark
    EXPECT_LT(image.at(90, 200, 0), 0.3f);
    EXPECT_LT(image.at(300, 330, 0), 0.3f);
    // The legend carries each curve's colour to the right of the plot
    EXPECT_TRUE(is_color(480, 60, 0));
    EXPECT_TRUE(is_color(480, 84, 2));
}

TEST(FadePlot, RefusesNothingToDraw)
{
    const fs::path file = fs::path(PATINA_TEST_BUILD_DIR) / "fade_plot" / "bad.png";
    EXPECT_NE(message_of([&] { write_reflectance_plot(file, {}, {}); }).find("no curves"),
              std::string::npos);
    PlotCurve one{"x", {400.0}, {0.5}, {}};
    EXPECT_NE(message_of([&] { write_reflectance_plot(file, {one}, {}); }).find("two or more"),
              std::string::npos);
    PlotCurve nan{"n", {400.0, 500.0}, {0.5, std::nan("")}, {}};
    EXPECT_NE(message_of([&] { write_reflectance_plot(file, {nan}, {}); }).find("non-finite"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(file));
}

TEST(FadePlot, DurationLabels)
{
    EXPECT_EQ(duration_label(0.0), "0h");
    EXPECT_EQ(duration_label(6 * 3600.0), "6h");
    EXPECT_EQ(duration_label(86400.0), "1d");
    EXPECT_EQ(duration_label(7 * 86400.0), "7d");
    EXPECT_EQ(duration_label(30 * 365 * 86400.0), "30y");
}

}  // namespace
}  // namespace patina::test
