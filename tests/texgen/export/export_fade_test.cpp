// Fade stacks exported (texgen/export/export_fade.h): the base colour is the stack's
// reflectance over its substrate seen under D65, checked here against the table itself
// through an independent path (the table's own wavelengths, the CIE 1931 functions and the
// sRGB standard's XYZ -> linear Rec.709 matrix, IEC 61966-2-1), and a series of newsprint
// stacks yellows with age, as Kimmel et al. 2013 §5.1 (lignin to o-quinone) has it.
#include "texgen/export/export_fade.h"

#include "core/color_difference.h"
#include "core/image_io.h"
#include "core/spectrum.h"
#include "formats/fade_stack/fade_stack.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>

namespace patina::texgen {
namespace {

namespace fs = std::filesystem;

class FadeExport : public ::testing::Test {
protected:
    void SetUp() override
    {
        dir_ = fs::path(PATINA_TEST_BUILD_DIR) / "export_fade_test" /
               ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }

    void fade(const std::string& name, const std::string& args) const
    {
        const std::string command = std::string(PATINA_TEST_BIN_DIR) +
                                    "/patina-texgen fade --material newsprint --entries 8 "
                                    "--quiet --out '" + (dir_ / name).string() + "' " + args;
        ASSERT_EQ(std::system(command.c_str()), 0) << command;
    }

    /// The base colour the stack's table gives at row `row`, linear Rec.709, computed
    /// without the export's code: a sum over the table's wavelengths (trapezoids) of
    /// R * D65 * CIE, normalised by D65's Y, and the sRGB matrix.
    Imath::V3d expected_rgb(const std::string& name, int row) const
    {
        const formats::FadeDescription d = formats::read_fade_description(dir_ / name);
        const ImageData table = read_image(d.table_path(dir_ / name));
        const int c = table.channel("R_total");
        double x = 0, y = 0, z = 0, white = 0;
        for (size_t i = 0; i + 1 < d.wavelength_nm.size(); ++i)
            for (size_t e : {i, i + 1}) {
                const double l = d.wavelength_nm[e];
                if (l < 360.0 || l > 830.0)
                    continue;
                const double w = 0.5 * (d.wavelength_nm[i + 1] - d.wavelength_nm[i]) * d65(float(l));
                const double r = table.at(static_cast<int>(e), row, c);
                x += w * r * cie_x(float(l));
                y += w * r * cie_y(float(l));
                z += w * r * cie_z(float(l));
                white += w * cie_y(float(l));
            }
        x /= white;
        y /= white;
        z /= white;
        return {3.2406 * x - 1.5372 * y - 0.4986 * z, -0.9689 * x + 1.8758 * y + 0.0415 * z,
                0.0557 * x - 0.2040 * y + 1.0570 * z};
    }

    /// The base colour PNG of the export, decoded to linear (the sRGB curve).
    Imath::V3d exported_rgb(const fs::path& png) const
    {
        const ImageData image = read_image(png);
        Imath::V3d rgb;
        for (int k = 0; k < 3; ++k) {
            const double v = image.at(0, 0, k);
            rgb[k] = v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4);
        }
        return rgb;
    }

    fs::path dir_;
    const ColorManager colors_{fs::path(PATINA_SOURCE_DIR) / "ocio/config.ocio"};
};

TEST_F(FadeExport, BaseColourIsTheTablesReflectanceUnderD65)
{
    fade("before", "--dose 0");
    fade("week", "--dose 6.048e7 --duration 7d --illuminant F11");
    ExportOptions o;
    o.separate = true;
    const ExportResult r =
        export_fade({dir_ / "before", dir_ / "week"}, dir_ / "out" / "page.gltf", o, colors_);
    EXPECT_EQ(r.steps, 2u);
    // A uniform dose sits on the table's first row (unexposed) or last (the dose itself).
    const Imath::V3d before = expected_rgb("before", 0), week = expected_rgb("week", 7);
    const Imath::V3d got_before = exported_rgb(dir_ / "out" / "page_before_base_color.png");
    const Imath::V3d got_week = exported_rgb(dir_ / "out" / "page_week_base_color.png");
    for (int k = 0; k < 3; ++k) {
        // Half an 8-bit sRGB step is under 0.7 % of a value above 0.2, and the two
        // integrations (1 nm resampled, the table's 5 nm) differ by less: 1 % together.
        EXPECT_NEAR(got_before[k], before[k], 0.01 * before[k] + 0.002) << k;
        EXPECT_NEAR(got_week[k], week[k], 0.01 * week[k] + 0.002) << k;
    }
    // Yellowing: b* rises (the white point is D65's, Y = 1).
    const Imath::V3d white(0.95047, 1.0, 1.08883);
    auto lab = [&](const Imath::V3d& rgb) {
        const Imath::V3d xyz(0.4124 * rgb[0] + 0.3576 * rgb[1] + 0.1805 * rgb[2],
                             0.2126 * rgb[0] + 0.7152 * rgb[1] + 0.0722 * rgb[2],
                             0.0193 * rgb[0] + 0.1192 * rgb[1] + 0.9505 * rgb[2]);
        return xyz_to_lab(xyz, white);
    };
    EXPECT_GT(lab(got_week).b, lab(got_before).b + 5.0);
}

TEST_F(FadeExport, SeriesOutOfOrderAndResolutionAreRefused)
{
    fade("before", "--dose 0");
    fade("week", "--dose 6.048e7 --duration 7d --illuminant F11");
    std::string m = test::message_of([&] {
        export_fade({dir_ / "week", dir_ / "before"}, dir_ / "x.glb", {}, colors_);
    });
    EXPECT_NE(m.find("must be given in order of age"), std::string::npos) << m;
    ExportOptions o;
    o.resolution = 64;
    m = test::message_of([&] { export_fade({dir_ / "week"}, dir_ / "x.glb", o, colors_); });
    EXPECT_NE(m.find("--resolution"), std::string::npos) << m;
    EXPECT_FALSE(fs::exists(dir_ / "x.glb"));
}

}  // namespace
}  // namespace patina::texgen
