#include "texgen/stack/map_output.h"
#include "texgen/stack/ply_writer.h"

#include "stack_test_util.h"
#include "test_util.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>

namespace patina::texgen {
namespace {

    namespace fs = std::filesystem;

    /// A minimal reader for what write_vertex_map writes: a binary little-endian PLY whose
    /// vertex properties are all floats and whose faces are uchar-counted int lists.
    struct PlyFile {
        std::string header;
        std::vector<std::string> comments;
        std::vector<std::string> vertex_properties;
        size_t vertex_count = 0;
        size_t face_count = 0;
        std::vector<float> vertex_data;  ///< vertex-major, vertex_properties.size() each
        std::vector<std::array<int32_t, 3>> faces;

        float value(size_t vertex, const std::string& property) const
        {
            const auto it = std::find(vertex_properties.begin(), vertex_properties.end(), property);
            EXPECT_NE(it, vertex_properties.end()) << "no property " << property;
            if (it == vertex_properties.end())
                return std::numeric_limits<float>::quiet_NaN();
            return vertex_data[vertex * vertex_properties.size() +
                               static_cast<size_t>(it - vertex_properties.begin())];
        }
    };

    PlyFile read_ply(const fs::path& path)
    {
        std::ifstream in(path, std::ios::binary);
        std::stringstream buffer;
        buffer << in.rdbuf();
        const std::string bytes = buffer.str();
        PlyFile ply;
        const size_t end = bytes.find("end_header\n");
        EXPECT_NE(end, std::string::npos);
        ply.header = bytes.substr(0, end + 11);
        std::istringstream lines(ply.header);
        std::string line, element;
        while (std::getline(lines, line)) {
            std::istringstream words(line);
            std::string word;
            words >> word;
            if (word == "comment") {
                ply.comments.push_back(line.substr(8));
            } else if (word == "element") {
                size_t count = 0;
                words >> element >> count;
                (element == "vertex" ? ply.vertex_count : ply.face_count) = count;
            } else if (word == "property" && element == "vertex") {
                std::string type, name;
                words >> type >> name;
                EXPECT_EQ(type, "float") << line;
                ply.vertex_properties.push_back(name);
            }
        }
        size_t at = end + 11;
        auto take = [&](void* dst, size_t n) {
            EXPECT_LE(at + n, bytes.size()) << "file too short";
            if (at + n <= bytes.size())
                std::memcpy(dst, bytes.data() + at, n);
            at += n;
        };
        ply.vertex_data.resize(ply.vertex_count * ply.vertex_properties.size());
        take(ply.vertex_data.data(), ply.vertex_data.size() * sizeof(float));
        for (size_t f = 0; f < ply.face_count; ++f) {
            uint8_t n = 0;
            take(&n, 1);
            EXPECT_EQ(n, 3);
            std::array<int32_t, 3> face{};
            take(face.data(), sizeof(face));
            ply.faces.push_back(face);
        }
        EXPECT_EQ(at, bytes.size()) << "trailing bytes";
        return ply;
    }

    MapDescription two_channel_map()
    {
        MapDescription map;
        map.name = "wet";
        map.channels = {"wetness", "albedo.r"};
        map.units = "1";
        map.description = "time of wetness\nper year";
        map.baker = "wetness";
        map.parameters = {{"samples", 64}, {"spread", 0.25f}, {"rain", std::string("0 -1 0")}};
        return map;
    }

    std::vector<float> vertex_values(size_t vertices)
    {
        std::vector<float> v(vertices * 2);
        for (size_t i = 0; i < vertices; ++i) {
            v[2 * i] = 0.5f * static_cast<float>(i);
            v[2 * i + 1] = -1.0f / static_cast<float>(i + 3);
        }
        return v;
    }

    TEST(SanitizePlyName, KeepsWordCharactersOnly)
    {
        EXPECT_EQ(sanitize_ply_name("albedo.r"), "albedo_r");
        EXPECT_EQ(sanitize_ply_name("time of wetness (h)"), "time_of_wetness__h_");
        EXPECT_EQ(sanitize_ply_name("AO_2"), "AO_2");
        EXPECT_EQ(sanitize_ply_name(""), "_");
    }

    TEST(WriteVertexMap, OwnReaderFindsGeometryPropertiesAndComments)
    {
        const fs::path dir = test::scratch_dir("ply_values");
        const TriangleMesh mesh = make_box(Imath::V3f(1, 2, 3), Imath::V3f(2, 1, 0.5f));
        const std::vector<float> values = vertex_values(mesh.positions.size());
        write_vertex_map(dir / "wet.ply", mesh, two_channel_map(), values);

        const PlyFile ply = read_ply(dir / "wet.ply");
        EXPECT_EQ(ply.header.rfind("ply\nformat binary_little_endian 1.0\n", 0), 0u) << ply.header;
        EXPECT_NE(ply.header.find("property list uchar int vertex_indices\n"), std::string::npos);
        const std::vector<std::string> expected_properties = {
            "x", "y", "z", "nx", "ny", "nz", "u", "v", "wetness", "albedo_r"};
        EXPECT_EQ(ply.vertex_properties, expected_properties);
        ASSERT_EQ(ply.vertex_count, mesh.positions.size());
        for (size_t v = 0; v < ply.vertex_count; ++v) {
            EXPECT_EQ(ply.value(v, "x"), mesh.positions[v].x);
            EXPECT_EQ(ply.value(v, "z"), mesh.positions[v].z);
            EXPECT_EQ(ply.value(v, "ny"), mesh.normals[v].y);
            EXPECT_EQ(ply.value(v, "v"), mesh.uvs[v].y);
            EXPECT_EQ(ply.value(v, "wetness"), values[2 * v]);
            EXPECT_EQ(ply.value(v, "albedo_r"), values[2 * v + 1]);
        }
        ASSERT_EQ(ply.faces.size(), mesh.triangle_count());
        for (size_t t = 0; t < ply.faces.size(); ++t)
            for (size_t k = 0; k < 3; ++k)
                EXPECT_EQ(static_cast<uint32_t>(ply.faces[t][k]), mesh.indices[3 * t + k]);
        // The bake is described in comments, one line each (the description's line break
        // became a space).
        const auto has = [&](const std::string& c) {
            return std::find(ply.comments.begin(), ply.comments.end(), c) != ply.comments.end();
        };
        EXPECT_TRUE(has("patina:map wet"));
        EXPECT_TRUE(has("patina:baker wetness"));
        EXPECT_TRUE(has("patina:description time of wetness per year"));
        EXPECT_TRUE(has("patina:samples 64"));
        EXPECT_TRUE(has("patina:spread 0.25"));
        EXPECT_TRUE(has("patina:rain 0 -1 0"));
        for (const auto& entry : fs::directory_iterator(dir))
            EXPECT_EQ(entry.path().filename(), "wet.ply") << "left behind: " << entry.path();
    }

    TEST(WriteVertexMap, AssimpReadsTheGeometryBack)
    {
        const fs::path dir = test::scratch_dir("ply_assimp");
        const TriangleMesh mesh = make_box(Imath::V3f(0.5f, 0, 0), Imath::V3f(1, 2, 3));
        write_vertex_map(dir / "box.ply", mesh, two_channel_map(),
                         vertex_values(mesh.positions.size()));

        const std::vector<TriangleMesh> loaded = load_meshes(dir / "box.ply");
        ASSERT_EQ(loaded.size(), 1u);
        const TriangleMesh& m = loaded[0];
        ASSERT_EQ(m.triangle_count(), mesh.triangle_count());
        ASSERT_TRUE(m.has_normals());
        ASSERT_TRUE(m.has_uvs());
        // Assimp may merge or reorder vertices: compare triangle corners by value.
        using Corner = std::array<float, 8>;
        auto corners = [](const TriangleMesh& x) {
            std::vector<std::array<Corner, 3>> tris;
            for (size_t t = 0; t < x.triangle_count(); ++t) {
                std::array<Corner, 3> tri;
                for (size_t k = 0; k < 3; ++k) {
                    const uint32_t i = x.indices[3 * t + k];
                    tri[k] = {x.positions[i].x, x.positions[i].y, x.positions[i].z, x.normals[i].x,
                              x.normals[i].y,   x.normals[i].z,   x.uvs[i].x,       x.uvs[i].y};
                }
                // Same winding, any starting corner.
                std::rotate(tri.begin(), std::min_element(tri.begin(), tri.end()), tri.end());
                tris.push_back(tri);
            }
            std::sort(tris.begin(), tris.end());
            return tris;
        };
        EXPECT_EQ(corners(m), corners(mesh));
    }

    TEST(WriteVertexMap, MeshWithoutNormalsOrUvsHasOnlyPositionsAndValues)
    {
        const fs::path dir = test::scratch_dir("ply_plain");
        TriangleMesh mesh = make_quad(Imath::V3f(0.0f), 2.0f);
        mesh.normals.clear();
        mesh.uvs.clear();
        MapDescription map = two_channel_map();
        map.channels = {"ao"};
        write_vertex_map(dir / "ao.ply", mesh, map, {0.0f, 0.25f, 0.5f, 1.0f});
        const PlyFile ply = read_ply(dir / "ao.ply");
        EXPECT_EQ(ply.vertex_properties, (std::vector<std::string>{"x", "y", "z", "ao"}));
        EXPECT_EQ(ply.value(2, "ao"), 0.5f);
        const std::vector<TriangleMesh> loaded = load_meshes(dir / "ao.ply");
        ASSERT_EQ(loaded.size(), 1u);
        EXPECT_EQ(loaded[0].triangle_count(), 2u);
    }

    TEST(WriteVertexMap, BadValuesAndNamesAreErrors)
    {
        const fs::path dir = test::scratch_dir("ply_errors");
        const TriangleMesh mesh = make_quad(Imath::V3f(0.0f), 1.0f);
        MapDescription map = two_channel_map();
        std::vector<float> values(8, 0.5f);
        values[5] = std::numeric_limits<float>::infinity();
        std::string message =
            patina::test::message_of([&] { write_vertex_map(dir / "m.ply", mesh, map, values); });
        EXPECT_NE(message.find("vertex 2 channel 'albedo.r' a infinite value"), std::string::npos)
            << message;
        EXPECT_NE(message.find("per-vertex map 'wet'"), std::string::npos) << message;
        values[5] = 0.0f;
        values.pop_back();
        message =
            patina::test::message_of([&] { write_vertex_map(dir / "m.ply", mesh, map, values); });
        EXPECT_NE(message.find("7 values for 4 vertices x 2 channels"), std::string::npos)
            << message;
        values.push_back(0.0f);
        map.channels = {"a.b", "a_b"};
        message =
            patina::test::message_of([&] { write_vertex_map(dir / "m.ply", mesh, map, values); });
        EXPECT_NE(message.find("'a_b' appears twice"), std::string::npos) << message;
        map.channels = {"u", "w"};
        message =
            patina::test::message_of([&] { write_vertex_map(dir / "m.ply", mesh, map, values); });
        EXPECT_NE(message.find("'u' appears twice"), std::string::npos) << message;
        EXPECT_FALSE(fs::exists(dir / "m.ply"));
    }

}  // namespace
}  // namespace patina::texgen
