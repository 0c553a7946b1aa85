#include "texgen/accessibility/tangent_sphere_baker.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace patina::texgen {

double largest_tangent_sphere(const ClosestPointScene& scene, const Imath::V3f& P,
                              const Imath::V3f& n, double max_radius)
{
    const Imath::V3d p(P.x, P.y, P.z);
    const Imath::V3d dir = Imath::V3d(n.x, n.y, n.z).normalized();
    // Rounding of P (a float on its facet) and of n moves the own facet by about an ulp of
    // P's coordinates: the tolerance covers that, relative to r and to P's magnitude.
    const double scale = std::max({std::abs(p.x), std::abs(p.y), std::abs(p.z)});
    const double abs_tolerance = 1e-6 * scale + 1e-12;
    constexpr double kRelTolerance = 1e-5;
    constexpr double kConvergence = 1e-6;

    double lo = 0.0;         // proved empty
    double hi = max_radius;  // not proved empty; the answer is at most hi
    bool newton = true;      // test hi itself (after a good step) or bisect
    for (int iteration = 0; iteration < 200; ++iteration) {
        if (hi - lo <= kConvergence * hi + abs_tolerance)
            break;
        const double r = newton ? hi : 0.5 * (lo + hi);
        const Imath::V3d centre = p + r * dir;
        const double tolerance = kRelTolerance * r + abs_tolerance;
        const ClosestPoint c = scene.closest(centre, r);
        if (!c.found || c.distance >= r - tolerance) {
            lo = r;
            newton = true;
            continue;
        }
        // q lies inside the sphere of radius r; every tangent sphere larger than the one
        // through q holds it, so the answer is below |q - P|^2 / (2 n.(q - P)).
        const Imath::V3d to_q = c.point - p;
        const double along = dir.dot(to_q);
        double bound = r;
        if (along > 0.0)
            bound = std::min(r, to_q.length2() / (2.0 * along));
        const double new_hi = std::max(lo, bound);
        // Keep the Newton steps while they remove at least a quarter of the interval.
        newton = (hi - new_hi) >= 0.25 * (hi - lo) || !newton;
        hi = new_hi;
    }
    return lo;
}

TangentSphereBaker::TangentSphereBaker(const EmbreeScene& scene,
                                       const TangentSphereOptions& options)
    : options_(options)
{
    if (!(options.max_radius > 0.0f) || !std::isfinite(options.max_radius))
        throw std::runtime_error(fmt::format(
            "accessibility: --max-radius must be a positive number of metres (got {})",
            options.max_radius));
    closest_ = std::make_unique<ClosestPointScene>(scene);
}

void TangentSphereBaker::evaluate(const SurfaceSample& s, size_t group_size, Pcg32& rng,
                                  float* out) const
{
    (void)group_size;
    (void)rng;
    const double radius = largest_tangent_sphere(*closest_, s.P, s.Ng, options_.max_radius);
    out[0] = static_cast<float>(std::clamp(radius / options_.max_radius, 0.0, 1.0));
    out[1] = static_cast<float>(radius);
}

}  // namespace patina::texgen
