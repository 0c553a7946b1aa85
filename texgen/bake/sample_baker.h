// A baker evaluates one value (a few channels) at a surface sample; the bake driver runs it
// over every sample in parallel and averages each group. Bakers are stateless after
// construction, so one instance serves every thread.
#pragma once

#include "core/embree_scene.h"
#include "core/image_io.h"
#include "core/sampling.h"
#include "texgen/texels/surface_samples.h"

#include <string>
#include <vector>

namespace patina::texgen {

class SampleBaker {
public:
    virtual ~SampleBaker() = default;
    /// Output channel names, e.g. {"ao"} or {"accessibility", "accessibility_radius"}.
    virtual std::vector<std::string> channels() const = 0;
    /// Rays a call to evaluate() casts for a group of `group_size` samples (for the progress
    /// and rays/s statistics; 0 if it does not trace).
    virtual size_t rays_per_sample(size_t group_size) const { (void)group_size; return 0; }
    /// Parameters whose values the baker worked out itself (defaults that depend on the scene
    /// or an input map, e.g. a map's maximum): run_bake writes these numbers into the map's
    /// header and manifest in place of the description of the default.
    virtual Metadata resolved_parameters() const { return {}; }
    /// Write channels().size() values for sample `s` to `out`. `group_size` is the number
    /// of samples in the sample's group (a baker with a per-texel ray budget divides it);
    /// `rng` is seeded from (seed, tile, group, sample) so results never depend on threads.
    virtual void evaluate(const SurfaceSample& s, size_t group_size, Pcg32& rng,
                          float* out) const = 0;
};

}  // namespace patina::texgen
