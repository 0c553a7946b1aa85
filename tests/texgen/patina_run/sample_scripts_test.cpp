// The samples' exposure terms act, and in the right direction (docs/your-asset.md, "The
// exposure in scripts"): samples/statue and samples/towers dry their wet-driven layers with
// the exposure map's `relative` channel. Each script runs on its sample's mesh with its own
// maps (baked small), and again with the sun taken away (`exposure` = 0: all shade). Shade
// keeps everything wetter, and most where the sun was: the growth of the wet-driven layers
// from the sunny run to the shaded one must rise with the texel's exposure. An exposure term
// that saturates (a map in J/m^2 clamped to [0, 1] is 1 everywhere) or is ignored makes that
// ratio the same on every texel, and fails.
#include "formats/texture_stack/texture_stack.h"

#include "core/image_io.h"

#include <gtest/gtest.h>

#include "test_util.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace patina {
namespace {

namespace fs = std::filesystem;

const std::string kBin = PATINA_TEST_BIN_DIR;
const std::string kSource = PATINA_SOURCE_DIR;

int run(const std::string& command) { return test::shell_status(command); }

using patina::test::read_text;

/// Per texel, the summed thickness of the stack's wet-driven layers: those made by a
/// statement of `script` whose line reads `wet` (a layer's `made_by` names its line).
std::vector<double> wet_thickness(const fs::path& stack_dir, const std::string& script,
                                  int& width, int& layers)
{
    std::vector<std::string> lines;
    std::istringstream in(script);
    for (std::string line; std::getline(in, line);)
        lines.push_back(line);
    const formats::TextureStack stack = formats::read_texture_stack(stack_dir);
    std::vector<double> sum;
    layers = 0;
    for (const formats::PatinaLayer& layer : formats::patina_of(stack).layers) {
        // "coat at <file>:<line>:<column>"
        const size_t colon = layer.made_by.rfind(".patina:");
        if (colon == std::string::npos)
            continue;
        const size_t line = std::stoul(layer.made_by.substr(colon + 8));
        if (line == 0 || line > lines.size() || lines[line - 1].find("wet") == std::string::npos)
            continue;
        ++layers;
        const ImageData image = read_image(stack.map(layer.map).files(stack.folder()).front());
        width = image.width;
        sum.resize(static_cast<size_t>(image.width) * image.height, 0.0);
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x)
                sum[static_cast<size_t>(y) * image.width + x] += image.at(x, y, layer.channel_index);
    }
    return sum;
}

/// Pearson's correlation of x and y over the pairs where `use` holds.
double correlation(const std::vector<double>& x, const std::vector<double>& y,
                   const std::vector<bool>& use)
{
    double n = 0, sx = 0, sy = 0, sxx = 0, syy = 0, sxy = 0;
    for (size_t i = 0; i < x.size(); ++i)
        if (use[i]) {
            n += 1;
            sx += x[i];
            sy += y[i];
            sxx += x[i] * x[i];
            syy += y[i] * y[i];
            sxy += x[i] * y[i];
        }
    const double cov = sxy / n - sx / n * sy / n;
    const double vx = sxx / n - sx / n * sx / n, vy = syy / n - sy / n * sy / n;
    return vx > 0 && vy > 0 ? cov / std::sqrt(vx * vy) : 0.0;
}

struct Sample {
    std::string name;      ///< the folder under samples/
    std::string mesh;      ///< patina-texgen mesh arguments
    std::string exposure;  ///< the exposure bake's site and period
    std::string times;     ///< --times of the patina run
};

void check_exposure_dries(const Sample& s)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "sample_scripts_test" / s.name;
    fs::remove_all(dir);
    fs::create_directories(dir);
    const std::string texgen = "'" + kBin + "/patina-texgen' ";
    const std::string mesh = (dir / "mesh.obj").string(), ground = (dir / "ground.obj").string();
    ASSERT_EQ(run(texgen + "mesh " + s.mesh + " -o '" + mesh + "'"), 0);
    ASSERT_EQ(run(texgen + "mesh plane --size 16 -o '" + ground + "'"), 0);
    const std::string common = "--mesh '" + mesh + "' --occluder '" + ground + "' -o '" +
                               (dir / "maps").string() + "' --resolution 64 --seed 1 --quiet ";
    ASSERT_EQ(run(texgen + "accessibility " + common + "--max-radius 0.2"), 0);
    ASSERT_EQ(run(texgen + "exposure " + common + s.exposure +
                  " --sky clear --sun-bins-deg 5 --sky-samples 64"), 0);

    // The script as shipped, and the same with the sun taken away.
    const std::string script = read_text(fs::path(kSource) / "samples" / s.name / (s.name + ".patina"));
    const std::string map_line = "map exposure = \"maps/exposure.exr\" \"relative\"";
    const size_t at = script.find(map_line);
    ASSERT_NE(at, std::string::npos) << s.name << ": the script reads its exposure as '"
                                     << map_line << "'";
    std::string shaded = script;
    shaded.replace(at, map_line.size(), "let exposure = 0");
    std::ofstream(dir / "sunny.patina") << script;
    std::ofstream(dir / "shaded.patina") << shaded;
    for (const char* run_name : {"sunny", "shaded"})
        ASSERT_EQ(run(texgen + "patina '" + (dir / (std::string(run_name) + ".patina")).string() +
                      "' --mesh '" + mesh + "' -o '" + (dir / run_name).string() +
                      "' --resolution 64 --times " + s.times + " --seed 1 --quiet --no-preview"),
                  0) << run_name;

    int width = 0, layers = 0;
    const std::vector<double> sunny = wet_thickness(dir / "sunny", script, width, layers);
    const std::vector<double> shade = wet_thickness(dir / "shaded", shaded, width, layers);
    ASSERT_GT(layers, 0) << s.name << ": no layer is grown by a statement that reads 'wet'";
    const ImageData exposure = read_image(dir / "maps" / "exposure.exr");
    const int relative = exposure.channel("relative"), coverage = exposure.channel("coverage.A");
    ASSERT_GE(relative, 0) << "the exposure map has no 'relative' channel";
    ASSERT_EQ(exposure.width, width);
    std::vector<double> ratio(sunny.size()), sun(sunny.size());
    std::vector<bool> use(sunny.size());
    size_t used = 0;
    for (int y = 0; y < exposure.height; ++y)
        for (int x = 0; x < exposure.width; ++x) {
            const size_t i = static_cast<size_t>(y) * width + x;
            use[i] = exposure.at(x, y, coverage) >= 1.0f && sunny[i] > 1e-3;
            ratio[i] = use[i] ? shade[i] / sunny[i] : 0.0;
            sun[i] = exposure.at(x, y, relative);
            used += use[i];
        }
    ASSERT_GT(used, 200u);
    const double r = correlation(sun, ratio, use);
    std::printf("[ samples  ] %s: the shade's growth over the sun's correlates with the "
                "texel's exposure by r = %.3f over %zu texels\n",
                s.name.c_str(), r, used);
    EXPECT_GT(r, 0.5) << s.name;
}

}  // namespace

TEST(SampleScripts, TheStatuesSunDriesItsWetPatina)
{
    check_exposure_dries({"statue", "statue",
                          "--latitude 41.9 --longitude 12.5 --timezone 1 --start 2026-01-01 "
                          "--end 2027-01-01",
                          "30"});
}

TEST(SampleScripts, TheTowersSunDriesItsStainsAndPatina)
{
    check_exposure_dries({"towers", "tower --size 4",
                          "--latitude 41.98 --longitude -87.9 --timezone -6 --start 2026-01-01 "
                          "--end 2027-01-01",
                          "40"});
}

}  // namespace patina
