// A user's own asset, in the conventions other programs write (docs/your-asset.md): Blender
// headless writes a figure 0.40 x 0.30 x 1.50 m as a Z-up FBX in centimetres, a Z-up COLLADA
// in centimetres and a glTF modelled in millimetres (tests/clients/blender_asset_corpus.py);
// each goes through uv-check, a bake, a patina script and export, and the exported glb is
// checked by the Khronos validator and opened by Blender: upright and in metres. Also uvs
// outside the tiles (refused, naming --uv-wrap; folded with it), the ground plane placed
// under the asset, an occluder that cuts through it, overlapping and missing uvs, a second
// uv set, three materials with an embedded texture (glb and FBX), a UDIM mesh, and bad
// options.
#include "core/image_io.h"
#include "core/mesh.h"
#include "texgen/export/gltf_document.h"

#include <Imath/ImathVec.h>

#include <gtest/gtest.h>

#include "test_util.h"
#include <nlohmann/json.hpp>
#include <toml++/toml.h>

#include <cstdint>
#include <cstdio>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>
#include <string>

#include <unistd.h>

namespace patina {
namespace {

namespace fs = std::filesystem;
namespace gltf = texgen::gltf;

const std::string kBin = PATINA_TEST_BIN_DIR;
const std::string kSource = PATINA_SOURCE_DIR;

struct Result {
    int status = -1;
    std::string out, err;
};

using patina::test::read_text;

/// Run `command` through the shell, capturing stdout and stderr.
Result run(const std::string& command, const fs::path& dir)
{
    const fs::path out = dir / "last.out", err = dir / "last.err";
    const int rc = std::system((command + " > '" + out.string() + "' 2> '" + err.string() + "'")
                                   .c_str());
    return {WIFEXITED(rc) ? WEXITSTATUS(rc) : -1, read_text(out), read_text(err)};
}

std::string texgen() { return "'" + kBin + "/patina-texgen'"; }
std::string quoted(const fs::path& p)
{
    // Appended, not "'" + ...: GCC 12 warns falsely (-Wrestrict, its bug 105329) on that.
    std::string s(1, '\'');
    s.append(p.string()).push_back('\'');
    return s;
}

/// The mean of `channel` over the texels a map covers (its coverage channel > 0).
double covered_mean(const fs::path& exr, const std::string& channel)
{
    const ImageData image = read_image(exr);
    const int c = image.channel(channel), a = image.channel("coverage.A");
    double sum = 0.0, weight = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x)
            if (image.at(x, y, a) > 0.0f) {
                sum += image.at(x, y, c);
                weight += 1.0;
            }
    return weight > 0.0 ? sum / weight : -1.0;
}

class OwnAsset : public ::testing::Test {
protected:
    /// The file blender_asset_corpus.py writes last.
    static constexpr const char* kLastOfCorpus = "two_tiles.glb";
    static fs::path corpus_;

    // The corpus once for all the tests: Blender takes seconds to start. CTest runs each
    // test in a process of its own, in parallel: the corpus is written into a folder of
    // this process and renamed into place, so no test reads a half-written file.
    static void SetUpTestSuite()
    {
        const fs::path root = fs::path(PATINA_TEST_BUILD_DIR) / "own_asset_test";
        corpus_ = root / "corpus";
        if (fs::exists(corpus_ / kLastOfCorpus))
            return;
        const fs::path mine = root / ("corpus." + std::to_string(::getpid()));
        fs::create_directories(mine);
        const std::string command =
            "blender -b --factory-startup --python-exit-code 1 --python '" + kSource +
            "/tests/clients/blender_asset_corpus.py' -- " + quoted(mine) + " > " +
            quoted(mine / "blender.log") + " 2>&1";
        if (std::system(command.c_str()) != 0) {
            corpus_ = mine;  // SetUp names its log
            return;
        }
        std::error_code ec;
        // A corpus of an older version of the script (without its last file) is replaced;
        // the rename fails when another process was first: then theirs is used.
        if (fs::exists(corpus_) && !fs::exists(corpus_ / kLastOfCorpus))
            fs::remove_all(corpus_, ec);
        fs::rename(mine, corpus_, ec);
        if (ec)
            fs::remove_all(mine, ec);
    }

    void SetUp() override
    {
        // Never skipped: without Blender the corpus is missing and the test says what to install.
        ASSERT_TRUE(fs::exists(corpus_ / kLastOfCorpus))
            << "Blender could not write the corpus (see " << (corpus_ / "blender.log").string()
            << "): install Debian 12's blender and python3-numpy (scripts/bootstrap.sh does)";
        dir_ = fs::path(PATINA_TEST_BUILD_DIR) / "own_asset_test" /
               ::testing::UnitTest::GetInstance()->current_test_info()->name();
        fs::remove_all(dir_);
        fs::create_directories(dir_);
    }

    Result texgen_run(const std::string& arguments) { return run(texgen() + " " + arguments, dir_); }

    /// Accessibility baked on `mesh` with `options` into `out`.
    Result bake_accessibility(const fs::path& mesh, const fs::path& out, const std::string& options)
    {
        return texgen_run("accessibility --mesh " + quoted(mesh) + " -o " + quoted(out) +
                          " --resolution 48 --max-radius 0.3 --seed 1 --quiet " + options);
    }

    /// The mesh's stack grown by a small script reading `maps`' accessibility, exported to a
    /// glb that the validator passes; Blender's report of it.
    nlohmann::json grow_export_open(const fs::path& mesh, const fs::path& maps,
                                    const std::string& options)
    {
        std::ofstream(maps.parent_path() / "grow.patina")
            << "new copper\nmap accessibility = \"" << maps.filename().string()
            << "/accessibility.exr\" \"accessibility\"\ncoat tarnish 1.0 0.5 * accessibility\n"
               "render maps\n";
        const Result grow = texgen_run("patina " + quoted(maps.parent_path() / "grow.patina") +
                                    " --mesh " + quoted(mesh) + " -o " + quoted(dir_ / "stack") +
                                    " --resolution 32 --quiet --no-preview " + options);
        EXPECT_EQ(grow.status, 0) << grow.err;
        const fs::path glb = dir_ / "asset.glb";
        const Result exported = texgen_run("export " + quoted(dir_ / "stack") + " -o " +
                                        quoted(glb) + " --quiet");
        EXPECT_EQ(exported.status, 0) << exported.err;
        return validate_and_open(glb);
    }

    /// The Khronos validator on `glb` (0 errors, 0 warnings), then Blender's importer
    /// (tests/clients/blender_gltf_check.py): its report.
    nlohmann::json validate_and_open(const fs::path& glb)
    {
        const Result valid = run("node '" + kSource + "/tests/clients/validate_gltf.mjs' " +
                                     quoted(glb), dir_);
        EXPECT_EQ(valid.status, 0) << valid.out << valid.err;
        const fs::path report = dir_ / "blender.json";
        const Result opened = run("blender -b --factory-startup --python-exit-code 1 --python '" +
                                      kSource + "/tests/clients/blender_gltf_check.py' -- " +
                                      quoted(glb) + " " + quoted(report), dir_);
        EXPECT_EQ(opened.status, 0) << opened.out.substr(0, 4000);
        std::ifstream in(report);
        return in ? nlohmann::json::parse(in) : nlohmann::json();
    }

    /// The figure upright in metres in Blender's axes (Z up): 0.40 x 0.30 x 1.50 m, standing
    /// on z = 0.
    static void expect_upright_figure(const nlohmann::json& report)
    {
        ASSERT_FALSE(report.is_null());
        const auto& lo = report["bounds_min"];
        const auto& hi = report["bounds_max"];
        EXPECT_NEAR(hi[0].get<double>() - lo[0].get<double>(), 0.40, 1e-4);
        EXPECT_NEAR(hi[1].get<double>() - lo[1].get<double>(), 0.30, 1e-4);
        EXPECT_NEAR(hi[2].get<double>() - lo[2].get<double>(), 1.50, 1e-4);
        EXPECT_NEAR(lo[2].get<double>(), 0.0, 1e-4);
    }

    /// patina-render reads the mesh by its declaration (and `object_keys`, e.g. unit = "mm")
    /// too: the grown stack (grow_export_open's) on the figure, lit by a sun, seen from the
    /// front against a black sky (no environment). The figure's pixels (any that are not
    /// black) span 1.5 m up and 0.4 m across.
    void expect_rendered_upright(const fs::path& mesh, const std::string& object_keys)
    {
        const fs::path scene = dir_ / "figure.toml";
        std::ofstream(scene) << "[film]\nwidth = 64\nheight = 64\nspp = 4\nseed = 1\n"
                                "[camera]\nfrom = [0.0, 0.75, 6.0]\nto = [0.0, 0.75, 0.0]\n"
                                "fov_deg = 20\n[sun]\nelevation_deg = 30\nazimuth_deg = 180\n"
                                "irradiance = 3.0\n[[shader]]\nname = \"patina\"\n"
                                "type = \"layered_km\"\nstack = \""
                             << (dir_ / "stack" / "stack.toml").string()
                             << "\"\n[[object]]\nmesh = \"" << mesh.string()
                             << "\"\nbsdf = \"patina\"\n"
                             << object_keys;
        const fs::path exr = dir_ / "figure.exr";
        const Result rendered =
            run("'" + kBin + "/patina-render' " + quoted(scene) + " -o " + quoted(exr) + " --quiet",
                dir_);
        ASSERT_EQ(rendered.status, 0) << rendered.err;
        const ImageData image = read_image(exr);
        int rows_lo = image.height, rows_hi = -1, cols_lo = image.width, cols_hi = -1;
        for (int y = 0; y < image.height; ++y)
            for (int x = 0; x < image.width; ++x)
                if (image.at(x, y, 0) + image.at(x, y, 1) + image.at(x, y, 2) > 0.0f) {
                    rows_lo = std::min(rows_lo, y);
                    rows_hi = std::max(rows_hi, y);
                    cols_lo = std::min(cols_lo, x);
                    cols_hi = std::max(cols_hi, x);
                }
        ASSERT_GE(rows_hi, 0) << "the figure is not in the picture";
        // 20 degrees at 6 m: 2.12 m over 64 rows, 30 px a metre: 1.5 m is 45 rows, 0.4 m 12
        // columns.
        EXPECT_NEAR(rows_hi - rows_lo + 1, 45, 3);
        EXPECT_NEAR(cols_hi - cols_lo + 1, 12, 3);
    }

    fs::path dir_;
};

fs::path OwnAsset::corpus_;

TEST_F(OwnAsset, ZUpFbxInCentimetresBakesUprightAndExportsInMetres)
{
    const fs::path fbx = corpus_ / "figure_zup_cm.fbx";
    const Result check = texgen_run("uv-check " + quoted(fbx) + " --resolution 64");
    ASSERT_EQ(check.status, 0) << check.err;
    EXPECT_NE(check.out.find("up +z (FBX GlobalSettings), unit cm (FBX GlobalSettings)"),
              std::string::npos) << check.out;
    EXPECT_EQ(check.err.find("warning"), std::string::npos) << check.err;

    const Result baked = bake_accessibility(fbx, dir_ / "maps", "--ground");
    ASSERT_EQ(baked.status, 0) << baked.err;
    const toml::table stack = toml::parse_file((dir_ / "maps" / "stack.toml").string());
    const auto* parameters = stack["maps"]["accessibility"]["parameters"].as_table();
    ASSERT_NE(parameters, nullptr);
    EXPECT_EQ((*parameters)["mesh_up"].value_or(std::string()), "+z");
    EXPECT_NEAR((*parameters)["mesh_metres_per_unit"].value_or(0.0), 0.01, 1e-9);

    // The same file read as metres: a 150 m figure, for which a 30 cm sphere reaches every
    // crevice; the options warn twice (a unit against the file's, a size against reason).
    const Result as_metres = bake_accessibility(fbx, dir_ / "maps_m", "--ground --unit m");
    ASSERT_EQ(as_metres.status, 0) << as_metres.err;
    EXPECT_NE(as_metres.err.find("the file declares its unit as cm (FBX GlobalSettings)"),
              std::string::npos) << as_metres.err;
    EXPECT_NE(as_metres.err.find("--unit cm"), std::string::npos) << as_metres.err;
    const double right = covered_mean(dir_ / "maps" / "accessibility.exr", "accessibility");
    const double wrong = covered_mean(dir_ / "maps_m" / "accessibility.exr", "accessibility");
    std::printf("[ own asset ] mean accessibility: %.3f in centimetres, %.3f read as metres\n",
                right, wrong);
    EXPECT_LT(right, wrong - 0.02);

    // patina reads the unit from the maps' stack; export writes +Y-up metres.
    expect_upright_figure(grow_export_open(fbx, dir_ / "maps", ""));

    expect_rendered_upright(fbx, "");
}

TEST_F(OwnAsset, ColladaUnitAndUpAxisAreHonoured)
{
    const fs::path dae = corpus_ / "figure_zup_cm.dae";
    const Result check = texgen_run("uv-check " + quoted(dae));
    ASSERT_EQ(check.status, 0) << check.err;
    EXPECT_NE(check.out.find("up +z (COLLADA <asset>), unit cm (COLLADA <asset>)"),
              std::string::npos) << check.out;
    ASSERT_EQ(bake_accessibility(dae, dir_ / "maps", "--ground").status, 0);
    expect_upright_figure(grow_export_open(dae, dir_ / "maps", ""));
    expect_rendered_upright(dae, "");
}

TEST_F(OwnAsset, AGltfInMillimetresIsNamedAndTheUnitOptionFixesIt)
{
    const fs::path glb = corpus_ / "figure_mm.glb";
    const Result check = texgen_run("uv-check " + quoted(glb));
    ASSERT_EQ(check.status, 0) << check.err;
    EXPECT_NE(check.err.find("1500 m along its longest side"), std::string::npos) << check.err;
    EXPECT_NE(check.err.find("--unit mm"), std::string::npos) << check.err;

    const Result baked = bake_accessibility(glb, dir_ / "maps", "--ground --unit mm");
    ASSERT_EQ(baked.status, 0) << baked.err;
    EXPECT_NE(baked.err.find("the file declares its unit as m (glTF"), std::string::npos)
        << baked.err;
    EXPECT_EQ(baked.err.find("longest side"), std::string::npos) << baked.err;
    // A later step that contradicts the stack is refused; one that says nothing agrees.
    std::ofstream(dir_ / "grow.patina") << "new copper\nmap accessibility = "
                                           "\"maps/accessibility.exr\"\nrender maps\n";
    const Result contradicted = texgen_run("patina " + quoted(dir_ / "grow.patina") + " --mesh " +
                                        quoted(glb) + " --unit cm -o " + quoted(dir_ / "bad") +
                                        " --resolution 16 --quiet");
    EXPECT_NE(contradicted.status, 0);
    EXPECT_NE(contradicted.err.find("was made with the mesh in mm, not cm"), std::string::npos)
        << contradicted.err;
    expect_upright_figure(grow_export_open(glb, dir_ / "maps", ""));
    expect_rendered_upright(glb, "unit = \"mm\"\n");
}

TEST_F(OwnAsset, UvsOutsideTheTilesAreRefusedNamingUvWrapAndFoldedWithIt)
{
    // A 1 m square whose uvs lie one tile left and one below the unit tile.
    const fs::path obj = dir_ / "negative_uvs.obj";
    std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nvt -1 -1\nvt -0.01 -1\n"
                          "vt -0.01 -0.01\nvt -1 -0.01\nvn 0 1 0\n"
                          "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n";
    const Result refused = texgen_run("ao --mesh " + quoted(obj) + " -o " + quoted(dir_ / "ao") +
                                   " --resolution 16 --rays 4 --quiet");
    EXPECT_EQ(refused.status, 1);
    EXPECT_NE(refused.err.find("--uv-wrap folds them into tile 1001"), std::string::npos)
        << refused.err;
    EXPECT_FALSE(fs::exists(dir_ / "ao" / "ao.exr"));

    // uv-check says the same, and exits non-zero as the bakers would.
    const Result check = texgen_run("uv-check " + quoted(obj));
    EXPECT_EQ(check.status, 1);
    EXPECT_NE(check.out.find("will refuse the mesh: 2 triangles lie outside"), std::string::npos)
        << check.out;
    const Result wrapped_check = texgen_run("uv-check " + quoted(obj) + " --uv-wrap");
    EXPECT_EQ(wrapped_check.status, 0) << wrapped_check.err;
    EXPECT_NE(wrapped_check.out.find("will bake 2 triangles (2 folded into tile 1001"),
              std::string::npos) << wrapped_check.out;

    const Result wrapped = texgen_run("ao --mesh " + quoted(obj) + " -o " + quoted(dir_ / "ao") +
                                   " --resolution 16 --rays 4 --quiet --uv-wrap");
    ASSERT_EQ(wrapped.status, 0) << wrapped.err;
    // The square fills 0.99 of the tile: nearly every texel is baked, AO 1 under an open sky.
    EXPECT_NEAR(covered_mean(dir_ / "ao" / "ao.exr", "ao"), 1.0, 1e-6);
    const toml::table stack = toml::parse_file((dir_ / "ao" / "stack.toml").string());
    EXPECT_EQ(stack["maps"]["ao"]["parameters"]["uv_wrap"].value_or(0), 1);
}

TEST_F(OwnAsset, TheGroundGoesUnderTheAssetAndAnOccluderThroughItIsReported)
{
    const fs::path fbx = corpus_ / "figure_zup_cm.fbx";
    // A ground plane at half the figure's height: it cuts the figure in two.
    const fs::path cut = dir_ / "cut.obj";
    std::ofstream(cut) << "v -5 0.75 5\nv 5 0.75 5\nv 5 0.75 -5\nv -5 0.75 -5\nf 1 2 3\nf 1 3 4\n";
    const Result cutting = bake_accessibility(fbx, dir_ / "cut", "--occluder " + quoted(cut));
    ASSERT_EQ(cutting.status, 0) << cutting.err;
    EXPECT_NE(cutting.err.find("cuts through the baked mesh"), std::string::npos) << cutting.err;
    EXPECT_NE(cutting.err.find("--ground places a ground plane there"), std::string::npos);

    const Result grounded = bake_accessibility(fbx, dir_ / "ground", "--ground");
    ASSERT_EQ(grounded.status, 0) << grounded.err;
    EXPECT_EQ(grounded.err.find("cuts through"), std::string::npos) << grounded.err;
    const toml::table stack = toml::parse_file((dir_ / "ground" / "stack.toml").string());
    EXPECT_NEAR(stack["maps"]["accessibility"]["parameters"]["ground_y"].value_or(1.0), 0.0, 1e-5);
    // On the ground the figure's foot is less accessible than standing in the air.
    const Result floating = bake_accessibility(fbx, dir_ / "air", "");
    ASSERT_EQ(floating.status, 0) << floating.err;
    EXPECT_LT(covered_mean(dir_ / "ground" / "accessibility.exr", "accessibility"),
              covered_mean(dir_ / "air" / "accessibility.exr", "accessibility"));
}

/// The mean linear RGB of the pixels in columns [x0, x1) and rows [y0, y1) of an image.
/// The JSON chunk of a .glb (glTF 2.0 §4.4.3).
nlohmann::json glb_json(const fs::path& glb)
{
    const std::string bytes = read_text(glb);
    if (bytes.size() < 20)
        return {};
    uint32_t length = 0;
    std::memcpy(&length, bytes.data() + 12, 4);
    return nlohmann::json::parse(bytes.substr(20, length));
}

/// The bytes of image `index` of a .glb: its buffer view in the BIN chunk (glTF 2.0 §4.4.3.3).
std::vector<unsigned char> glb_image(const fs::path& glb, int index)
{
    const std::string bytes = read_text(glb);
    const nlohmann::json gltf = glb_json(glb);
    uint32_t json_length = 0;
    std::memcpy(&json_length, bytes.data() + 12, 4);
    const size_t bin = 20 + json_length + 8;  // past the JSON chunk and the BIN chunk's header
    const auto& view = gltf["bufferViews"][gltf["images"][index]["bufferView"].get<int>()];
    const size_t offset = bin + view.value("byteOffset", size_t(0));
    const size_t length = view["byteLength"].get<size_t>();
    if (offset + length > bytes.size())
        return {};
    return std::vector<unsigned char>(bytes.begin() + static_cast<std::ptrdiff_t>(offset),
                                      bytes.begin() + static_cast<std::ptrdiff_t>(offset + length));
}

Imath::V3d mean_rgb(const ImageData& image, int x0, int x1, int y0, int y1)
{
    Imath::V3d sum(0.0);
    const int r = image.channel("R"), g = image.channel("G"), b = image.channel("B");
    for (int y = y0; y < y1; ++y)
        for (int x = x0; x < x1; ++x)
            sum += Imath::V3d(image.at(x, y, r), image.at(x, y, g), image.at(x, y, b));
    return sum / (static_cast<double>(x1 - x0) * (y1 - y0));
}

TEST_F(OwnAsset, AUdimStackRendersEveryTileWithLayeredKm)
{
    // Blender's two 1 m squares side by side facing up (x from 0 and from 1.5 m, z from 0 to
    // -1 m in Patina's axes), the left on tile 1001, the right on 1002, under a uniform layer
    // of Dorsey & Hanrahan 1996 §5.1's rural patina, 20 um: both must look alike, and unlike
    // bare copper. Were tile 1002 not read, the right quad would render as bare copper (a
    // thickness of 0).
    const fs::path obj = corpus_ / "two_tiles.glb";
    const auto render_grown = [&](const std::string& name, const std::string& script) {
        std::ofstream(dir_ / (name + ".patina")) << script;
        const Result grown = texgen_run("patina " + quoted(dir_ / (name + ".patina")) +
                                        " --mesh " + quoted(obj) + " -o " +
                                        quoted(dir_ / name) + " --resolution 16 --quiet "
                                        "--no-preview");
        EXPECT_EQ(grown.status, 0) << grown.err;
        const fs::path scene = dir_ / (name + ".toml");
        std::ofstream(scene) << "[film]\nwidth = 80\nheight = 32\nspp = 16\nseed = 1\n"
                                "[camera]\nfrom = [1.25, 4.0, -0.5]\nto = [1.25, 0.0, -0.5]\n"
                                "up = [0.0, 0.0, -1.0]\nfov_deg = 16.5\n[environment]\n"
                                "color = [1.0, 1.0, 1.0]\ncolorspace = \"lin_rec709\"\n"
                                "[[shader]]\nname = \"patina\"\ntype = \"layered_km\"\n"
                                "stack = \""
                             << (dir_ / name / "stack.toml").string()
                             << "\"\n[[object]]\nmesh = \"" << obj.string()
                             << "\"\nbsdf = \"patina\"\n";
        const fs::path exr = dir_ / (name + ".exr");
        const Result rendered = run("'" + kBin + "/patina-render' " + quoted(scene) + " -o " +
                                        quoted(exr) + " --quiet", dir_);
        EXPECT_EQ(rendered.status, 0) << rendered.err;
        return read_image(exr);
    };
    const ImageData patina =
        render_grown("patina", "new copper\ncoat rural patina 3 1.0 20\nrender maps\n");
    const ImageData copper = render_grown("copper", "new copper\nrender maps\n");
    ASSERT_GT(patina.width, 0);
    ASSERT_GT(copper.width, 0);
    // 32 rows span 1.16 m at 4 m (16.5 degrees): 27.6 px a metre; the quads' centres,
    // x = 0.5 and 2.0 m, lie 0.75 m either side of the axis, at columns 19 and 61.
    const auto quad = [](const ImageData& image, int centre) {
        return mean_rgb(image, centre - 6, centre + 6, 6, 26);
    };
    const Imath::V3d left = quad(patina, 19), right = quad(patina, 61);
    const Imath::V3d bare = quad(copper, 61);
    std::printf("[ own asset ] UDIM render: tile 1001 (%.3f, %.3f, %.3f), tile 1002 (%.3f, "
                "%.3f, %.3f), bare copper (%.3f, %.3f, %.3f)\n",
                left.x, left.y, left.z, right.x, right.y, right.z, bare.x, bare.y, bare.z);
    EXPECT_LT((right - left).length(), 0.05 * left.length());
    EXPECT_GT((right - bare).length(), 0.3 * bare.length());

    // Exported: a material per tile, each square on its own; valid, and Blender opens it
    // 2.5 m wide, flat.
    const fs::path glb = dir_ / "two_tiles.glb";
    const Result exported = texgen_run("export " + quoted(dir_ / "patina") + " -o " +
                                       quoted(glb) + " --quiet");
    ASSERT_EQ(exported.status, 0) << exported.err;
    const nlohmann::json gltf = glb_json(glb);
    EXPECT_EQ(gltf["meshes"][0]["primitives"].size(), 2u);
    EXPECT_EQ(gltf["materials"].size(), 2u) << gltf["materials"].dump();
    const nlohmann::json blender = validate_and_open(glb);
    ASSERT_FALSE(blender.is_null());
    EXPECT_NEAR(blender["dimensions"][0].get<double>(), 2.5, 1e-4);
    EXPECT_NEAR(blender["dimensions"][2].get<double>(), 0.0, 1e-4);
}

TEST_F(OwnAsset, MirroredHalvesGetAUniqueLayoutAndExportKeepsTheArtistsUvs)
{
    // Two 1 m squares side by side sharing one uv square, the second mirrored: the usual
    // mirrored halves of a symmetric model. uv-check names the overlap and the remedy.
    const fs::path obj = dir_ / "mirrored.obj";
    std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 1 0 -1\nv 0 0 -1\nv -1 0 0\nv -1 0 -1\n"
                          "vt 0 0\nvt 1 0\nvt 1 1\nvt 0 1\nvn 0 1 0\n"
                          "f 1/1/1 2/2/1 3/3/1\nf 1/1/1 3/3/1 4/4/1\n"
                          "f 1/1/1 6/3/1 5/2/1\nf 1/1/1 4/4/1 6/3/1\n";
    const Result overlapping = texgen_run("uv-check " + quoted(obj) + " --resolution 64");
    ASSERT_EQ(overlapping.status, 0) << overlapping.err;
    EXPECT_NE(overlapping.out.find("overlapping uvs  100% of the covered uv area"),
              std::string::npos) << overlapping.out;
    EXPECT_NE(overlapping.out.find("patina-texgen unwrap MESH -o OUT.glb"), std::string::npos);
    EXPECT_NE(overlapping.out.find("mirrored uvs     2 triangles"), std::string::npos)
        << overlapping.out;

    const fs::path unwrapped = dir_ / "mirrored_unwrapped.glb";
    const Result unwrap = texgen_run("unwrap " + quoted(obj) + " -o " + quoted(unwrapped) +
                                     " --resolution 256");
    ASSERT_EQ(unwrap.status, 0) << unwrap.err << unwrap.out;
    EXPECT_NE(unwrap.out.find("uv set           1 (bake with --uv-set 1)"), std::string::npos)
        << unwrap.out;
    EXPECT_NE(unwrap.out.find("overlapping uvs  0% of the covered area"), std::string::npos)
        << unwrap.out;
    const Result check = texgen_run("uv-check " + quoted(unwrapped) + " --uv-set 1");
    ASSERT_EQ(check.status, 0) << check.err;
    EXPECT_NE(check.out.find("uvs              set 1 of 2"), std::string::npos) << check.out;
    EXPECT_NE(check.out.find("overlapping uvs  none"), std::string::npos) << check.out;

    // Baked into the new set; the growth and the export follow the stack's record.
    const Result baked = texgen_run("ao --mesh " + quoted(unwrapped) + " --uv-set 1 -o " +
                                    quoted(dir_ / "maps") + " --resolution 32 --rays 8 --quiet");
    ASSERT_EQ(baked.status, 0) << baked.err;
    std::ofstream(dir_ / "grow.patina") << "new copper\nmap ao = \"maps/ao.exr\" \"ao\"\n"
                                           "coat tarnish 1.0 0.5 * ao\nrender maps\n";
    const Result grown = texgen_run("patina " + quoted(dir_ / "grow.patina") + " --mesh " +
                                    quoted(unwrapped) + " -o " + quoted(dir_ / "stack") +
                                    " --resolution 32 --quiet --no-preview");
    ASSERT_EQ(grown.status, 0) << grown.err;
    const fs::path glb = dir_ / "mirrored.glb";
    const Result exported = texgen_run("export " + quoted(dir_ / "stack") + " -o " +
                                       quoted(glb) + " --quiet");
    ASSERT_EQ(exported.status, 0) << exported.err;
    const nlohmann::json gltf = glb_json(glb);
    const auto& attributes = gltf["meshes"][0]["primitives"][0]["attributes"];
    EXPECT_TRUE(attributes.contains("TEXCOORD_0"));
    EXPECT_TRUE(attributes.contains("TEXCOORD_1"));
    const auto& material = gltf["materials"][0];
    EXPECT_EQ(material["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"], 1);
    EXPECT_EQ(material["normalTexture"]["texCoord"], 1);
    const nlohmann::json blender = validate_and_open(glb);
    ASSERT_FALSE(blender.is_null());
    EXPECT_EQ(blender["uv_maps"].size(), 2u) << blender.dump();
}

TEST_F(OwnAsset, ASecondUvSetIsReadAsTheFileHasIt)
{
    // Two triangles of a square: vertices 0 and 2 are written twice, equal in position and
    // first uv set but not in the second (an island seam of a new layout). Assimp 5.2's
    // vertex joining merged such vertices, moving set 1's uvs (core/mesh.cpp).
    gltf::Document doc;
    const std::vector<Imath::V3f> positions{{0, 0, 0}, {1, 0, 0}, {1, 0, -1}, {0, 0, 0}, {1, 0, -1}, {0, 0, -1}};
    const std::vector<Imath::V2f> first{{0, 1}, {1, 1}, {1, 0}, {0, 1}, {1, 0}, {0, 0}};
    const std::vector<Imath::V2f> second{{0, 1}, {0.4f, 1}, {0.4f, 0.6f}, {0.5f, 0.5f}, {0.9f, 0.1f}, {0.5f, 0.1f}};
    const std::vector<uint32_t> indices{0, 1, 2, 3, 4, 5};
    const auto accessor = [&](const auto& values, int target, int component, const char* type,
                              std::vector<float> lo = {}, std::vector<float> hi = {}) {
        const int view = doc.add_view(values.data(), values.size() * sizeof(values[0]), target);
        return doc.add_accessor(view, component, values.size(), type, lo, hi);
    };
    const nlohmann::json primitive = {
        {"attributes",
         {{"POSITION", accessor(positions, gltf::kArrayBuffer, gltf::kFloat, "VEC3", {0, 0, -1}, {1, 0, 0})},
          {"TEXCOORD_0", accessor(first, gltf::kArrayBuffer, gltf::kFloat, "VEC2")},
          {"TEXCOORD_1", accessor(second, gltf::kArrayBuffer, gltf::kFloat, "VEC2")}}},
        {"indices", accessor(indices, gltf::kElementArrayBuffer, gltf::kUnsignedInt, "SCALAR")}};
    const int mesh = doc.add("meshes", {{"primitives", {primitive}}});
    doc.add("scenes", {{"nodes", {doc.add("nodes", {{"mesh", mesh}})}}});
    const fs::path glb = dir_ / "two_sets.glb";
    std::ofstream(glb, std::ios::binary) << doc.glb();

    MeshConventionOptions set1;
    set1.uv_set = 1;
    const std::vector<TriangleMesh> meshes = load_meshes(glb, set1);
    ASSERT_EQ(meshes.size(), 1u);
    const TriangleMesh& m = meshes[0];
    ASSERT_EQ(m.uvs.size(), m.source_uvs.size());
    EXPECT_EQ(m.uv_set, 1);
    EXPECT_EQ(m.uv_set_count, 2);
    // Every corner keeps its own second-set uv: triangle 0's corner at (0, 0, 0) reads
    // (0, 1), triangle 1's reads (0.5, 0.5) (glTF's v down; Patina's v up: 1 - v).
    for (size_t t = 0; t < m.triangle_count(); ++t)
        for (int k = 0; k < 3; ++k) {
            const uint32_t v = m.indices[3 * t + k];
            const size_t written = 3 * t + static_cast<size_t>(k);
            EXPECT_EQ(m.positions[v], positions[written]) << "triangle " << t << " corner " << k;
            EXPECT_EQ(m.uvs[v], Imath::V2f(second[written].x, 1.0f - second[written].y))
                << "triangle " << t << " corner " << k;
        }
}

TEST_F(OwnAsset, AMeshWithoutUvsGetsThereInOneCommand)
{
    const fs::path obj = dir_ / "no_uvs.obj";
    std::ofstream(obj) << "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\n"
                          "v 0 1 1\nf 1 4 3 2\nf 5 6 7 8\nf 1 2 6 5\nf 2 3 7 6\nf 3 4 8 7\n"
                          "f 4 1 5 8\n";
    const Result refused = texgen_run("ao --mesh " + quoted(obj) + " -o " + quoted(dir_ / "x") +
                                      " --resolution 16 --quiet");
    EXPECT_EQ(refused.status, 1);
    const fs::path unwrapped = dir_ / "cube.glb";
    const Result unwrap = texgen_run("unwrap " + quoted(obj) + " -o " + quoted(unwrapped) +
                                     " --method lightmap --quiet");
    ASSERT_EQ(unwrap.status, 0) << unwrap.err;
    const Result baked = texgen_run("ao --mesh " + quoted(unwrapped) + " -o " +
                                    quoted(dir_ / "maps") + " --resolution 32 --rays 8 --quiet");
    ASSERT_EQ(baked.status, 0) << baked.err;
    // A closed cube seen from outside: every face is open to the sky it faces.
    EXPECT_NEAR(covered_mean(dir_ / "maps" / "ao.exr", "ao"), 1.0, 1e-6);

    // Blender missing: one message naming what to install, nothing written.
    const Result missing = texgen_run("unwrap " + quoted(obj) + " -o " +
                                      quoted(dir_ / "none.glb") + " --blender /nonexistent/blender");
    EXPECT_EQ(missing.status, 1);
    EXPECT_NE(missing.err.find("install Debian's blender"), std::string::npos) << missing.err;
    EXPECT_FALSE(fs::exists(dir_ / "none.glb"));
}

TEST_F(OwnAsset, SourceMaterialsMaskTheScriptAndKeepPatinaOff)
{
    // Three 1 m squares of three materials side by side (bronze, glass, rubber), each on its
    // own third of tile 1001, as an OBJ with its material file.
    std::ofstream(dir_ / "parts.mtl") << "newmtl Bronze\nKd 0.6 0.4 0.2\nnewmtl Glass\nKd 0.9 0.9 0.9\n"
                                         "newmtl Rubber\nKd 1 1 1\nmap_Kd tread.png\n";
    // The rubber's own texture: a 4 x 4 grey tread.
    const std::vector<float> tread(4 * 4 * 3, 0.2f);
    write_image_atomic(dir_ / "tread.png", tread.data(), 4, 4, 3, {}, OIIO::TypeDesc::UINT8);
    std::ofstream obj(dir_ / "parts.obj");
    obj << "mtllib parts.mtl\nvn 0 1 0\n";
    const char* names[] = {"Bronze", "Glass", "Rubber"};
    for (int k = 0; k < 3; ++k) {
        const float x = 1.5f * k, u = 0.35f * k;
        obj << "v " << x << " 0 0\nv " << x + 1 << " 0 0\nv " << x + 1 << " 0 -1\nv " << x
            << " 0 -1\nvt " << u << " 0\nvt " << u + 0.3f << " 0\nvt " << u + 0.3f << " 1\nvt "
            << u << " 1\nusemtl " << names[k] << "\nf " << 4 * k + 1 << "/" << 4 * k + 1 << "/1 "
            << 4 * k + 2 << "/" << 4 * k + 2 << "/1 " << 4 * k + 3 << "/" << 4 * k + 3 << "/1\nf "
            << 4 * k + 1 << "/" << 4 * k + 1 << "/1 " << 4 * k + 3 << "/" << 4 * k + 3 << "/1 "
            << 4 * k + 4 << "/" << 4 * k + 4 << "/1\n";
    }
    obj.close();
    std::ofstream(dir_ / "masked.patina") << "new copper\nmap glass = material \"Glass\"\n"
                                             "coat tarnish 1.0 2 * (1 - glass)\nrender maps\n";
    const Result grown = texgen_run("patina " + quoted(dir_ / "masked.patina") + " --mesh " +
                                    quoted(dir_ / "parts.obj") + " --keep-off Rubber -o " +
                                    quoted(dir_ / "stack") + " --resolution 40 --quiet --no-preview");
    ASSERT_EQ(grown.status, 0) << grown.err;
    const ImageData total = read_image(dir_ / "stack" / "total_thickness.exr");
    const int c = total.channel("thickness");
    ASSERT_GE(c, 0);
    // The middle row of each part's third of the tile: 40 texels, 12 to a part.
    const auto at_u = [&](float u) { return total.at(static_cast<int>(u * 40), 20, c); };
    EXPECT_NEAR(at_u(0.15f), 2.0f, 1e-5f);  // bronze: the script's 2 um
    EXPECT_EQ(at_u(0.50f), 0.0f);           // glass: masked by the script
    EXPECT_EQ(at_u(0.85f), 0.0f);           // rubber: --keep-off
    const toml::table stack = toml::parse_file((dir_ / "stack" / "stack.toml").string());
    EXPECT_EQ(stack["maps"]["total_thickness"]["parameters"]["keep_off"].value_or(std::string()),
              "Rubber");

    // A material the mesh does not have is named, with the ones it has.
    std::ofstream(dir_ / "typo.patina") << "new copper\nmap glass = material \"Glas\"\n"
                                           "coat tarnish 1.0 2 * glass\nrender maps\n";
    const Result typo = texgen_run("patina " + quoted(dir_ / "typo.patina") + " --mesh " +
                                   quoted(dir_ / "parts.obj") + " -o " + quoted(dir_ / "bad") +
                                   " --resolution 16 --quiet");
    EXPECT_EQ(typo.status, 1);
    EXPECT_NE(typo.err.find("no material 'Glas' (its materials: 'Bronze', 'Glass', 'Rubber')"),
              std::string::npos) << typo.err;
    const Result keep_typo = texgen_run("patina " + quoted(dir_ / "masked.patina") + " --mesh " +
                                        quoted(dir_ / "parts.obj") + " --keep-off Rubbr -o " +
                                        quoted(dir_ / "bad") + " --resolution 16 --quiet");
    EXPECT_EQ(keep_typo.status, 1);
    EXPECT_NE(keep_typo.err.find("--keep-off: the mesh has no material 'Rubbr'"),
              std::string::npos) << keep_typo.err;
    EXPECT_FALSE(fs::exists(dir_ / "bad" / "stack.toml"));

    // Export: a material per source material and age; glass and rubber kept off keep their
    // own base colour (the OBJ's Kd) and no weathering maps, at every age.
    const Result kept = texgen_run("patina " + quoted(dir_ / "masked.patina") + " --mesh " +
                                   quoted(dir_ / "parts.obj") + " --keep-off Glass,Rubber -o " +
                                   quoted(dir_ / "series") + " --times 0,30 --resolution 32 "
                                   "--quiet --no-preview");
    ASSERT_EQ(kept.status, 0) << kept.err;
    const fs::path glb = dir_ / "parts.glb";
    const Result exported = texgen_run("export " + quoted(dir_ / "series") + " -o " +
                                       quoted(glb) + " --quiet");
    ASSERT_EQ(exported.status, 0) << exported.err;
    const nlohmann::json gltf = glb_json(glb);
    std::map<std::string, nlohmann::json> by_name;
    for (const auto& m : gltf["materials"])
        by_name[m["name"].get<std::string>()] = m;
    ASSERT_TRUE(by_name.count("parts Bronze 30 y")) << gltf["materials"].dump();
    ASSERT_TRUE(by_name.count("parts Bronze 0 y"));
    ASSERT_TRUE(by_name.count("parts Glass"));
    ASSERT_TRUE(by_name.count("parts Rubber"));
    EXPECT_FALSE(by_name.count("parts Glass 30 y"));
    EXPECT_TRUE(by_name["parts Bronze 30 y"]["pbrMetallicRoughness"].contains("baseColorTexture"));
    const auto& glass = by_name["parts Glass"]["pbrMetallicRoughness"];
    EXPECT_FALSE(glass.contains("baseColorTexture"));
    EXPECT_NEAR(glass["baseColorFactor"][0].get<double>(), 0.9, 1e-6);  // Kd 0.9 0.9 0.9
    EXPECT_EQ(gltf["meshes"][0]["primitives"].size(), 3u);
    const nlohmann::json blender = validate_and_open(glb);
    ASSERT_FALSE(blender.is_null());
    EXPECT_TRUE(blender["materials"]["parts Glass"].empty()) << blender["materials"].dump();
    // The rubber keeps its own texture, on the artist's uvs.
    const auto& rubber = by_name["parts Rubber"]["pbrMetallicRoughness"];
    ASSERT_TRUE(rubber.contains("baseColorTexture")) << rubber.dump();
    EXPECT_FALSE(rubber["baseColorTexture"].contains("texCoord"));
    EXPECT_TRUE(blender["materials"]["parts Rubber"].contains("Base Color"))
        << blender["materials"].dump();
    EXPECT_TRUE(blender["materials"]["parts Bronze 30 y"].contains("Base Color"));
}

/// The base colour texture of `pbr` (a material's pbrMetallicRoughness in `glb`) is the
/// tread as Blender made it (blender_asset_corpus.py): 8 x 8, 8-bit codes 51 (0.2) with a
/// cross of 204 (0.8) on column 3 and row 3 from the bottom (Blender counts rows up): row 4
/// of the PNG. On the artist's uvs (TEXCOORD_0).
void expect_tread(const fs::path& glb, const nlohmann::json& pbr)
{
    ASSERT_TRUE(pbr.contains("baseColorTexture")) << pbr.dump();
    EXPECT_EQ(pbr["baseColorTexture"].value("texCoord", 0), 0);
    const nlohmann::json gltf = glb_json(glb);
    const int texture = pbr["baseColorTexture"]["index"].get<int>();
    const std::vector<unsigned char> png =
        glb_image(glb, gltf["textures"][texture]["source"].get<int>());
    const ImageData tread = read_image(png, "png", "the exported tread");
    ASSERT_EQ(tread.width, 8);
    ASSERT_EQ(tread.height, 8);
    for (int y = 0; y < 8; ++y)
        for (int x = 0; x < 8; ++x)
            EXPECT_EQ(std::lround(tread.at(x, y, 0) * 255.0f), x == 3 || y == 4 ? 204 : 51)
                << "texel (" << x << ", " << y << ")";
}

TEST_F(OwnAsset, ThreeMaterialsFromBlenderKeepTheirOwnEmbeddedTexture)
{
    // Blender's three squares of Bronze, Glass and Rubber (blender_asset_corpus.py), the
    // rubber's tread embedded in the file (the glb's buffer; the FBX's media, Z up in cm):
    // the script masks the glass, --keep-off keeps patina off glass and rubber, and the
    // exported rubber carries the tread itself.
    std::ofstream(dir_ / "masked.patina") << "new copper\nmap glass = material \"Glass\"\n"
                                             "coat tarnish 1.0 2 * (1 - glass)\nrender maps\n";
    for (const char* file : {"parts.glb", "parts_zup_cm.fbx"}) {
        SCOPED_TRACE(file);
        const fs::path stack = dir_ / (std::string(file) + ".stack");
        const Result grown = texgen_run("patina " + quoted(dir_ / "masked.patina") + " --mesh " +
                                        quoted(corpus_ / file) + " --keep-off Glass,Rubber -o " +
                                        quoted(stack) + " --times 0,30 --resolution 40 --quiet "
                                        "--no-preview");
        ASSERT_EQ(grown.status, 0) << grown.err;
        const ImageData total = read_image(stack / "t30" / "total_thickness.exr");
        const int c = total.channel("thickness");
        ASSERT_GE(c, 0);
        // Each square holds a third of tile 1001's width (0.3 of it, from u = 0, 0.35, 0.70).
        const auto at_u = [&](float u) { return total.at(static_cast<int>(u * 40), 20, c); };
        EXPECT_NEAR(at_u(0.15f), 2.0f, 1e-5f);  // bronze: the script's 2 um
        EXPECT_EQ(at_u(0.50f), 0.0f);           // glass
        EXPECT_EQ(at_u(0.85f), 0.0f);           // rubber

        const fs::path glb = dir_ / (std::string(file) + ".glb");
        const Result exported = texgen_run("export " + quoted(stack) + " -o " + quoted(glb) +
                                           " --quiet");
        ASSERT_EQ(exported.status, 0) << exported.err;
        const nlohmann::json gltf = glb_json(glb);
        const std::string stem = glb.stem().string();
        nlohmann::json glass, rubber;
        for (const auto& m : gltf["materials"]) {
            if (m["name"] == stem + " Glass")
                glass = m["pbrMetallicRoughness"];
            if (m["name"] == stem + " Rubber")
                rubber = m["pbrMetallicRoughness"];
        }
        ASSERT_FALSE(glass.is_null()) << gltf["materials"].dump();
        ASSERT_FALSE(rubber.is_null()) << gltf["materials"].dump();
        EXPECT_FALSE(glass.contains("baseColorTexture"));
        EXPECT_NEAR(glass["baseColorFactor"][0].get<double>(), 0.9, 1e-6);
        ASSERT_TRUE(rubber.contains("baseColorTexture")) << rubber.dump();
        expect_tread(glb, rubber);

        const nlohmann::json blender = validate_and_open(glb);
        ASSERT_FALSE(blender.is_null());
        EXPECT_TRUE(blender["materials"][stem + " Glass"].empty()) << blender["materials"].dump();
        EXPECT_TRUE(blender["materials"][stem + " Rubber"].contains("Base Color"));
        // Lying flat, 4 m along x, 1 m deep, in metres.
        EXPECT_NEAR(blender["dimensions"][0].get<double>(), 4.0, 1e-4);
        EXPECT_NEAR(blender["dimensions"][1].get<double>(), 1.0, 1e-4);
        EXPECT_NEAR(blender["dimensions"][2].get<double>(), 0.0, 1e-4);
    }

    // unwrap keeps every material's colour and texture; grown in the new set, the kept-off
    // rubber still wears its tread on the artist's uvs while the bronze's maps read set 1.
    const fs::path unwrapped = dir_ / "parts_unwrapped.glb";
    const Result unwrap = texgen_run("unwrap " + quoted(corpus_ / "parts_zup_cm.fbx") + " -o " +
                                     quoted(unwrapped) + " --quiet");
    ASSERT_EQ(unwrap.status, 0) << unwrap.err;
    const nlohmann::json unwrapped_gltf = glb_json(unwrapped);
    int rubbers = 0;
    for (const auto& m : unwrapped_gltf["materials"])
        if (m["name"] == "Rubber") {
            expect_tread(unwrapped, m["pbrMetallicRoughness"]);
            ++rubbers;
        }
    EXPECT_EQ(rubbers, 1) << unwrapped_gltf["materials"].dump();
    const Result grown = texgen_run("patina " + quoted(dir_ / "masked.patina") + " --mesh " +
                                    quoted(unwrapped) + " --uv-set 1 --keep-off Glass,Rubber -o " +
                                    quoted(dir_ / "unwrapped") + " --resolution 40 --quiet "
                                    "--no-preview");
    ASSERT_EQ(grown.status, 0) << grown.err;
    const fs::path glb = dir_ / "unwrapped.glb";
    const Result exported = texgen_run("export " + quoted(dir_ / "unwrapped") + " -o " +
                                       quoted(glb) + " --quiet");
    ASSERT_EQ(exported.status, 0) << exported.err;
    int checked = 0;
    const nlohmann::json gltf = glb_json(glb);
    for (const auto& m : gltf["materials"]) {
        if (m["name"] == "unwrapped Rubber") {
            expect_tread(glb, m["pbrMetallicRoughness"]);
            ++checked;
        }
        if (m["name"] == "unwrapped Bronze 30 y") {
            EXPECT_EQ(m["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"], 1);
            ++checked;
        }
    }
    EXPECT_EQ(checked, 2) << gltf["materials"].dump();
    EXPECT_FALSE(validate_and_open(glb).is_null());
}

TEST_F(OwnAsset, BadAxisAndUnitOptionsGetOneClearMessage)
{
    const fs::path fbx = corpus_ / "figure_zup_cm.fbx";
    const Result bad_axis = texgen_run("uv-check " + quoted(fbx) + " --up w");
    EXPECT_EQ(bad_axis.status, 2);
    EXPECT_NE(bad_axis.err.find("'w' is not an axis"), std::string::npos) << bad_axis.err;
    const Result bad_unit = texgen_run("uv-check " + quoted(fbx) + " --unit furlong");
    EXPECT_EQ(bad_unit.status, 2);
    EXPECT_NE(bad_unit.err.find("'furlong' is not a unit"), std::string::npos) << bad_unit.err;
    const Result both = texgen_run("uv-check " + quoted(fbx) + " --unit cm --scale 0.01");
    EXPECT_EQ(both.status, 2);
    EXPECT_NE(both.err.find("excludes"), std::string::npos) << both.err;
    std::ofstream(dir_ / "bare.patina") << "new copper\nrender maps\n";
    const Result strip = texgen_run("patina " + quoted(dir_ / "bare.patina") + " --up z -o " +
                                 quoted(dir_ / "strip") + " --quiet");
    EXPECT_EQ(strip.status, 1);
    EXPECT_NE(strip.err.find("describe the file of --mesh"), std::string::npos) << strip.err;
}

}  // namespace
}  // namespace patina
