// fade.toml's one reader and writer (formats/fade_stack/fade_stack.h): a round trip of every key and
// the refusals (a newer format, keys out of order or range).
#include "formats/fade_stack/fade_stack.h"

#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <limits>

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

/// A PixelReader serving one image from memory (with or without channel names, as OIIO and
/// a plugin host's read_image give them).
class MemoryReader final : public PixelReader {
public:
    explicit MemoryReader(Pixels pixels) : pixels_(std::move(pixels)) {}
    Pixels read(const fs::path&, int) const override { return pixels_; }

private:
    Pixels pixels_;
};

FadeTable example_table()
{
    // 3 doses x 3 wavelengths of example(): r_bottom 0.1, r_top 0.2 + 0.01 k, R 0.3, T 0.5.
    FadeTable t;
    t.rows = 3;
    t.columns = 3;
    for (int i = 0; i < 9; ++i) {
        t.r_bottom.push_back(0.1f);
        t.r_top.push_back(0.2f + 0.01f * static_cast<float>(i));
        t.r_total.push_back(0.3f);
        t.t.push_back(0.5f);
    }
    return t;
}

TEST(FadeStackFormat, TheTableRoundTripsByNameAndInTheDocumentedOrder)
{
    const FadeDescription d = example();
    const Pixels written = fade_table_pixels(example_table(), d);
    EXPECT_EQ(written.channel_names,
              (std::vector<std::string>(kFadeTableChannels.begin(), kFadeTableChannels.end())));
    // OIIO gives names (here shuffled, as a reader may order them); the host none.
    Pixels shuffled = written;
    shuffled.channel_names = {"T", "R_total", "R_top", "R_bottom"};
    for (size_t i = 0; i < 9; ++i)
        std::reverse(shuffled.values.begin() + 4 * i, shuffled.values.begin() + 4 * i + 4);
    Pixels unnamed = written;
    unnamed.channel_names.clear();
    for (const Pixels& p : {written, shuffled, unnamed}) {
        const FadeTable back = read_fade_table(MemoryReader(p), d, "stack");
        EXPECT_EQ(back.r_top, example_table().r_top);
        EXPECT_EQ(back.r_bottom, example_table().r_bottom);
        EXPECT_EQ(back.r_total, example_table().r_total);
        EXPECT_EQ(back.t, example_table().t);
    }
}

TEST(FadeStackFormat, ABadTableIsNamedWithWhatIsWrong)
{
    const FadeDescription d = example();
    Pixels small = fade_table_pixels(example_table(), d);
    small.height = 2;
    std::string m = test::message_of([&] { read_fade_table(MemoryReader(small), d, "stack"); });
    EXPECT_NE(m.find("fade_table.exr: 3x2 pixels, but its fade.toml describes 3 wavelengths x 3 "
                     "doses"), std::string::npos) << m;
    Pixels renamed = fade_table_pixels(example_table(), d);
    renamed.channel_names[3] = "Tr";
    m = test::message_of([&] { read_fade_table(MemoryReader(renamed), d, "stack"); });
    EXPECT_NE(m.find("no channel 'T' (its channels: R_bottom, R_top, R_total, Tr)"),
              std::string::npos) << m;
    FadeTable gaining = example_table();
    gaining.t[4] = 0.9f;  // R_top 0.24 + T 0.9 > 1
    m = test::message_of([&] {
        read_fade_table(MemoryReader(fade_table_pixels(gaining, d)), d, "stack");
    });
    EXPECT_NE(m.find("row 1, column 1 is not a passive layer"), std::string::npos) << m;
}

TEST(FadeStackFormat, TheDoseMapsCoordinatesAreReadByName)
{
    const FadeDescription d = example();
    std::vector<float> texels;
    for (int i = 0; i < 4; ++i)
        texels.insert(texels.end(), {0.5f * static_cast<float>(i), 100.0f * i, 1.0f});
    const Pixels dose = dose_map_pixels(2, 2, texels, d);
    int w = 0, h = 0;
    EXPECT_EQ(read_dose_coordinates(MemoryReader(dose), d, "stack", &w, &h),
              (std::vector<float>{0.0f, 0.5f, 1.0f, 1.5f}));
    EXPECT_EQ(w, 2);
    EXPECT_EQ(h, 2);
    Pixels bad = dose;
    bad.values[3] = std::numeric_limits<float>::quiet_NaN();
    const std::string m =
        test::message_of([&] { read_dose_coordinates(MemoryReader(bad), d, "stack", &w, &h); });
    EXPECT_NE(m.find("dose.exr: texel (1, 0) has a coordinate that is not finite"),
              std::string::npos) << m;
}

}  // namespace
}  // namespace patina::formats
