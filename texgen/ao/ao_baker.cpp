#include "texgen/ao/ao_baker.h"

#include <vector>

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

namespace patina::texgen {

AoBaker::AoBaker(const EmbreeScene& scene, const AoOptions& options)
    : scene_(scene), options_(options)
{
    if (options.rays < 1)
        throw std::runtime_error(fmt::format("ao: --rays must be at least 1 (got {})", options.rays));
    if (!(options.max_distance > 0.0f))
        throw std::runtime_error(
            fmt::format("ao: --max-distance must be positive (got {})", options.max_distance));
}

size_t AoBaker::rays_per_sample(size_t group_size) const
{
    // The element's budget split evenly, rounded up so an element never gets fewer rays
    // than asked for, and at least one ray per sample.
    const size_t rays = static_cast<size_t>(options_.rays);
    if (group_size == 0)
        return rays;
    return std::max<size_t>(1, (rays + group_size - 1) / group_size);
}

void AoBaker::evaluate(const SurfaceSample& s, size_t group_size, Pcg32& rng, float* out) const
{
    // Gather the sample's rays and trace them as one stream (EmbreeScene::count_unoccluded).
    thread_local std::vector<ShadowRay> rays;
    rays.clear();
    const uint32_t n = for_each_ray(s, group_size, rng, [&](const Imath::V3f& origin,
                                                            const Imath::V3f& dir) {
        rays.push_back({origin, dir, options_.max_distance});
    });
    const size_t unoccluded = scene_.count_unoccluded(rays);
    out[0] = static_cast<float>(unoccluded) / static_cast<float>(n);
}

}  // namespace patina::texgen
