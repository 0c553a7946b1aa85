// The colours before the fade: fade a chart by known doses with the fading model itself,
// invert, and compare the restored colours with the chart's own.
#include "texgen/restore/fade_inversion.h"

#include "texgen/fade/fade_material.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fmt/format.h>

using namespace patina;
using namespace patina::texgen;
namespace fs = std::filesystem;

namespace {

struct Patch {
    std::array<double, 3> amounts;
    double dose;
    Imath::V3d faded, unfaded;
};

}  // namespace

TEST(FadeInversion, RestoresAFadedChartWhereUniqueAndFlagsTheRest)
{
    const fade::FadeLibrary lib = fade::FadeLibrary::load_files(
        {fs::path(PATINA_SOURCE_DIR) / "shaders/fade/pigments.toml"});
    const fade::FadeMaterial cmy = lib.material("cyan_magenta_yellow");
    const fade::WavelengthGrid grid = fade::WavelengthGrid::uniform(360.0, 830.0, 10.0);
    const fade::Illuminant d65 = fade::illuminant_by_name("D65");
    const forecast::ColourMeter meter(grid, d65);
    restore::InversionOptions o;
    o.max_dose_j_m2 = 2000.0;
    o.sublayers = 30;
    const restore::FadeInversion inversion(cmy, d65, grid, meter, o);
    ASSERT_EQ(inversion.dimensions(), 3u);

    // The chart: amounts off the inversion's grid, faded with the model at each dose
    std::vector<Patch> chart;
    const double levels[] = {0.3, 0.9, 1.45};
    for (double dose : {3.0, 15.0, 60.0, 2000.0})
        for (double c : levels)
            for (double m : levels)
                for (double y : levels) {
                    fade::FadeMaterial mat = cmy;
                    const std::array<double, 3> s{c, m, y};
                    for (size_t d = 0; d < 3; ++d)
                        mat.initial_fractions[mat.colorant_index(inversion.free_colorants()[d])] *= s[d];
                    fade::DoseTableOptions t;
                    t.max_dose_j_m2 = dose;
                    t.knee_dose_j_m2 = dose * 1e-3;
                    t.entries = 48;
                    t.sublayers = o.sublayers;
                    const fade::DoseTable table = fade::DoseTable::build(mat, d65, grid, t);
                    chart.push_back({s, dose, meter.xyz(table.spectra(t.entries - 1).reflectance),
                                     meter.xyz(table.spectra(0).reflectance)});
                }

    int unique = 0, flagged = 0, flagged_at_last_dose = 0, unique_at_first_dose = 0;
    double worst = 0.0;
    for (const Patch& p : chart) {
        const restore::Inversion r = inversion.invert(p.faded, p.dose);
        if (std::getenv("PATINA_DEBUG_INVERSION"))
            std::printf("%.2f %.2f %.2f dose %g: ampl %.3f resid %.3f -> %.3f %.3f %.3f\n", p.amounts[0], p.amounts[1], p.amounts[2], p.dose, r.amplification, r.residual, r.amounts[0], r.amounts[1], r.amounts[2]);
        if (r.unique) {
            ++unique;
            unique_at_first_dose += p.dose == 3.0;
            const double de = delta_e2000(meter.lab_of_xyz(r.unfaded_xyz), meter.lab_of_xyz(p.unfaded));
            worst = std::max(worst, de);
            EXPECT_LE(de, 0.5) << fmt::format("amounts {} {} {}, dose {}: restored {} {} {}",
                                              p.amounts[0], p.amounts[1], p.amounts[2], p.dose,
                                              r.amounts[0], r.amounts[1], r.amounts[2]);
        } else {
            ++flagged;
            flagged_at_last_dose += p.dose == 2000.0;
        }
    }
    std::printf("restored %d patches within dE2000 %.3f; %d flagged (%d of them at 2000 J/m^2)\n",
                unique, worst, flagged, flagged_at_last_dose);
    // At 2000 J/m^2 the Table V pigments are bleached (docs/fading.md): nothing is unique
    EXPECT_EQ(flagged_at_last_dose, 27);
    // At the smallest dose every patch keeps enough of each colorant to be restored
    EXPECT_EQ(unique_at_first_dose, 27);
    EXPECT_GT(unique, 27);
}
