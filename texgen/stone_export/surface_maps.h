// Surface maps of the weathered stone on the input mesh's uvs, for renderers that do not
// read volumes: "stone_colour" (R, G, B: linear albedo of the fresh stone at the eroded
// surface, darkened by black crust, tinted by iron oxide, whitened by salt) and "stone_crust"
// (crust, iron, salt fractions in [0, 1] and "erosion": the depth in metres from the original
// surface to the eroded one). Each texel marches inwards from its surface point along the
// normal to the first stone voxel (density >= 1/2) and reads the slab voxels there.
#pragma once

#include "core/mesh.h"
#include "texgen/stone/stone_state.h"
#include "texgen/stack/map_output.h"

#include <filesystem>
#include <vector>

namespace patina::texgen::stone {

struct SurfaceAppearance {
    Imath::V3f colour{0.0f};
    float crust = 0.0f, iron = 0.0f, salt = 0.0f, erosion = 0.0f;
};

/// Appearance at surface point P with outward normal N.
class SurfaceReader {
public:
    explicit SurfaceReader(const StoneState& st);
    SurfaceAppearance at(const Imath::V3f& P, const Imath::V3f& N) const;

private:
    const StoneState& st_;
    std::vector<float> density_, crust_, iron_, salt_;
    std::array<std::vector<float>, 3> colour_;
    double step_ = 0.0;
    double reach_ = 0.0;
};

/// Write stone_colour and stone_crust into `out_dir` (texel maps of `resolution` squared per
/// UDIM tile, and stack.toml entries). Returns the files written.
std::vector<std::filesystem::path> write_surface_maps(const std::filesystem::path& out_dir,
                                                      const StoneState& st,
                                                      const TriangleMesh& mesh, int resolution,
                                                      const Metadata& parameters);

} // namespace patina::texgen::stone
