#include "texgen/accessibility/offset_surface_baker.h"

#include <algorithm>

namespace patina::texgen {

OffsetSurfaceBaker::OffsetSurfaceBaker(const EmbreeScene& scene, const Imath::Box3f& bounds,
                                       const OffsetSurfaceOptions& options)
    : options_(options)
{
    closest_ = std::make_unique<ClosestPointScene>(scene);
    closed_ = std::make_unique<ClosedSurface>(*closest_, bounds, options.radius, options.voxels);
}

void OffsetSurfaceBaker::evaluate(const SurfaceSample& s, size_t group_size, Pcg32& rng,
                                  float* out) const
{
    (void)group_size;
    (void)rng;
    const float height = closed_->height(s.P, s.N);
    out[0] = 1.0f - std::clamp(height / options_.radius, 0.0f, 1.0f);
    out[1] = height;
}

}  // namespace patina::texgen
