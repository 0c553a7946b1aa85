// Stone volumes exported as OpenVDB (texgen/export/vdb_export.h), read back with OpenVDB
// itself: the grids renderers expect by name and class, the voxels where the volume.exr has
// them, density as the extinction sigma_t x density, colour as the medium's albedo mix, and
// a step series as consecutively numbered frames with their cycles in the metadata and the
// frame manifest.
#include "texgen/export/vdb_export.h"

#include "formats/vdb_sequence/vdb_sequence.h"

#include "core/output_transaction.h"
#include "texgen/stone_export/volume_export.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <openvdb/openvdb.h>

namespace patina::texgen {
namespace {

namespace fs = std::filesystem;

stone::WorldVolume small_volume()
{
    stone::WorldVolume v;
    v.nx = 4;
    v.ny = 3;
    v.nz = 2;
    v.bounds = Imath::Box3d(Imath::V3d(-0.2, 0.0, -0.1), Imath::V3d(0.2, 0.3, 0.1));
    const size_t n = 4 * 3 * 2;
    v.density.assign(n, 0.0f);
    v.crust.assign(n, 0.0f);
    v.iron.assign(n, 0.0f);
    v.salt.assign(n, 0.0f);
    v.density[v.index(1, 2, 1)] = 0.5f;
    v.crust[v.index(1, 2, 1)] = 0.25f;
    v.iron[v.index(1, 2, 1)] = 0.125f;
    v.density[v.index(3, 0, 0)] = 1.0f;
    return v;
}

TEST(VdbExport, GridsHoldTheVolumeAsRenderersReadIt)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "vdb_export_test";
    fs::remove_all(dir);
    for (const char* step : {"cycle_0000", "cycle_0030"}) {
        fs::create_directories(dir / "run" / step);
        stone::write_world_volume(dir / "run" / step / "volume.exr", small_volume());
    }
    const ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio/config.ocio");
    VdbOptions options;
    // The stone sample's sandstone (samples/stone): bright, and red above 1 in Rec.709.
    options.albedo[0][0] = 0.99f;
    options.albedo[0][1] = 0.96f;
    options.albedo[0][2] = 0.90f;
    const std::vector<fs::path> files =
        export_stone_vdb(dir / "run", dir / "out" / "block.vdb", options, colors);
    ASSERT_EQ(files.size(), 3u);
    // Frames 1, 2 (what Blender reads as a sequence), the cycles in the manifest.
    EXPECT_EQ(files[0], dir / "out" / "block.0001.vdb");
    EXPECT_EQ(files[1], dir / "out" / "block.0002.vdb");
    EXPECT_EQ(files[2], dir / "out" / "block.frames.toml");
    const formats::VdbSequence sequence = formats::read_vdb_sequence(files[2]);
    ASSERT_EQ(sequence.frames.size(), 2u);
    EXPECT_EQ(sequence.frames[1].frame, 2);
    EXPECT_EQ(sequence.frames[1].cycle, 30);
    EXPECT_EQ(sequence.frames[1].volume, "block.0002.vdb");
    EXPECT_EQ(sequence.frames[1].boundary, "");

    openvdb::initialize();
    openvdb::io::File file(files[1].string());
    file.open();
    // ... and in each file's metadata.
    const openvdb::MetaMap::Ptr meta = file.getMetadata();
    EXPECT_EQ(meta->metaValue<int32_t>(formats::kVdbCycleMeta), 30);
    EXPECT_EQ(meta->metaValue<int32_t>(formats::kVdbFrameMeta), 2);
    std::vector<std::string> names;
    for (auto it = file.beginName(); it != file.endName(); ++it)
        names.push_back(it.gridName());
    std::sort(names.begin(), names.end());
    EXPECT_EQ(names, (std::vector<std::string>{"color", "crust", "density", "iron", "salt"}));
    auto density = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("density"));
    auto color = openvdb::gridPtrCast<openvdb::Vec3SGrid>(file.readGrid("color"));
    auto crust = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("crust"));
    file.close();
    ASSERT_TRUE(density && color && crust);
    EXPECT_EQ(density->getGridClass(), openvdb::GRID_FOG_VOLUME);
    EXPECT_EQ(density->activeVoxelCount(), 2u);  // only where there is stone
    // 0.1 m voxels (the volume.exr keeps its bounds as floats); voxel (i, j, k) centred at
    // min + (i + 1/2, j + 1/2, k + 1/2) h.
    EXPECT_NEAR(density->voxelSize()[0], 0.1, 1e-7);
    const openvdb::Vec3d centre = density->indexToWorld(openvdb::Coord(1, 2, 1));
    EXPECT_NEAR(centre[0], -0.05, 1e-7);
    EXPECT_NEAR(centre[1], 0.25, 1e-7);
    EXPECT_NEAR(centre[2], 0.05, 1e-7);
    // Extinction sigma_t x density (1/m), the fractions as they are.
    EXPECT_FLOAT_EQ(density->tree().getValue(openvdb::Coord(1, 2, 1)), 0.5f * 200.0f);
    EXPECT_FLOAT_EQ(density->tree().getValue(openvdb::Coord(3, 0, 0)), 200.0f);
    EXPECT_FLOAT_EQ(density->tree().getValue(openvdb::Coord(0, 0, 0)), 0.0f);
    EXPECT_FLOAT_EQ(crust->tree().getValue(openvdb::Coord(1, 2, 1)), 0.25f);
    // The albedo mix (patina/volume/stone_albedo.h): 5/8 stone, 1/4 crust, 1/8 iron, in
    // linear Rec.709 (the defaults are in the working space), each albedo clamped to [0, 1].
    float albedo[4][3];
    for (int m = 0; m < 4; ++m) {
        std::copy(options.albedo[m], options.albedo[m] + 3, albedo[m]);
        colors.convert(colors.working_space(), "lin_rec709", albedo[m], 1);
        if (m == 0)
            EXPECT_GT(albedo[0][0], 1.01f);  // the sandstone's red in Rec.709: 1.016
        for (float& c : albedo[m])
            c = std::clamp(c, 0.0f, 1.0f);
    }
    EXPECT_EQ(albedo[0][0], 1.0f);
    const openvdb::Vec3s mixed = color->tree().getValue(openvdb::Coord(1, 2, 1));
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(mixed[c], 0.625f * albedo[0][c] + 0.25f * albedo[1][c] + 0.125f * albedo[2][c],
                    1e-6);

    const std::string m = test::message_of(
        [&] { export_stone_vdb(dir / "out", dir / "none.vdb", options, colors); });
    EXPECT_NE(m.find("no stone volume"), std::string::npos) << m;
}

TEST(VdbExport, SimulationFieldsBecomeGridsOfTheirNames)
{
    // A volume with the simulation's decay and moisture (formats/stone_volume/stone_volume.h part 2)
    // round-trips through volume.exr and becomes the grids `moisture` and `decay`.
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "vdb_export_fields_test";
    fs::remove_all(dir);
    fs::create_directories(dir / "run");
    stone::WorldVolume v = small_volume();
    v.decay.assign(v.density.size(), 0.0f);
    v.moisture.assign(v.density.size(), 0.0f);
    v.decay[v.index(1, 2, 1)] = 3.5f;
    v.moisture[v.index(1, 2, 1)] = 0.75f;
    v.moisture[v.index(0, 0, 0)] = 0.5f;  // no stone there: not a voxel of the grids
    stone::write_world_volume(dir / "run" / "volume.exr", v);
    const stone::WorldVolume back = stone::read_world_volume(dir / "run" / "volume.exr");
    EXPECT_EQ(back.decay, v.decay);
    EXPECT_EQ(back.moisture, v.moisture);

    const ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio/config.ocio");
    ASSERT_EQ(export_stone_vdb(dir / "run", dir / "block.vdb", {}, colors).size(), 1u);
    openvdb::initialize();
    openvdb::io::File file((dir / "block.vdb").string());
    file.open();
    auto moisture = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("moisture"));
    auto decay = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid("decay"));
    file.close();
    ASSERT_TRUE(moisture && decay);
    EXPECT_FLOAT_EQ(moisture->tree().getValue(openvdb::Coord(1, 2, 1)), 0.75f);
    EXPECT_FLOAT_EQ(decay->tree().getValue(openvdb::Coord(1, 2, 1)), 3.5f);
    EXPECT_FALSE(moisture->tree().isValueOn(openvdb::Coord(0, 0, 0)));
    EXPECT_EQ(moisture->activeVoxelCount(), 2u);
}

TEST(VdbExport, BoundaryMeshGoesBesideItsVolume)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "vdb_export_boundary_test";
    fs::remove_all(dir);
    fs::create_directories(dir / "run" / "cycle_0060");
    stone::write_world_volume(dir / "run" / "cycle_0060" / "volume.exr", small_volume());
    const std::string obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
    {
        std::ofstream(dir / "run" / "cycle_0060" / "eroded.obj") << obj;
    }
    const ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio/config.ocio");
    const std::vector<fs::path> files =
        export_stone_vdb(dir / "run", dir / "out" / "column.vdb", {}, colors);
    ASSERT_EQ(files.size(), 3u);
    EXPECT_EQ(files[0], dir / "out" / "column.0001.vdb");
    EXPECT_EQ(files[1], dir / "out" / "column.0001.obj");
    EXPECT_EQ(formats::read_vdb_sequence(files[2]).frames.at(0).boundary, "column.0001.obj");
    std::ifstream in(files[1]);
    EXPECT_EQ(std::string((std::istreambuf_iterator<char>(in)), {}), obj);
}

TEST(VdbExport, StepsOfAnotherGridAreRefusedAndNothingIsWritten)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "vdb_export_disagree_test";
    fs::remove_all(dir);
    fs::create_directories(dir / "run" / "cycle_0000");
    fs::create_directories(dir / "run" / "cycle_0030");
    stone::WorldVolume v = small_volume();
    stone::write_world_volume(dir / "run" / "cycle_0000" / "volume.exr", v);
    v.bounds.max.x = 0.6;  // the second step on another grid
    stone::write_world_volume(dir / "run" / "cycle_0030" / "volume.exr", v);
    const ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio/config.ocio");
    OutputTransaction outputs;
    const CurrentOutputs current(outputs);
    const std::string m = test::message_of(
        [&] { export_stone_vdb(dir / "run", dir / "out" / "column.vdb", {}, colors); });
    EXPECT_NE(m.find("the steps disagree: 'cycle_0000' is 4x3x2 voxels"), std::string::npos) << m;
    EXPECT_NE(m.find("'cycle_0030' 4x3x2 over [-0.2, 0, -0.1] to [0.6, 0.3, 0.1] m"),
              std::string::npos) << m;
    EXPECT_FALSE(fs::exists(dir / "out" / "column.0001.vdb"));  // nothing committed
}

TEST(VdbExport, FrameManifestRoundTripsAndRefusesBadFrames)
{
    formats::VdbSequence s;
    s.source = "out/stone/column";
    s.frames = {{1, 0, "column.0001.vdb", "column.0001.obj"}, {2, 30, "column.0002.vdb", ""}};
    const std::string text = formats::vdb_sequence_text(s);
    const formats::VdbSequence back = formats::parse_vdb_sequence(text, "column.frames.toml");
    EXPECT_EQ(back.source, s.source);
    ASSERT_EQ(back.frames.size(), 2u);
    EXPECT_EQ(back.frames[0].boundary, "column.0001.obj");
    EXPECT_EQ(back.frames[1].cycle, 30);
    EXPECT_EQ(formats::vdb_sequence_text(back), text);
    auto fails = [](const std::string& t) {
        return test::message_of([&] { formats::parse_vdb_sequence(t, "f.toml"); });
    };
    const std::string head = "[sequence]\nformat = 1\nsource = 'x'\n";
    EXPECT_NE(fails(head + "[[frame]]\nframe = 2\ncycle = 0\nvolume = 'a'\n")
                  .find("f.toml:5:9: frame 1: frame numbers run 1, 2, 3"),
              std::string::npos);
    EXPECT_NE(fails(head + "[[frame]]\nframe = 1\ncycle = 5\nvolume = 'a'\n"
                           "[[frame]]\nframe = 2\ncycle = 5\nvolume = 'b'\n")
                  .find("frame 2: cycles must increase"),
              std::string::npos);
    EXPECT_NE(fails(head + "[[frame]]\nframe = 1\ncycle = 0\nvolume = 'a'\nvolumes = 1\n")
                  .find("volumes: unknown key"),
              std::string::npos);
    EXPECT_NE(fails("[sequence]\nformat = 2\nsource = 'x'\n[[frame]]\nframe = 1\ncycle = 0\n"
                    "volume = 'a'\n").find("format 2 is newer"),
              std::string::npos);
    EXPECT_NE(fails(head).find("no [[frame]]"), std::string::npos);
}

TEST(VdbExport, MediumParametersComeFromTheScene)
{
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "vdb_export_medium_test";
    fs::remove_all(dir);
    fs::create_directories(dir);
    {
        std::ofstream(dir / "scene.toml") << R"([[shader]]
name = "glass"
type = "dielectric"

[[shader]]
name = "sandstone"
type = "slab_volume"
sigma_t = 150.0
stone_albedo = [0.99, 0.96, 0.90]
crust_albedo = 0.05
iron_albedo = { rgb = [0.5, 0.5, 0.5], colorspace = "lin_rec709" }
iron_gain = 0.35
forward_k = 0.2
)";
    }
    const ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio/config.ocio");
    const VdbOptions o = read_medium_options(dir / "scene.toml", "", colors);
    EXPECT_EQ(o.sigma_t, 150.0);
    EXPECT_FLOAT_EQ(o.albedo[0][1], 0.96f);  // [r, g, b]: the working space, as given
    EXPECT_FLOAT_EQ(o.albedo[1][2], 0.05f);
    // lin_rec709 grey is grey in ACEScg too (both white points D65 after the config's
    // Bradford adaptation): 0.5 in every channel, to float rounding.
    for (int c = 0; c < 3; ++c)
        EXPECT_NEAR(o.albedo[2][c], 0.5f, 1e-4f);
    EXPECT_FLOAT_EQ(o.albedo[3][0], VdbOptions().albedo[3][0]);  // not given: the default
    EXPECT_FLOAT_EQ(o.gain[1], 0.35f);
    EXPECT_FLOAT_EQ(o.gain[0], 1.0f);

    std::string m = test::message_of([&] { read_medium_options(dir / "scene.toml", "marble", colors); });
    EXPECT_NE(m.find("no slab_volume shader named 'marble'"), std::string::npos) << m;
    {
        std::ofstream(dir / "bad.toml") << "[[shader]]\nname = \"s\"\ntype = \"slab_volume\"\n"
                                           "stone_albedo = [0.9, 0.9]\n";
    }
    m = test::message_of([&] { read_medium_options(dir / "bad.toml", "s", colors); });
    EXPECT_NE(m.find("bad.toml:4:"), std::string::npos) << m;
    EXPECT_NE(m.find("stone_albedo must be"), std::string::npos) << m;
}

}  // namespace
}  // namespace patina::texgen
