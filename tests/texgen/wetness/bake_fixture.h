// Shared by the wetness and deposit tests: scenes made in code, single surface samples, a
// synthetic input map written with core's make_texture_atomic, and a one-sample bake.
#pragma once

#include "core/embree_scene.h"
#include "core/image_io.h"
#include "core/mesh.h"
#include "texgen/bake/bake_driver.h"

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace patina::texgen::test {

inline const std::filesystem::path kOcioConfig = PATINA_SOURCE_DIR "/ocio/config.ocio";

inline std::filesystem::path scratch(const std::string& folder, const std::string& name)
{
    const std::filesystem::path dir = std::filesystem::path(PATINA_TEST_BUILD_DIR) / folder;
    std::filesystem::create_directories(dir);
    return dir / name;
}

/// An Embree scene of the given meshes, committed.
inline std::unique_ptr<EmbreeScene> make_scene(const std::vector<TriangleMesh>& meshes)
{
    auto scene = std::make_unique<EmbreeScene>();
    for (const TriangleMesh& m : meshes)
        scene->add_mesh(m);
    scene->commit();
    return scene;
}

/// A surface sample at P with unit normal N (shading = geometric).
inline SurfaceSample sample_at(const Imath::V3f& P, const Imath::V3f& N,
                               const Imath::V2f& uv = Imath::V2f(0.5f, 0.5f))
{
    SurfaceSample s;
    s.P = P;
    s.N = N.normalized();
    s.Ng = s.N;
    s.uv = uv;
    return s;
}

/// Every sample alone in its group.
inline SampleGroups one_per_group(const std::vector<SurfaceSample>& samples)
{
    SampleGroups groups;
    for (const SurfaceSample& s : samples)
        groups.add_group({s});
    return groups;
}

/// The value of one sample baked alone (group of one) through the bake driver.
inline float bake_one(const SampleBaker& baker, const SurfaceSample& s, uint64_t seed = 1)
{
    return bake_groups(one_per_group({s}), baker, {seed, 1001, nullptr}).at(0);
}

/// A width x height single-channel float texture named `channel` whose texel (x, y) holds
/// f(x, y) (row 0 at the top, v = 1).
template <class F>
std::filesystem::path write_map(const std::filesystem::path& path, const std::string& channel,
                                int width, int height, F f)
{
    std::vector<float> pixels(static_cast<size_t>(width) * height);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            pixels[static_cast<size_t>(y) * width + x] = f(x, y);
    TextureOptions options;
    options.format = OIIO::TypeDesc::FLOAT;
    options.tile_size = 16;
    options.wrap = "clamp";
    make_texture_atomic(path, pixels.data(), width, height, 1, {channel}, options);
    return path;
}

/// The uv of the centre of texel (x, y) of a width x height tile 1001.
inline Imath::V2f texel_centre(int x, int y, int width, int height)
{
    return {(static_cast<float>(x) + 0.5f) / static_cast<float>(width),
            1.0f - (static_cast<float>(y) + 0.5f) / static_cast<float>(height)};
}

} // namespace patina::texgen::test
