// The points a baker evaluates: groups of surface samples, one group per output element (a
// texel of a UV grid, or a vertex in the per-vertex mode). An element's value is the mean
// of its samples' values, which is how texels get supersampled.
#pragma once

#include <Imath/ImathVec.h>

#include <cstdint>
#include <vector>

namespace patina::texgen {

/// One point on the mesh surface, world space.
struct SurfaceSample {
    Imath::V3f P{0.0f, 0.0f, 0.0f};   ///< position
    Imath::V3f N{0.0f, 0.0f, 1.0f};   ///< unit shading normal (interpolated, or Ng without vertex normals)
    Imath::V3f Ng{0.0f, 0.0f, 1.0f};  ///< unit geometric normal of the triangle, on N's side
    Imath::V2f uv{0.0f, 0.0f};        ///< the mesh's uv at P (for reading input maps)
    uint32_t triangle = 0;
};

/// Samples in groups: group g owns samples[offsets[g] .. offsets[g + 1]).
struct SampleGroups {
    std::vector<uint32_t> offsets{0};
    std::vector<SurfaceSample> samples;

    size_t group_count() const { return offsets.size() - 1; }
    size_t group_size(size_t g) const { return offsets[g + 1] - offsets[g]; }
    /// Append one group made of `group` (which may be empty only if you mean it).
    void add_group(const std::vector<SurfaceSample>& group)
    {
        samples.insert(samples.end(), group.begin(), group.end());
        offsets.push_back(static_cast<uint32_t>(samples.size()));
    }
};

}  // namespace patina::texgen
