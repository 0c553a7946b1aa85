#include "texgen/ao/ao_baker.h"

#include "texgen/ao/sobol02.h"

#include <patina/shading/sampling.h>

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
    const uint32_t n = static_cast<uint32_t>(rays_per_sample(group_size));
    // A fresh random-digit scramble per sample keeps the estimate unbiased while the
    // points stay stratified (Kollig & Keller 2002 §3).
    const uint32_t scramble0 = rng.uniform_u32();
    const uint32_t scramble1 = rng.uniform_u32();

    // Orthonormal frame about N: Duff et al. 2017, "Building an Orthonormal Basis,
    // Revisited", JCGT 6(1), Listing 3.
    const Imath::V3f& N = s.N;
    const float sign = std::copysign(1.0f, N.z);
    const float a = -1.0f / (sign + N.z);
    const float b = N.x * N.y * a;
    const Imath::V3f T(1.0f + sign * N.x * N.x * a, sign * b, -sign * N.x);
    const Imath::V3f B(b, sign + N.y * N.y * a, -N.y);

    uint32_t unoccluded = 0;
    for (uint32_t i = 0; i < n; ++i) {
        const shading::Vec2 u(sobol02_to_float(sobol02_dimension0(i, scramble0)),
                              sobol02_to_float(sobol02_dimension1(i, scramble1)));
        // Cosine-weighted direction (Malley's method): pbrt-v4 §A.5.3
        const shading::Vec3 w = shading::sample_cosine_hemisphere(u);
        const Imath::V3f dir = w.x * T + w.y * B + w.z * N;
        // Below the facet: the surface itself blocks it.
        if (dir.dot(s.Ng) <= 0.0f)
            continue;
        const Imath::V3f origin = offset_ray_origin(s.P, s.Ng, dir);
        if (!scene_.occluded(origin, dir, 0.0f, options_.max_distance))
            ++unoccluded;
    }
    out[0] = static_cast<float>(unoccluded) / static_cast<float>(n);
}

}  // namespace patina::texgen
