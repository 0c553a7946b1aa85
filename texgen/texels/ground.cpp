#include "texgen/texels/ground.h"

#include "core/embree_scene.h"

#include <fmt/format.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cstdint>
#include <stdexcept>

namespace patina::texgen {

TriangleMesh ground_under(const TriangleMesh& mesh)
{
    const Imath::Box3f box = bounds_of(mesh);
    if (box.isEmpty())
        throw std::runtime_error("--ground: the mesh has no vertices");
    const Imath::V3f size = box.size();
    const float side = std::max(1.0f, 20.0f * std::max(size.x, size.z));
    const Imath::V3f centre((box.min.x + box.max.x) / 2, box.min.y, (box.min.z + box.max.z) / 2);
    TriangleMesh ground = make_plane(centre, side);
    ground.name = "ground";
    return ground;
}

std::string occluder_crossing(const TriangleMesh& target, const std::vector<TriangleMesh>& occluder)
{
    EmbreeScene scene;
    for (const TriangleMesh& m : occluder)
        scene.add_mesh(m);
    scene.commit();

    // Each edge of each triangle as a segment a + t (b - a), t in the open (0, 1): a hit
    // strictly inside an edge is a crossing, one at its ends only a touch.
    constexpr float kEnd = 1e-4f;
    const size_t edges = target.indices.size();
    std::vector<uint8_t> crosses(edges, 0);
    tbb::parallel_for(tbb::blocked_range<size_t>(0, edges, 4096), [&](const auto& range) {
        for (size_t e = range.begin(); e != range.end(); ++e) {
            const size_t t = e / 3 * 3;
            const Imath::V3f& a = target.positions[target.indices[e]];
            const Imath::V3f& b = target.positions[target.indices[t + (e - t + 1) % 3]];
            if ((b - a).length2() > 0.0f)
                crosses[e] = scene.occluded(a, b - a, kEnd, 1.0f - kEnd);
        }
    });
    const auto first = std::find(crosses.begin(), crosses.end(), uint8_t{1});
    if (first == crosses.end())
        return {};
    const size_t count =
        static_cast<size_t>(std::count(crosses.begin(), crosses.end(), uint8_t{1}));
    const size_t e = static_cast<size_t>(first - crosses.begin());
    const Imath::V3f& p = target.positions[target.indices[e]];
    const Imath::Box3f box = bounds_of(target);
    return fmt::format("{} of {} triangle edges cross it (the first from ({:.4g}, {:.4g}, "
                       "{:.4g})); the occluder hides parts of the mesh from the sky. The mesh "
                       "reaches down to y = {:.4g} m: --ground places a ground plane there",
                       count, edges, p.x, p.y, p.z, box.min.y);
}

} // namespace patina::texgen
