// Miller's accessibility, tangent-sphere variant (Miller 1994, "Efficient algorithms for
// local and global accessibility shading"; Dorsey & Hanrahan 1996 §3.2, "offset radius"):
// the radius of the largest sphere that touches the surface at a point, from the side its
// normal faces, without intersecting any geometry. Large on open and convex surfaces, small
// in cracks and crevices, 0 in a sharp concave crease.
#pragma once

#include "texgen/accessibility/closest_point.h"
#include "texgen/bake/sample_baker.h"

#include <memory>

namespace patina::texgen {

/// The radius of the largest sphere with centre P + r n (n unit) that holds no geometry,
/// capped at max_radius. Tangent spheres at a point are nested, so emptiness is monotone in
/// r; each closest-point query either proves a sphere empty or finds a point q inside it,
/// and the sphere through q, |q - P|^2 / (2 n.(q - P)), bounds the answer from above
/// (a Newton-like step that converges fast), with bisection as the fallback. A sphere
/// counts as empty when nothing is nearer its centre than r less a small tolerance
/// (1e-5 r plus 1e-6 of P's largest coordinate), so the facet that holds P, which the
/// sphere touches at P, does not count; nothing else is excluded. Returns the largest radius
/// proved empty, within 1e-6 relative.
double largest_tangent_sphere(const ClosestPointScene& scene, const Imath::V3f& P,
                              const Imath::V3f& n, double max_radius);

struct TangentSphereOptions {
    float max_radius = 1.0f;  ///< m; also the normalisation of the "accessibility" channel
};

/// Channels "accessibility" (radius / max_radius, in [0, 1]) and "accessibility_radius" (m).
/// The sphere is tangent to the facet that holds the sample (centre along Ng): a sphere
/// along an interpolated normal would cut its own facet. Deterministic (draws no numbers).
class TangentSphereBaker final : public SampleBaker {
public:
    /// Throws std::runtime_error naming --max-radius when it is not positive and finite.
    TangentSphereBaker(const EmbreeScene& scene, const TangentSphereOptions& options);

    std::vector<std::string> channels() const override
    {
        return {"accessibility", "accessibility_radius"};
    }
    void evaluate(const SurfaceSample& s, size_t group_size, Pcg32& rng,
                  float* out) const override;

private:
    std::unique_ptr<ClosestPointScene> closest_;
    TangentSphereOptions options_;
};

}  // namespace patina::texgen
