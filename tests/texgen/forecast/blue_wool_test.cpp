// The ISO Blue Wool categories (shaders/fade/blue_wool.toml): each reaches a just-noticeable
// fade (ΔE00 1.6 under D65) at the dose it was defined by under the reference lamp, CIE
// LED-B2, and each lasts longer than the one below it.
#include "texgen/forecast/fade_forecast.h"

#include "texgen/fade/fade_material.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fmt/format.h>

using namespace patina::texgen;
using namespace patina::texgen::forecast;
namespace fs = std::filesystem;

TEST(BlueWool, EachCategoryReachesAJustNoticeableFadeAtItsPublishedDose)
{
    // CIE 157:2004 table 3: Mlx h to a just-noticeable fade of ISO Blue Wool 1-8
    const double published_mlx_h[] = {0.22, 0.6, 1.5, 3.5, 8.0, 20.0, 50.0, 120.0};
    const fade::FadeLibrary lib =
        fade::FadeLibrary::load_files({fs::path(PATINA_SOURCE_DIR) / "shaders/fade/blue_wool.toml"});
    const fade::WavelengthGrid grid = fade::WavelengthGrid::uniform(300.0, 830.0, 5.0);
    const ColourMeter meter(grid, fade::illuminant_by_name("D65"));
    ForecastOptions o;
    o.threshold_de2000 = 1.6;
    o.horizon_years = 10.0;
    o.curve_points = 2;
    LightingPolicy led;
    led.name = "LED-B2 50 lx";
    led.lamp = fade::illuminant_by_name("LED-B2");
    led.lux = 50.0;
    double previous_years = 0.0;
    for (int k = 1; k <= 8; ++k) {
        const fade::FadeMaterial m =
            lib.material_with_rates("blue_wool", fmt::format("blue_wool_{}", k));
        const PolicyForecast f = forecast_policy(m, led, grid, meter, o);
        EXPECT_NEAR(f.threshold_lux_hours * 1e-6, published_mlx_h[k - 1], 0.01 * published_mlx_h[k - 1])
            << "category " << k;
        // At 50 lx, 8 h a day, 365 days (146 klx h a year): dose / 146 klx h
        EXPECT_NEAR(f.years_to_threshold, published_mlx_h[k - 1] / 0.146,
                    0.01 * published_mlx_h[k - 1] / 0.146);
        EXPECT_GT(f.years_to_threshold, previous_years) << "category " << k;
        previous_years = f.years_to_threshold;
    }
}

TEST(BlueWool, UnknownRateSetIsNamed)
{
    const fade::FadeLibrary lib =
        fade::FadeLibrary::load_files({fs::path(PATINA_SOURCE_DIR) / "shaders/fade/blue_wool.toml"});
    try {
        lib.material_with_rates("blue_wool", "blue_wool_9");
        FAIL() << "category 9 accepted";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("blue_wool_9"), std::string::npos) << e.what();
    }
}
