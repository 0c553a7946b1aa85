// fade.toml's one reader and writer (formats/fade_stack.h): a round trip of every key and
// the refusals (a newer format, keys out of order or range).
#include "formats/fade_stack.h"

#include "test_util.h"

#include <gtest/gtest.h>

#include <fstream>

namespace patina::formats {
namespace {

namespace fs = std::filesystem;

FadeDescription example()
{
    FadeDescription d;
    d.generator = "patina-texgen test";
    d.material = "alizarin on paper";
    d.material_file = "fade_materials.toml";
    d.illuminant = "D65";
    d.band_min_nm = 300.0;
    d.band_max_nm = 780.0;
    d.sublayers = 100;
    d.both_sides = true;
    d.entries = 3;
    d.substeps = 2;
    d.knee_dose = 1e4;
    d.max_dose = 1e8;
    d.max_interpolation_error = 0.0025;
    d.wavelength_nm = {400.0, 550.0, 700.0};
    d.doses = {0.0, 9900.0, 1e8};
    d.substrate = {0.75, 0.875, 0.5};
    d.width = 64;
    d.height = 32;
    d.min_dose = 10.0;
    d.mean_dose = 2e5;
    d.max_dose_in_map = 4e6;
    d.exposure.files = {"exposure.exr", "lamp.exr"};
    d.exposure.units = "W/m^2";
    d.exposure.scale = 0.5;
    d.exposure.duration_s = 3.15e7;
    d.exposure.period_s = 86400.0;
    return d;
}

fs::path write(const char* name, const std::string& text)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "fade_stack_test" / name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    std::ofstream(dir / kFadeDescription) << text;
    return dir;
}

std::string replaced(std::string text, const std::string& from, const std::string& to)
{
    const size_t at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos)
        text.replace(at, from.size(), to);
    return text;
}

TEST(FadeStackFormat, RoundTripsEveryKey)
{
    const FadeDescription d = example();
    const fs::path dir = write("round_trip", fade_description_text(d));
    const FadeDescription r = read_fade_description(dir);
    EXPECT_EQ(r.format, kFadeFormatVersion);
    EXPECT_EQ(r.generator, d.generator);
    EXPECT_EQ(r.material, d.material);
    EXPECT_EQ(r.material_file, d.material_file);
    EXPECT_EQ(r.illuminant, d.illuminant);
    EXPECT_EQ(r.band_min_nm, d.band_min_nm);
    EXPECT_EQ(r.band_max_nm, d.band_max_nm);
    EXPECT_EQ(r.sublayers, d.sublayers);
    EXPECT_EQ(r.both_sides, d.both_sides);
    EXPECT_EQ(r.entries, d.entries);
    EXPECT_EQ(r.substeps, d.substeps);
    EXPECT_EQ(r.knee_dose, d.knee_dose);
    EXPECT_EQ(r.max_dose, d.max_dose);
    EXPECT_EQ(r.max_interpolation_error, d.max_interpolation_error);
    EXPECT_EQ(r.wavelength_nm, d.wavelength_nm);
    EXPECT_EQ(r.doses, d.doses);
    EXPECT_EQ(r.substrate, d.substrate);
    EXPECT_EQ(r.width, d.width);
    EXPECT_EQ(r.height, d.height);
    EXPECT_EQ(r.min_dose, d.min_dose);
    EXPECT_EQ(r.mean_dose, d.mean_dose);
    EXPECT_EQ(r.max_dose_in_map, d.max_dose_in_map);
    EXPECT_EQ(r.exposure.files, d.exposure.files);
    EXPECT_EQ(r.exposure.channel, d.exposure.channel);
    EXPECT_EQ(r.exposure.units, d.exposure.units);
    EXPECT_EQ(r.exposure.scale, d.exposure.scale);
    EXPECT_EQ(r.exposure.duration_s, d.exposure.duration_s);
    EXPECT_EQ(r.exposure.period_s, d.exposure.period_s);
    EXPECT_EQ(r.table_path(dir), dir / kFadeTableFile);
    EXPECT_EQ(r.dose_map_path(dir), dir / kDoseMapFile);
}

TEST(FadeStackFormat, NewerFormatAndBadKeysAreRefused)
{
    const std::string good = fade_description_text(example());
    auto message = [&](const char* name, const std::string& from, const std::string& to) {
        const fs::path dir = write(name, replaced(good, from, to));
        return test::message_of([&] { read_fade_description(dir / kFadeDescription); });
    };
    std::string m = message("newer", "format = 1", "format = 2");
    EXPECT_NE(m.find("fade.toml:"), std::string::npos) << m;
    EXPECT_NE(m.find("fade stack format 2 is newer than the 1"), std::string::npos) << m;
    m = message("order", "'R_bottom', 'R_top'", "'R_top', 'R_bottom'");
    EXPECT_NE(m.find("[table] channels must be R_bottom, R_top, R_total, T"), std::string::npos)
        << m;
    m = message("substrate", "reflectance = [ 0.75,", "reflectance = [ 1.75,");
    EXPECT_NE(m.find("[substrate] reflectance must lie in [0, 1]"), std::string::npos) << m;
    m = message("wavelengths", "wavelength_nm = [ 400.0, 550.0", "wavelength_nm = [ 600.0, 550.0");
    EXPECT_NE(m.find("wavelength_nm must increase"), std::string::npos) << m;
    m = message("syntax", "[substrate]", "[substrate");
    EXPECT_NE(m.find("fade.toml:"), std::string::npos) << m;
}

}  // namespace
}  // namespace patina::formats
