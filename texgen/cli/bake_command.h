// What every baking sub-command shares: the mesh to bake, extra occluders, the output
// folder, resolution and supersampling, seed, threads, padding, per-vertex mode; and the
// run itself (load, rasterise, bake with progress, pad, write the maps and stack.toml).
#pragma once

#include "core/embree_scene.h"
#include "core/mesh_convention.h"
#include "texgen/bake/sample_baker.h"
#include "texgen/stack/map_output.h"

#include <CLI/CLI.hpp>

#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace patina::texgen {

struct CommonBakeOptions {
    std::filesystem::path mesh;                    ///< the mesh whose surface is baked
    MeshConventionOptions convention;              ///< --up, --unit, --scale (mesh, occluders)
    std::vector<std::filesystem::path> occluders;  ///< more geometry that casts shadows
    bool ground = false;                           ///< a ground plane under the mesh
    bool uv_wrap = false;                          ///< fold uvs outside the UDIM tiles
    std::filesystem::path out_dir = "maps";
    std::string name;                              ///< map name (file stem); baker's default
    int width = 1024;
    int height = 1024;
    int supersampling = 2;
    uint64_t seed = 0;
    int threads = 0;                               ///< 0: all cores
    std::filesystem::path per_vertex;              ///< if set: write this PLY instead of maps
    int padding = 16;                              ///< texels; -1 fills every empty texel
    bool half = false;
    bool quiet = false;
};

/// Add --mesh, --up, --unit, --scale, --occluder, --ground, --out, --name, --resolution, --supersampling, --seed,
/// --threads, --per-vertex, --padding, --half, --quiet to `command`.
void add_common_bake_options(CLI::App& command, CommonBakeOptions& options);

/// Everything a baker factory may need about the scene.
struct BakeScene {
    const EmbreeScene& scene;
    const TriangleMesh& target;  ///< the baked mesh (all meshes of --mesh merged, world space)
    Imath::Box3f bounds;         ///< world bounds of the whole scene (target + occluders)
};

using BakerFactory = std::function<std::unique_ptr<SampleBaker>(const BakeScene&)>;

/// Load, rasterise (or take the vertices), bake with `make_baker`, and write `map` (its
/// channels are taken from the baker) into options.out_dir with stack.toml updated, or the
/// PLY of the per-vertex mode. Prints a one-line summary (texels, rays, rays/s) unless quiet.
void run_bake(const CommonBakeOptions& options, const BakerFactory& make_baker,
              MapDescription map);

}  // namespace patina::texgen
