// Fade maps and fade stacks: exposure -> dose -> table row; the table against a direct
// solve; the stack's files; bad inputs.
#include "texgen/fade_map/test_material.h"

#include "core/image_io.h"
#include "test_util.h"
#include "texgen/fade/fade_map.h"
#include "texgen/stack/map_output.h"
#include "texgen/fade/fade_stack.h"
#include "texgen/fade/fading_simulation.h"

#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <cmath>
#include <filesystem>
#include <limits>

namespace patina::test {
namespace {

namespace fs = std::filesystem;
using namespace texgen::fade;

fs::path scratch(const std::string& name)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "fade_map" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// An exposure map like the texgen exposure baker's: channel `exposure` (J/m^2), the period
// and the illuminant in the header.
fs::path write_exposure_map(const fs::path& dir, int width, int height,
                            const std::function<float(int, int)>& value,
                            const std::string& channel = "exposure",
                            const std::string& units = "J/m^2")
{
    std::vector<float> pixels(static_cast<size_t>(width) * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            pixels[static_cast<size_t>(y) * width + x] = value(x, y);
    const fs::path file = dir / "exposure.exr";
    write_image_atomic(file, pixels.data(), width, height, 1, {channel}, OIIO::TypeDesc::FLOAT,
                       {{"patina:units", units},
                        {"patina:period_seconds", std::string("86400")},
                        {"patina:illuminant", std::string("D65")}});
    return file;
}

DoseTable test_table(double max_dose, int entries = 32)
{
    DoseTableOptions o;
    o.max_dose_j_m2 = max_dose;
    o.knee_dose_j_m2 = max_dose * 1e-3;
    o.entries = entries;
    o.sublayers = 40;
    o.substeps = 2;
    return DoseTable::build(fading_test_material(), illuminant_by_name("D65"), fading_test_grid(),
                            o);
}

TEST(FadeMap, TableCoordinateFollowsTheDoseRule)
{
    const DoseTable table = test_table(1e7);
    // Every table dose sits exactly on its row; doses beyond the table clamp to the last row
    for (size_t k = 0; k < table.doses().size(); ++k)
        EXPECT_NEAR(table_coordinate(table, table.doses()[k]), static_cast<double>(k), 1e-9);
    EXPECT_DOUBLE_EQ(table_coordinate(table, 0.0), 0.0);
    EXPECT_NEAR(table_coordinate(table, 1e9), table.doses().size() - 1.0, 1e-12);
    // Between rows the coordinate is linear in u = ln(1 + H / H0) (dose_table.h)
    const double h0 = table.options().knee_dose_j_m2;
    const double a = table.doses()[5], b = table.doses()[6];
    const double mid = h0 * (std::sqrt((1.0 + a / h0) * (1.0 + b / h0)) - 1.0);
    EXPECT_NEAR(table_coordinate(table, mid), 5.5, 1e-9);
}

TEST(FadeMap, TableAgreesWithTheDirectSolveWithinItsDocumentedError)
{
    // The error fade.toml documents: the table's interpolation at interval midpoints against
    // a table twice as fine
    const DoseTable table = test_table(1e7, 32);
    DoseTableOptions fine_options = table.options();
    fine_options.entries = 63;
    const DoseTable fine = DoseTable::build(fading_test_material(), illuminant_by_name("D65"),
                                            fading_test_grid(), fine_options);
    const double documented = interpolation_error(table, fine);
    std::printf("[ fade     ] table of 32 entries: documented error %.3g\n", documented);
    EXPECT_GT(documented, 0.0);
    EXPECT_LT(documented, 0.02);

    // The direct solve: the same material run to a midpoint dose with 400 small steps
    const Illuminant d65 = illuminant_by_name("D65");
    const Illumination light = d65.illumination(fading_test_grid(), 1.0);  // 1 W/m^2 band
    double worst = 0.0;
    for (size_t k : {3u, 12u, 20u, 28u}) {
        const double dose = fine.doses()[2 * k + 1];
        FadeSimulation direct(fading_test_material(), fading_test_grid(), 40);
        direct.run(light, dose, 400);  // dose = irradiance (1 W/m^2) x seconds
        const std::vector<double> r = direct.reflectance();
        const LayerSpectra looked_up = table.spectra_at(dose);
        for (size_t w = 0; w < r.size(); ++w)
            worst = std::max(worst, std::abs(looked_up.reflectance[w] - r[w]));
    }
    std::printf("[ fade     ] table vs direct solve at 4 midpoints: %.3g\n", worst);
    // Interpolation plus the time-stepping difference (the table takes 2 steps per interval)
    EXPECT_LE(worst, documented + 5e-4);
}

TEST(FadeMap, ExposureBecomesDoseAndRow)
{
    const fs::path dir = scratch("dose");
    const fs::path file =
        write_exposure_map(dir, 8, 4, [](int x, int y) { return 1e5f * static_cast<float>(x + 8 * y); });
    const ExposureMap map = read_exposure_map(file, "");
    EXPECT_EQ(map.channel, "exposure");
    EXPECT_EQ(map.units, "J/m^2");
    EXPECT_DOUBLE_EQ(map.period_s, 86400.0);
    // A week of a day's exposure: seven times the dose
    const double factor = dose_factor(map, 0.5, 7 * 86400.0);
    EXPECT_DOUBLE_EQ(factor, 3.5);
    const DoseRange range = scan_doses(map, factor);
    EXPECT_DOUBLE_EQ(range.max, 3.5 * 31e5);
    EXPECT_DOUBLE_EQ(range.min, 0.0);
    const DoseTable table = test_table(range.max, 16);
    const std::vector<float> pixels = make_dose_pixels(map, table, factor);
    ASSERT_EQ(pixels.size(), 96u);
    for (int i = 0; i < 32; ++i) {
        const double dose = 3.5 * 1e5 * i;
        EXPECT_NEAR(pixels[3 * i + 1], dose, 1e-6 * dose);
        EXPECT_NEAR(pixels[3 * i], table_coordinate(table, dose), 1e-5);
        EXPECT_EQ(pixels[3 * i + 2], map.coverage.at(static_cast<size_t>(i)));
    }
}

TEST(FadeMap, DoseMapCarriesTheExposureMapsCoverage)
{
    // An exposure map with a coverage channel (as every baker writes, stack/map_output.h):
    // the dose map keeps it, so an empty texel (exposure 0, coverage 0) stays apart from a
    // baked one that saw no light (exposure 0, coverage 1).
    const fs::path dir = scratch("dose_coverage");
    fs::create_directories(dir);
    const int w = 8, h = 4;
    std::vector<float> pixels;
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            pixels.push_back(x < 4 ? 0.0f : 1e5f);                  // exposure
            pixels.push_back(x == 0 ? 0.0f : x == 1 ? 0.25f : 1.0f);  // coverage
        }
    const fs::path file = dir / "exposure.exr";
    write_image_atomic(file, pixels.data(), w, h, 2, {"exposure", patina::texgen::kCoverageChannel},
                       OIIO::TypeDesc::FLOAT,
                       {{"patina:units", std::string("J/m^2")},
                        {"patina:period_seconds", std::string("86400")}});
    const ExposureMap map = read_exposure_map(file, "");
    const DoseTable table = test_table(1e5, 8);
    const std::vector<float> dose = make_dose_pixels(map, table, 1.0);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            const size_t i = static_cast<size_t>(y) * w + x;
            EXPECT_EQ(dose[3 * i + 2], pixels[2 * i + 1]) << x << ", " << y;
        }
    FadeStackInfo info;
    info.material = "test_magenta_layer";
    info.illuminant = "D65";
    info.substrate = fading_test_grid().sample(fading_test_material().substrate_reflectance);
    info.width = w;
    info.height = h;
    write_fade_stack(dir / "out", table, info, dose);
    const ImageData written = read_image(dir / "out" / kDoseMapFile);
    EXPECT_EQ(written.channel_names.at(0), "coordinate");  // the plugin reads channel 0
    const int a = written.channel(patina::texgen::kCoverageChannel);
    ASSERT_EQ(a, 2);
    EXPECT_EQ(written.at(0, 0, a), 0.0f);
    EXPECT_EQ(written.at(1, 0, a), 0.25f);
    EXPECT_EQ(written.at(2, 0, a), 1.0f);
    const toml::table fade = toml::parse_file((dir / "out" / kFadeToml).string());
    EXPECT_EQ(fade["dose_map"]["coverage"].value<std::string>(), patina::texgen::kCoverageChannel);
}

TEST(FadeMap, IrradianceMapsNeedADuration)
{
    const fs::path dir = scratch("irradiance");
    const fs::path file =
        write_exposure_map(dir, 2, 2, [](int, int) { return 10.0f; }, "irradiance", "W/m^2");
    const ExposureMap map = read_exposure_map(file, "");
    EXPECT_EQ(map.units, "W/m^2");
    EXPECT_NE(message_of([&] { dose_factor(map, 1.0, 0.0); }).find("--duration"),
              std::string::npos);
    EXPECT_DOUBLE_EQ(dose_factor(map, 1.0, 3600.0), 3600.0);
}

TEST(FadeMap, BadInputsAreNamed)
{
    const fs::path dir = scratch("bad");
    EXPECT_NE(message_of([&] { read_exposure_map(dir / "missing.exr", ""); }).find("missing.exr"),
              std::string::npos);
    const fs::path file = write_exposure_map(dir, 4, 3, [](int x, int y) {
        return x == 2 && y == 1 ? std::numeric_limits<float>::quiet_NaN() : 1.0f;
    });
    EXPECT_NE(message_of([&] { read_exposure_map(file, "thickness"); }).find("no channel"),
              std::string::npos);
    const ExposureMap map = read_exposure_map(file, "");
    const std::string nan = message_of([&] { scan_doses(map, 1.0); });
    EXPECT_NE(nan.find("texel (2, 1)"), std::string::npos) << nan;
    const DoseTable table = test_table(1e6, 4);
    const std::string nan2 = message_of([&] { make_dose_pixels(map, table, 1.0); });
    EXPECT_NE(nan2.find("texel (2, 1)"), std::string::npos) << nan2;
    EXPECT_NE(message_of([&] { dose_factor(map, -1.0, 0.0); }).find("--scale"), std::string::npos);
}

TEST(FadeStack, WritesAndReadsBack)
{
    const fs::path dir = scratch("stack");
    const fs::path file =
        write_exposure_map(dir, 16, 8, [](int x, int) { return 2e5f * static_cast<float>(x); });
    const ExposureMap map = read_exposure_map(file, "");
    const DoseRange range = scan_doses(map, 1.0);
    const DoseTable table = test_table(range.max, 16);
    FadeStackInfo info;
    info.material = "test_magenta_layer";
    info.illuminant = "D65";
    info.substrate = fading_test_grid().sample(fading_test_material().substrate_reflectance);
    info.width = map.width;
    info.height = map.height;
    info.max_dose = range.max;
    info.max_interpolation_error = 1e-3;
    const fs::path out = dir / "out";
    write_fade_stack(out, table, info, make_dose_pixels(map, table, 1.0));
    ASSERT_TRUE(fs::exists(out / kFadeToml));

    const FadeStack stack = read_fade_stack(out);
    EXPECT_EQ(stack.material, "test_magenta_layer");
    ASSERT_EQ(stack.doses.size(), 16u);
    ASSERT_EQ(stack.wavelength_nm.size(), fading_test_grid().size());
    for (size_t k = 0; k < stack.doses.size(); ++k) {
        EXPECT_DOUBLE_EQ(stack.doses[k], table.doses()[k]);
        for (size_t w = 0; w < stack.wavelength_nm.size(); ++w) {
            EXPECT_NEAR(stack.r_total[k][w], table.spectra(k).reflectance[w], 1e-6);
            // R_total is the layer over the substrate (layer_optics.h)
            const double composite = stack.r_top[k][w] + stack.t[k][w] * stack.t[k][w] *
                                                             stack.substrate[w] /
                                                             (1.0 - stack.r_bottom[k][w] *
                                                                        stack.substrate[w]);
            EXPECT_NEAR(stack.r_total[k][w], composite, 1e-5);
        }
    }
    // The dose map: tiled and mip-mapped, coordinate first
    const ImageData dose = read_image(stack.dose_map);
    EXPECT_EQ(dose.width, 16);
    ASSERT_EQ(dose.channel("coordinate"), 0);
    ASSERT_EQ(dose.channel("dose"), 1);
    EXPECT_NEAR(dose.at(15, 3, 1), 15 * 2e5, 1.0);
    EXPECT_NEAR(dose.at(15, 3, 0), 15.0, 1e-4);  // the largest dose is the last row
    EXPECT_DOUBLE_EQ(dose.at(0, 3, 0), 0.0);

    // A bad stack description is reported with its file
    write_file_atomic(out / kFadeToml, {"[fade]\nformat = 1\n"}, "test");
    EXPECT_NE(message_of([&] { read_fade_stack(out); }).find("fade.toml:1:1: no [table] table"),
              std::string::npos);
    write_file_atomic(out / kFadeToml, {"[fade]\nformat = 1\n[table]\nfile = 'x.exr'\n"}, "test");
    EXPECT_NE(message_of([&] { read_fade_stack(out); }).find("wavelength_nm"), std::string::npos);
}

TEST(FadeStack, RefusesMismatchedSizesBeforeWriting)
{
    const fs::path dir = scratch("mismatch");
    const DoseTable table = test_table(1e6, 4);
    FadeStackInfo info;
    info.width = 4;
    info.height = 4;
    info.substrate = fading_test_grid().sample(fading_test_material().substrate_reflectance);
    EXPECT_NE(message_of([&] { write_fade_stack(dir / "a", table, info, std::vector<float>(8)); })
                  .find("4x4"),
              std::string::npos);
    info.substrate.pop_back();
    EXPECT_NE(message_of([&] { write_fade_stack(dir / "b", table, info, std::vector<float>(48)); })
                  .find("substrate"),
              std::string::npos);
    EXPECT_FALSE(fs::exists(dir / "a" / kFadeTableFile));
    EXPECT_FALSE(fs::exists(dir / "b" / kFadeTableFile));
}

}  // namespace
}  // namespace patina::test
