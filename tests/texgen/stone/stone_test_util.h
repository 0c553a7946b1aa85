// Meshes and small simulations shared by the stone tests (made in code).
#pragma once

#include "core/mesh.h"
#include "texgen/slabs/slab_lattice.h"
#include "texgen/stone/stone_state.h"

#include <algorithm>
#include <cmath>
#include <memory>

namespace patina::texgen::stone::test {

/// A closed blob with concave dents: a uv sphere whose radius is modulated by
/// 1 + a sin(3 theta) cos(3 phi).
inline TriangleMesh concave_blob(float radius = 0.5f, float amplitude = 0.25f, int rings = 16,
                                 int segments = 24)
{
    TriangleMesh m = make_uv_sphere(Imath::V3f(0.0f), radius, rings, segments);
    for (auto& p : m.positions) {
        const float r = p.length();
        if (r <= 0.0f)
            continue;
        const float theta = std::acos(std::clamp(p.y / r, -1.0f, 1.0f));
        const float phi = std::atan2(p.x, p.z);
        p *= 1.0f + amplitude * std::sin(3.0f * theta) * std::cos(3.0f * phi);
    }
    m.normals.clear();
    return m;
}

/// A torus around the y axis (ring radius R, tube radius r): closed, outward-wound, concave
/// on the inner side of the ring (negative Gaussian curvature) and convex outside.
inline TriangleMesh torus(float R = 0.5f, float r = 0.2f, int ring = 32, int tube = 16)
{
    TriangleMesh m;
    m.name = "torus";
    for (int i = 0; i < ring; ++i)
        for (int j = 0; j < tube; ++j) {
            const float a = 2.0f * float(M_PI) * i / ring, b = 2.0f * float(M_PI) * j / tube;
            const float rho = R + r * std::cos(b);
            m.positions.emplace_back(rho * std::cos(a), r * std::sin(b), rho * std::sin(a));
        }
    auto id = [&](int i, int j) { return uint32_t(((i + ring) % ring) * tube + (j + tube) % tube); };
    for (int i = 0; i < ring; ++i)
        for (int j = 0; j < tube; ++j) {
            // Outward: (d/db) x (d/da) points away from the tube's centre line.
            for (uint32_t v : {id(i, j), id(i, j + 1), id(i + 1, j + 1), id(i, j), id(i + 1, j + 1), id(i + 1, j)})
                m.indices.push_back(v);
        }
    return m;
}

/// A lattice on `mesh` with the stone command's default shell (15% of the size, a margin of
/// 1.5 depth voxels outside).
struct TestLattice {
    std::unique_ptr<SlabLattice> lattice;
    SlabShell shell;
};

inline TestLattice make_lattice(const TriangleMesh& mesh, int n_t, int n_d, double depth)
{
    ShellOptions o;
    o.outer_margin = 1.5 * depth / n_d;
    o.depth = depth + o.outer_margin;
    TestLattice t;
    t.shell = build_slab_shell(mesh, o);
    t.lattice = std::make_unique<SlabLattice>(t.shell, n_t, n_d);
    return t;
}

} // namespace patina::texgen::stone::test
