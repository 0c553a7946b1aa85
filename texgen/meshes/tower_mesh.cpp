#include "texgen/meshes/tower_mesh.h"

#include <Imath/ImathVec.h>

#include <array>
#include <cmath>
#include <stdexcept>

namespace patina::texgen {

namespace {

    using Imath::V2f;
    using Imath::V3f;

    /// Append a quad grid from corner `o` along `du` and `dv` (cross(du, dv) is the outward
    /// normal), mapped to the uv rectangle [u0, u1] x [v0, v1].
    void add_grid(TriangleMesh& m, const V3f& o, const V3f& du, const V3f& dv, int n,
                  float u0, float u1, float v0, float v1)
    {
        const V3f normal = du.cross(dv).normalized();
        const auto first = static_cast<uint32_t>(m.positions.size());
        for (int j = 0; j <= n; ++j) {
            for (int i = 0; i <= n; ++i) {
                const float s = static_cast<float>(i) / n, t = static_cast<float>(j) / n;
                m.positions.push_back(o + du * s + dv * t);
                m.normals.push_back(normal);
                m.uvs.emplace_back(u0 + (u1 - u0) * s, v0 + (v1 - v0) * t);
            }
        }
        for (int j = 0; j < n; ++j) {
            for (int i = 0; i < n; ++i) {
                const uint32_t a = first + j * (n + 1) + i;
                m.indices.insert(m.indices.end(), {a, a + 1, a + n + 2, a, a + n + 2, a + n + 1});
            }
        }
    }

    /// Append a triangle a, b, apex (counter-clockwise seen from outside) subdivided into n
    /// rows, mapped to a uv triangle with base [u0, u1] at v0 and apex at v1.
    void add_triangle(TriangleMesh& m, const V3f& a, const V3f& b, const V3f& apex, int n,
                      float u0, float u1, float v0, float v1)
    {
        const V3f normal = (b - a).cross(apex - a).normalized();
        const auto first = static_cast<uint32_t>(m.positions.size());
        // Row j (0 at the base) holds n - j + 1 vertices.
        std::vector<uint32_t> row_start;
        for (int j = 0; j <= n; ++j) {
            row_start.push_back(static_cast<uint32_t>(m.positions.size()) - first);
            const float t = static_cast<float>(j) / n;
            for (int i = 0; i <= n - j; ++i) {
                const float s = n - j > 0 ? static_cast<float>(i) / (n - j) : 0.5f;
                const V3f left = a + (apex - a) * t, right = b + (apex - b) * t;
                m.positions.push_back(left + (right - left) * s);
                m.normals.push_back(normal);
                const float ul = u0 + 0.5f * (u1 - u0) * t, ur = u1 - 0.5f * (u1 - u0) * t;
                m.uvs.emplace_back(ul + (ur - ul) * s, v0 + (v1 - v0) * t);
            }
        }
        for (int j = 0; j < n; ++j) {
            const uint32_t r0 = first + row_start[j], r1 = first + row_start[j + 1];
            for (int i = 0; i < n - j; ++i) {
                m.indices.insert(m.indices.end(), {r0 + i, r0 + i + 1, r1 + i});
                if (i + 1 < n - j)
                    m.indices.insert(m.indices.end(), {r0 + i + 1, r1 + i + 1, r1 + i});
            }
        }
    }

}  // namespace

TriangleMesh make_tower(const Imath::V3f& base, const TowerOptions& o)
{
    if (!(o.width > 0 && o.shaft_height > 0 && o.roof_height > 0 && o.eave >= 0) ||
        o.subdivisions < 1)
        throw std::invalid_argument("make_tower: sizes must be positive, subdivisions >= 1");
    TriangleMesh m;
    m.name = "tower";
    const float h = 0.5f * o.width, e = h + o.eave, top = o.shaft_height;
    const V3f c(base.x, 0.0f, base.z);
    // Corners counter-clockwise seen from above (+y): the outward normals of the faces
    // between consecutive corners then point away from the axis.
    const std::array<V3f, 4> corner = {V3f(-h, 0, h), V3f(h, 0, h), V3f(h, 0, -h), V3f(-h, 0, -h)};
    const std::array<V3f, 4> eave = {V3f(-e, top, e), V3f(e, top, e), V3f(e, top, -e),
                                     V3f(-e, top, -e)};
    const V3f apex = c + V3f(0, top + o.roof_height, 0);
    const float gap = 0.01f, cell = 0.25f;
    for (int f = 0; f < 4; ++f) {
        const V3f a = c + corner[f], b = c + corner[(f + 1) % 4];
        const float u0 = f * cell + gap, u1 = (f + 1) * cell - gap;
        add_grid(m, a, b - a, V3f(0, top, 0), o.subdivisions, u0, u1, 0.02f, 0.47f);
        add_triangle(m, c + eave[f], c + eave[(f + 1) % 4], apex, o.subdivisions, u0, u1, 0.52f,
                     0.98f);
    }
    // The soffit under the overhang (a flat ring facing down): thin, so each side gets a
    // narrow strip of uv space between the walls and the roof.
    if (o.eave > 0) {
        for (int f = 0; f < 4; ++f) {
            const V3f a = c + V3f(corner[f].x, top, corner[f].z);
            const V3f b = c + V3f(corner[(f + 1) % 4].x, top, corner[(f + 1) % 4].z);
            const V3f ea = c + eave[f], eb = c + eave[(f + 1) % 4];
            const auto first = static_cast<uint32_t>(m.positions.size());
            const float u0 = f * cell + gap, u1 = (f + 1) * cell - gap;
            for (const V3f& p : {a, b, eb, ea}) {
                m.positions.push_back(p);
                m.normals.emplace_back(0, -1, 0);
            }
            m.uvs.insert(m.uvs.end(), {V2f(u0, 0.48f), V2f(u1, 0.48f), V2f(u1, 0.51f),
                                       V2f(u0, 0.51f)});
            // Seen from below, a, eb, ea and a, b, eb wind counter-clockwise (normal -y).
            m.indices.insert(m.indices.end(),
                             {first, first + 2, first + 3, first, first + 1, first + 2});
        }
    }
    return m;
}

}  // namespace patina::texgen
