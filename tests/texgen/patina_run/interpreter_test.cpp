// Running patina scripts: the three §5.1 scripts of Dorsey & Hanrahan 1996 on a strip, time
// series, the environment (curves, built-in fields, baked maps) and errors found at run time.
#include "texgen/patina/interpreter.h"
#include "texgen/patina/script_parser.h"

#include "core/image_io.h"
#include "test_util.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <sstream>

namespace fs = std::filesystem;
using namespace patina::texgen;

namespace {

const MaterialLibrary& library()
{
    static const MaterialLibrary lib = [] {
        patina::ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio" / "config.ocio");
        MaterialLibrary l;
        l.load(fs::path(PATINA_SOURCE_DIR) / "shaders/patina/copper.toml", colors);
        return l;
    }();
    return lib;
}

std::string read_text(const fs::path& path)
{
    std::ifstream in(path);
    std::stringstream s;
    s << in.rdbuf();
    return s.str();
}

std::vector<PatinaStep> run_text(const std::string& text, const PatinaDomain& domain,
                                 std::vector<double> times = {30.0}, uint64_t seed = 1)
{
    const Script script = parse_script(text, "test.patina", library().names());
    InterpreterOptions options;
    options.times_years = std::move(times);
    options.seed = seed;
    options.script_dir = PATINA_TEST_BUILD_DIR;
    options.ocio_config = fs::path(PATINA_SOURCE_DIR) / "ocio" / "config.ocio";
    return run_patina_script(script, library(), domain, options);
}

std::vector<PatinaStep> run_sample(const std::string& name, const PatinaDomain& domain,
                                   std::vector<double> times = {30.0})
{
    return run_text(read_text(fs::path(PATINA_SOURCE_DIR) / "samples/copper_strips" /
                              (name + ".patina")),
                    domain, std::move(times));
}

double mean(const std::vector<float>& v)
{
    return std::accumulate(v.begin(), v.end(), 0.0) / static_cast<double>(v.size());
}

double coverage(const std::vector<float>& v)
{
    return static_cast<double>(std::count_if(v.begin(), v.end(), [](float x) { return x > 0; })) /
           static_cast<double>(v.size());
}

float max_of(const std::vector<float>& v) { return *std::max_element(v.begin(), v.end()); }

std::string run_error(const std::string& text)
{
    const PatinaDomain strip = make_strip_domain(16, 16, 0.01);
    return patina::test::message_of([&] { run_text(text, strip); });
}

}  // namespace

TEST(PatinaScripts, CopperStripsFollowTheScriptsLayerByLayer)
{
    const PatinaDomain strip = make_strip_domain(64, 64, 0.02);
    // Materials bottom to top as the §5.1 scripts coat them (D&H 1996 §5.1).
    const std::vector<std::pair<std::string, std::vector<std::string>>> expected = {
        {"marine", {"tarnish", "cuprite", "marine patina 3", "marine patina 4"}},
        {"rural", {"tarnish", "cuprite", "rural patina 3", "rural patina 4"}},
        {"urban", {"tarnish", "cuprite urban 2", "patina urban 3", "patina urban 4", "dirt"}},
    };
    for (const auto& [name, materials] : expected) {
        const PatinaStep step = run_sample(name, strip).at(0);
        EXPECT_EQ(step.base->name, "copper") << name;
        ASSERT_EQ(step.layers.size(), materials.size()) << name;
        for (size_t l = 0; l < materials.size(); ++l)
            EXPECT_EQ(step.layers[l].material->name, materials[l]) << name << " layer " << l;
        // The total is the sum of the layers.
        for (size_t i = 0; i < strip.size(); i += 97) {
            float sum = 0;
            for (const ResultLayer& layer : step.layers)
                sum += layer.thickness_um[i];
            EXPECT_NEAR(step.total_um[i], sum, 1e-5f);
        }
    }
}

TEST(PatinaScripts, CoatThicknessIsTheLayersMaximumAtTheScriptsTime)
{
    const PatinaDomain strip = make_strip_domain(64, 64, 0.02);
    const PatinaStep rural = run_sample("rural", strip).at(0);
    // "coat tarnish 1 0.25 texture(ST cubic 1 20)": the map peaks at 1 (§3.2: "a specified
    // maximum thickness that is modulated by the thickness map").
    EXPECT_FLOAT_EQ(max_of(rural.layers[0].thickness_um), 0.25f);
    EXPECT_FLOAT_EQ(max_of(rural.layers[3].thickness_um), 1.1f);
}

TEST(PatinaScripts, UrbanDirtIsOnTopAndPartlyCoversTheErodedPatina)
{
    const PatinaDomain strip = make_strip_domain(96, 96, 0.02);
    const PatinaStep urban = run_sample("urban", strip).at(0);
    const ResultLayer& dirt = urban.layers.back();
    EXPECT_EQ(dirt.material->name, "dirt");
    // BD dirt (texture(BD linear 5 20)) is rough: thick in places, thin in others.
    const std::vector<float>& d = dirt.thickness_um;
    const auto [lo, hi] = std::minmax_element(d.begin(), d.end());
    EXPECT_FLOAT_EQ(*hi, 1.9f);
    EXPECT_LT(*lo, 0.5f * *hi);
    // The DPD patina patches cover part of the strip; the erosion (DPD linear 30 40, 0.8 µm)
    // cut through them in places: patina 4 is thinner than its coat somewhere it exists.
    const std::vector<float>& p4 = urban.layers[3].thickness_um;
    EXPECT_GT(coverage(p4), 0.02);
    EXPECT_LT(coverage(p4), 0.98);
    EXPECT_LT(mean(p4), 3.0);
}

TEST(PatinaScripts, ASeriesStartsFromBareCopperAndOnlyGrows)
{
    const PatinaDomain strip = make_strip_domain(48, 48, 0.02);
    const std::vector<double> times = {0, 6, 12, 18, 24, 30};
    const std::vector<PatinaStep> steps = run_sample("rural", strip, times);
    ASSERT_EQ(steps.size(), times.size());
    // t = 0: "the leftmost strips represent the appearance of pure copper" (§5.1).
    for (const ResultLayer& layer : steps[0].layers)
        EXPECT_EQ(max_of(layer.thickness_um), 0.0f);
    // The rural script only coats: every layer thickens with time at every texel.
    for (size_t k = 1; k < steps.size(); ++k)
        for (size_t l = 0; l < steps[k].layers.size(); ++l)
            for (size_t i = 0; i < strip.size(); ++i)
                ASSERT_GE(steps[k].layers[l].thickness_um[i],
                          steps[k - 1].layers[l].thickness_um[i])
                    << "t=" << times[k] << " layer " << l << " texel " << i;
    // The last step is the script as printed.
    const PatinaStep alone = run_sample("rural", strip).at(0);
    EXPECT_EQ(alone.total_um, steps.back().total_um);
}

TEST(PatinaScripts, CoatThenErodeOfTheSameMapRestoresTheStack)
{
    const PatinaDomain strip = make_strip_domain(32, 32, 0.01);
    const PatinaStep step = run_text("new copper\n"
                                     "coat cuprite 1.0 texture(RD linear 4 8)\n"
                                     "let spots = texture(DPD linear 10 40)\n"
                                     "coat dirt 2.0 spots\n"
                                     "erode 2.0 spots\n",
                                     strip)
                                .at(0);
    EXPECT_EQ(max_of(step.layers[1].thickness_um), 0.0f);
    EXPECT_GT(mean(step.layers[0].thickness_um), 0.0);
}

TEST(PatinaScripts, CurvesFieldsAndArithmetic)
{
    const PatinaDomain strip = make_strip_domain(8, 8, 0.01);
    const std::vector<PatinaStep> steps =
        run_text("curve c = (0 0, 10 1, 20 1)\n"
                 "new copper\n"
                 "coat tarnish 2.0 c * inclination\n"  // the strip faces up: inclination 1
                 "coat dirt 1.0 clamp(t / 10 - 1, 0, 1); render maps\n",
                 strip, {5, 15, 30});
    EXPECT_FLOAT_EQ(steps[0].layers[0].thickness_um[0], 1.0f);  // 2 * c(5) = 2 * 0.5
    EXPECT_FLOAT_EQ(steps[1].layers[0].thickness_um[0], 2.0f);
    EXPECT_FLOAT_EQ(steps[0].layers[1].thickness_um[0], 0.0f);  // clamp(-0.5) = 0
    EXPECT_FLOAT_EQ(steps[1].layers[1].thickness_um[0], 0.5f);
    EXPECT_FLOAT_EQ(steps[2].layers[1].thickness_um[0], 1.0f);
}

TEST(PatinaScripts, BakedMapsModulateThickness)
{
    // A 4x4 map with a ramp in x, read at the strip's texel centres.
    const fs::path file = fs::path(PATINA_TEST_BUILD_DIR) / "patina_run_ramp.exr";
    std::vector<float> ramp(16);
    for (int y = 0; y < 4; ++y)
        for (int x = 0; x < 4; ++x)
            ramp[y * 4 + x] = static_cast<float>(x);
    patina::write_image_atomic(file, ramp.data(), 4, 4, 1, {"wetness"}, OIIO::TypeDesc::FLOAT);
    const PatinaDomain strip = make_strip_domain(4, 4, 0.01);
    const PatinaStep step = run_text("map wet = \"patina_run_ramp.exr\"\n"
                                     "new copper\ncoat dirt 1.0 wet\n",
                                     strip)
                                .at(0);
    for (int x = 0; x < 4; ++x)
        EXPECT_NEAR(step.layers[0].thickness_um[x], static_cast<float>(x), 1e-5f);
}

TEST(PatinaScripts, SameBitsForAnyThreadCount)
{
    const PatinaDomain strip = make_strip_domain(64, 64, 0.02);
    std::vector<PatinaStep> one, two;
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
        one = run_sample("urban", strip);
    }
    {
        tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 2);
        two = run_sample("urban", strip);
    }
    for (size_t l = 0; l < one[0].layers.size(); ++l)
        EXPECT_EQ(one[0].layers[l].thickness_um, two[0].layers[l].thickness_um) << l;
}

TEST(PatinaScripts, RunTimeErrorsNameTheLineAndColumn)
{
    EXPECT_NE(run_error("coat dirt 1.0\n").find("test.patina:1:1: error: 'coat' before 'new'"),
              std::string::npos);
    EXPECT_NE(run_error("new copper\nnew copper\n").find("test.patina:2:1: error: a second 'new'"),
              std::string::npos);
    const std::string missing =
        run_error("map wet = \"no_such_map.exr\"\nnew copper\ncoat dirt 1.0 wet\n");
    EXPECT_NE(missing.find("test.patina:1:1: error:"), std::string::npos) << missing;
    EXPECT_NE(missing.find("no_such_map.exr"), std::string::npos) << missing;
    const std::string param =
        run_error("new copper\ncoat dirt 1.0 texture(DPD linear 1 2 patch_sise=0.1)\n");
    EXPECT_NE(param.find("test.patina:2:38: error: unknown texture parameter 'patch_sise' "
                         "(did you mean 'patch_size'?)"),
              std::string::npos)
        << param;
    const std::string nan = run_error("new copper\ncoat dirt 1.0 (t - t) / (t - t)\n");
    EXPECT_NE(nan.find("test.patina:2:"), std::string::npos) << nan;
    EXPECT_NE(nan.find("is NaN at node 0"), std::string::npos) << nan;
}
