// Miller's accessibility, offset-surface variant: the height of the surface closed by a
// ball of radius r (see closed_surface.h) above each sample, and 1 - height / r.
#pragma once

#include "texgen/accessibility/closed_surface.h"
#include "texgen/bake/sample_baker.h"

#include <memory>

namespace patina::texgen {

struct OffsetSurfaceOptions {
    float radius = 1.0f;  ///< m, the ball that closes the surface
    int voxels = 256;     ///< voxels along the longest side of the scene bounds
};

/// Channels "accessibility" (1 - clamp(height / r, 0, 1): 1 where the ball touches the
/// surface, 0 at the bottom of crevices at least r deeper than the ball reaches) and
/// "offset_height" (m, the height of the closed surface above the sample along its shading
/// normal N). The voxel grid is built once, in the constructor.
class OffsetSurfaceBaker final : public SampleBaker {
public:
    OffsetSurfaceBaker(const EmbreeScene& scene, const Imath::Box3f& bounds,
                       const OffsetSurfaceOptions& options);

    std::vector<std::string> channels() const override
    {
        return {"accessibility", "offset_height"};
    }
    void evaluate(const SurfaceSample& s, size_t group_size, Pcg32& rng,
                  float* out) const override;

    const ClosedSurface& closed_surface() const { return *closed_; }

private:
    std::unique_ptr<ClosestPointScene> closest_;
    std::unique_ptr<ClosedSurface> closed_;
    OffsetSurfaceOptions options_;
};

}  // namespace patina::texgen
