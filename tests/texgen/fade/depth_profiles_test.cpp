// The fading simulation run for itself: colorant fractions over depth at chosen times.
#include "texgen/fade/depth_profiles.h"

#include "fade_test_util.h"
#include "texgen/fade/fade_material.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

using namespace patina::texgen::fade;
namespace fs = std::filesystem;

namespace {

FadeMaterial newsprint()
{
    static const FadeLibrary lib =
        FadeLibrary::load_files({fs::path(PATINA_SOURCE_DIR) / "shaders/fade/paper.toml"});
    return lib.material("newsprint");
}

}  // namespace

TEST(DepthProfiles, SnapshotsAreTheSimulationsStateAtThoseTimes)
{
    const WavelengthGrid grid = WavelengthGrid::uniform(300.0, 830.0, 10.0);
    const Illuminant flat = illuminant_by_name("flat");
    ProfileRun run;
    run.irradiance_w_m2 = 1.0;
    run.time_step_s = 3600.0;
    run.steps = 48;
    run.sublayers = 30;
    run.times_s = {6 * 3600.0, 48 * 3600.0};
    const DepthProfiles p = run_depth_profiles(newsprint(), flat, grid, run);
    ASSERT_EQ(p.snapshots.size(), 3u);
    EXPECT_EQ(p.snapshots[0].time_s, 0.0);

    // The same steps by hand: bitwise the same state
    FadeSimulation sim(newsprint(), grid, 30);
    const Illumination light = flat.illumination(grid, 1.0);
    sim.run(light, 6 * 3600.0, 6);
    EXPECT_EQ(sim.fractions(), p.snapshots[1].fractions);
    EXPECT_EQ(sim.reflectance(), p.snapshots[1].reflectance);

    // Light comes from the top: lignin is used up there first (Kimmel et al. 2013, figure 5)
    const size_t J = p.colorants.size();
    size_t lignin = 0;
    while (p.colorants[lignin] != "lignin")
        ++lignin;
    const std::vector<double>& f = p.snapshots[1].fractions;
    for (int i = 1; i < run.sublayers; ++i)
        EXPECT_LE(f[(i - 1) * J + lignin], f[i * J + lignin]) << "sublayer " << i;
    EXPECT_LT(f[lignin], 0.5 * f[(run.sublayers - 1) * J + lignin]);

    // The CSV has a row per snapshot and sublayer, a column per colorant
    const std::string csv = profiles_csv(p);
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 1 + 3 * 30);
    EXPECT_EQ(csv.substr(0, csv.find('\n')), "time_s,sublayer,depth_um,fibre,lignin,newsprint_other,o_quinone");
}

TEST(DepthProfiles, TimesOffTheStepsAreRefused)
{
    const WavelengthGrid grid = WavelengthGrid::uniform(400.0, 700.0, 50.0);
    ProfileRun run;
    run.irradiance_w_m2 = 1.0;
    run.time_step_s = 3600.0;
    run.steps = 10;
    run.times_s = {5400.0};
    try {
        run_depth_profiles(newsprint(), illuminant_by_name("D65"), grid, run);
        FAIL() << "1.5 steps accepted";
    } catch (const std::runtime_error& e) {
        EXPECT_NE(std::string(e.what()).find("--profiles-at"), std::string::npos) << e.what();
    }
    run.times_s = {11 * 3600.0};
    EXPECT_THROW(run_depth_profiles(newsprint(), illuminant_by_name("D65"), grid, run),
                 std::runtime_error);
}

TEST(DepthProfiles, FractionsSummingOverOneAreRefusedWithTheMaterialNamed)
{
    const fs::path file = fs::temp_directory_path() / "patina_overfull.toml";
    std::ofstream(file) << "[colorants.a]\nabsorption_per_m = 1.0\n[colorants.b]\nabsorption_per_m = 0.0\nscattering_per_m = 1.0\n"
                           "[materials.overfull]\nthickness_um = 10\ncolorants = { a = 0.7, b = 0.6 }\n";
    FadeLibrary lib;
    try {
        lib.load(file);
        FAIL() << "fractions summing to 1.3 accepted";
    } catch (const std::runtime_error& e) {
        const std::string m = e.what();
        EXPECT_NE(m.find("overfull"), std::string::npos) << m;
        EXPECT_NE(m.find("1.3"), std::string::npos) << m;
        EXPECT_NE(m.find(file.string() + ":6"), std::string::npos) << m;
    }
}
