#include "texgen/slabs/voxelizer.h"

#include "core/embree_scene.h"
#include "texgen/accessibility/closest_point.h"

#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>

namespace patina::texgen::stone {

using Imath::V3d;

void voxelize(const SlabLattice& lattice, const TriangleMesh& mesh, std::vector<float>& density,
              std::vector<ColumnSurface>& columns)
{
    EmbreeScene scene;
    scene.add_mesh(mesh);
    scene.commit();
    const ClosestPointScene closest(scene);
    const SlabGrid& g = lattice.grid();
    density.assign(g.cell_count(), 0.0f);
    columns.assign(size_t(g.slab_count) * g.n_t * g.n_t, ColumnSurface{});

    tbb::parallel_for(0, g.slab_count, [&](int s) {
        const SlabCorners& c = lattice.slabs()[size_t(s)];
        std::vector<double> crossings;
        for (int j = 0; j < g.n_t; ++j)
            for (int i = 0; i < g.n_t; ++i) {
                // The column as a segment from its outer end (w = 0) to its inner end.
                const V3d a = slab_to_world(c, V3d((i + 0.5) / g.n_t, (j + 0.5) / g.n_t, 0.0));
                const V3d b = slab_to_world(c, V3d((i + 0.5) / g.n_t, (j + 0.5) / g.n_t, 1.0));
                const V3d dir = b - a;
                // Start a little outside the column's outer end (Embree needs tnear >= 0).
                constexpr double kLead = 1e-4;
                const V3d start = a - kLead * dir;
                const Imath::V3f o(float(start.x), float(start.y), float(start.z));
                const Imath::V3f d(float(dir.x), float(dir.y), float(dir.z));
                crossings.clear();
                ColumnSurface& col = columns[column_index(g, s, i, j)];
                float t = 0.0f;
                for (int guard = 0; guard < 64; ++guard) {
                    auto hit = scene.intersect(o, d, t, float(1.0 + 2.0 * kLead));
                    if (!hit)
                        break;
                    if (crossings.empty()) {
                        const SurfacePoint sp = scene.interpolate(*hit, o, d);
                        col.P = sp.P;
                        col.N = sp.Ng.dot(d) < 0.0f ? sp.N : -sp.N;
                        if (col.N.dot(d) > 0.0f)
                            col.N = -col.N;
                        col.uv = sp.uv;
                        col.hit = true;
                    }
                    crossings.push_back(hit->t - kLead); // as w along the column
                    t = hit->t + 1e-6f;
                }
                if (!col.hit) {
                    col.P = Imath::V3f(float(a.x), float(a.y), float(a.z));
                    const Imath::V3f out = -d;
                    col.N = out.length() > 0 ? out.normalized() : Imath::V3f(0, 1, 0);
                }
                for (int k = 0; k < g.n_d; ++k) {
                    const double w = (k + 0.5) / g.n_d;
                    const size_t n_before = size_t(
                        std::count_if(crossings.begin(), crossings.end(),
                                      [&](double x) { return x < w; }));
                    const bool inside = n_before % 2 == 1;
                    const size_t cell = g.index(s, i, j, k);
                    const Imath::V3f& pf = lattice.position()[cell];
                    const V3d p(pf.x, pf.y, pf.z);
                    const double h = dir.length() / g.n_d;
                    const double dist = closest.distance(p, 2.0 * h);
                    const double sd = inside ? dist : -dist;
                    density[cell] = float(std::clamp(0.5 + sd / h, 0.0, 1.0));
                }
            }
    });
}

} // namespace patina::texgen::stone
