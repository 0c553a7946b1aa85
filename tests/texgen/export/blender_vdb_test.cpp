// Blender opens the OpenVDB stone volumes `patina-texgen export` writes: Debian 12's Blender
// 3.4, headless, imports the .vdb as a Volume object (tests/clients/blender_vdb_check.py),
// finds the grids by the names and types renderers expect, at the volume's place and size,
// and Cycles renders light scattered by it (a sun, a black world: any light is the volume's).
#include "texgen/export/vdb_export.h"

#include "core/image_io.h"
#include "texgen/stone_export/volume_export.h"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fmt/format.h>

#include <cstdlib>
#include <fstream>

namespace patina::texgen {
namespace {

namespace fs = std::filesystem;

TEST(BlenderVdb, VolumeImportsWithItsGridsAndRenders)
{
    if (std::system("blender --version > /dev/null 2>&1") != 0)
        GTEST_FAIL() << "Blender not found: install Debian 12's blender and python3-numpy "
                        "(scripts/bootstrap.sh does)";
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "blender_vdb_test";
    fs::remove_all(dir);
    fs::create_directories(dir / "run");
    // A 0.4 m block of stone, 16³ voxels, its top quarter crusted.
    stone::WorldVolume v;
    v.nx = v.ny = v.nz = 16;
    v.bounds = Imath::Box3d(Imath::V3d(-0.2), Imath::V3d(0.2));
    const size_t n = 16 * 16 * 16;
    v.density.assign(n, 1.0f);
    v.crust.assign(n, 0.0f);
    v.iron.assign(n, 0.1f);
    v.salt.assign(n, 0.0f);
    v.decay.assign(n, 0.5f);     // the simulation's own fields, as a stone run writes them
    v.moisture.assign(n, 0.25f);
    for (int k = 12; k < 16; ++k)
        for (int j = 0; j < 16; ++j)
            for (int i = 0; i < 16; ++i)
                v.crust[v.index(i, j, k)] = 0.8f;
    stone::write_world_volume(dir / "run" / "volume.exr", v);
    const ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio/config.ocio");
    ASSERT_EQ(export_stone_vdb(dir / "run", dir / "block.vdb", {}, colors).size(), 1u);

    const std::string command =
        std::string("blender -b --factory-startup --python-exit-code 1 --python '") +
        PATINA_SOURCE_DIR + "/tests/clients/blender_vdb_check.py' -- '" +
        (dir / "block.vdb").string() + "' '" + (dir / "report.json").string() + "' '" +
        (dir / "render.exr").string() + "' 32 16 > '" + (dir / "blender.log").string() +
        "' 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << "see " << (dir / "blender.log").string();
    std::ifstream in(dir / "report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    EXPECT_EQ(report["grids"], nlohmann::json({{"color", "VECTOR_FLOAT"},
                                               {"crust", "FLOAT"},
                                               {"decay", "FLOAT"},
                                               {"density", "FLOAT"},
                                               {"iron", "FLOAT"},
                                               {"moisture", "FLOAT"},
                                               {"salt", "FLOAT"}}));
    for (int a = 0; a < 3; ++a) {
        // Blender bounds a volume by its outer voxels' centres: 0.2 m less half a 0.025 m
        // voxel, where the volume.exr put them.
        EXPECT_NEAR(report["min"][a].get<double>(), -0.1875, 1e-5) << a;
        EXPECT_NEAR(report["max"][a].get<double>(), 0.1875, 1e-5) << a;
    }
    const ImageData image = read_image(dir / "render.exr");
    double sum = 0.0, top = 0.0;
    for (int y = 0; y < image.height; ++y)
        for (int x = 0; x < image.width; ++x) {
            const double g = image.at(x, y, image.channel("G"));
            sum += g;
            top = std::max(top, g);
        }
    const double mean = sum / (image.width * image.height);
    std::printf("[ blender  ] block.vdb: grids %s, render mean %.3f, max %.3f\n",
                report["grids"].dump().c_str(), mean, top);
    EXPECT_GT(mean, 0.01);  // the black world gives nothing: this light is the volume's
    EXPECT_GT(top, 0.05);
}

TEST(BlenderVdb, ASequenceImportsAsOneVolumeWithEveryFrame)
{
    // Three steps of a stone run (cycles 0, 30 and 60) exported as column.0001-0003.vdb:
    // selected together in File > Import > OpenVDB, Blender 3.4 makes one volume whose
    // frames 1, 2 and 3 load the three files.
    if (std::system("blender --version > /dev/null 2>&1") != 0)
        GTEST_FAIL() << "Blender not found: install Debian 12's blender and python3-numpy "
                        "(scripts/bootstrap.sh does)";
    const fs::path dir = fs::path(PATINA_TEST_BUILD_DIR) / "blender_vdb_sequence_test";
    fs::remove_all(dir);
    stone::WorldVolume v;
    v.nx = v.ny = v.nz = 8;
    v.bounds = Imath::Box3d(Imath::V3d(-0.2), Imath::V3d(0.2));
    const size_t n = 8 * 8 * 8;
    v.density.assign(n, 1.0f);
    v.crust.assign(n, 0.0f);
    v.iron.assign(n, 0.1f);
    v.salt.assign(n, 0.0f);
    for (const char* step : {"cycle_0000", "cycle_0030", "cycle_0060"}) {
        fs::create_directories(dir / "run" / step);
        stone::write_world_volume(dir / "run" / step / "volume.exr", v);
        v.crust.assign(n, v.crust[0] + 0.2f);
    }
    const ColorManager colors(fs::path(PATINA_SOURCE_DIR) / "ocio/config.ocio");
    const std::vector<fs::path> files =
        export_stone_vdb(dir / "run", dir / "out" / "column.vdb", {}, colors);
    ASSERT_EQ(files.size(), 4u);  // three frames and the manifest

    std::string command = std::string("blender -b --factory-startup --python-exit-code 1 "
                                      "--python '") +
                          PATINA_SOURCE_DIR + "/tests/clients/blender_vdb_sequence_check.py' -- '" +
                          (dir / "report.json").string() + "'";
    for (size_t f = 0; f < 3; ++f)
        command += " '" + files[f].string() + "'";
    command += " > '" + (dir / "blender.log").string() + "' 2>&1";
    ASSERT_EQ(std::system(command.c_str()), 0) << "see " << (dir / "blender.log").string();
    std::ifstream in(dir / "report.json");
    const nlohmann::json report = nlohmann::json::parse(in);
    std::printf("[ blender  ] column.0001-0003.vdb: %s\n", report.dump().c_str());
    EXPECT_EQ(report["objects"], 1);
    EXPECT_EQ(report["is_sequence"], true);
    EXPECT_EQ(report["frame_duration"], 3);
    ASSERT_EQ(report["frames"].size(), 3u);
    for (int f = 0; f < 3; ++f) {
        const nlohmann::json& frame = report["frames"][static_cast<size_t>(f)];
        EXPECT_EQ(frame["file"], fmt::format("column.{:04}.vdb", f + 1)) << frame.dump();
        EXPECT_EQ(frame["loaded"], true) << frame.dump();
        EXPECT_EQ(frame["grids"], nlohmann::json({"color", "crust", "density", "iron", "salt"}))
            << frame.dump();
    }
}

}  // namespace
}  // namespace patina::texgen
