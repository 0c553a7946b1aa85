#include "texgen/stone_export/eroded_mesh.h"

#include <stdexcept>
#include <unordered_map>

namespace patina::texgen::stone {

using Imath::V3d;

TriangleMesh extract_eroded_surface(const WorldVolume& v, float iso)
{
    // Cells are the cubes between 8 voxel centres: (nx - 1) x (ny - 1) x (nz - 1).
    const int cx = v.nx - 1, cy = v.ny - 1, cz = v.nz - 1;
    auto value = [&](int i, int j, int k) { return v.density[v.index(i, j, k)]; };
    std::vector<int> vertex_of(size_t(cx) * cy * cz, -1);
    TriangleMesh mesh;
    mesh.name = "eroded";
    static const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0},
                                     {0, 0, 1}, {1, 0, 1}, {0, 1, 1}, {1, 1, 1}};
    static const int edge[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                    {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
    for (int k = 0; k < cz; ++k)
        for (int j = 0; j < cy; ++j)
            for (int i = 0; i < cx; ++i) {
                float d[8];
                int inside = 0;
                for (int c = 0; c < 8; ++c) {
                    d[c] = value(i + corner[c][0], j + corner[c][1], k + corner[c][2]);
                    inside += d[c] >= iso ? 1 : 0;
                }
                if (inside == 0 || inside == 8)
                    continue;
                V3d sum(0.0);
                int n = 0;
                for (const auto& e : edge) {
                    const float a = d[e[0]], b = d[e[1]];
                    if ((a >= iso) == (b >= iso))
                        continue;
                    const double t = (iso - a) / (b - a);
                    const V3d pa = v.centre(i + corner[e[0]][0], j + corner[e[0]][1],
                                            k + corner[e[0]][2]);
                    const V3d pb = v.centre(i + corner[e[1]][0], j + corner[e[1]][1],
                                            k + corner[e[1]][2]);
                    sum += pa + t * (pb - pa);
                    ++n;
                }
                const V3d p = sum / double(n);
                vertex_of[(size_t(k) * cy + j) * cx + i] = int(mesh.positions.size());
                mesh.positions.emplace_back(float(p.x), float(p.y), float(p.z));
            }
    auto cell = [&](int i, int j, int k) { return vertex_of[(size_t(k) * cy + j) * cx + i]; };
    auto quad = [&](int a, int b, int c, int d, bool flip) {
        if (a < 0 || b < 0 || c < 0 || d < 0)
            return;
        if (flip) {
            std::swap(b, d);
        }
        for (uint32_t idx : {uint32_t(a), uint32_t(b), uint32_t(c), uint32_t(a), uint32_t(c),
                             uint32_t(d)})
            mesh.indices.push_back(idx);
    };
    // A grid edge from voxel (i,j,k) to its +x/+y/+z neighbour that crosses the level set is
    // shared by four cells; their vertices make a quad around the edge.
    for (int k = 1; k < v.nz - 1; ++k)
        for (int j = 1; j < v.ny - 1; ++j)
            for (int i = 0; i < v.nx - 1; ++i) {
                const bool a = value(i, j, k) >= iso, b = value(i + 1, j, k) >= iso;
                if (a != b)
                    quad(cell(i, j - 1, k - 1), cell(i, j, k - 1), cell(i, j, k), cell(i, j - 1, k), b);
            }
    for (int k = 1; k < v.nz - 1; ++k)
        for (int j = 0; j < v.ny - 1; ++j)
            for (int i = 1; i < v.nx - 1; ++i) {
                const bool a = value(i, j, k) >= iso, b = value(i, j + 1, k) >= iso;
                if (a != b)
                    quad(cell(i - 1, j, k - 1), cell(i - 1, j, k), cell(i, j, k), cell(i, j, k - 1), b);
            }
    for (int k = 0; k < v.nz - 1; ++k)
        for (int j = 1; j < v.ny - 1; ++j)
            for (int i = 1; i < v.nx - 1; ++i) {
                const bool a = value(i, j, k) >= iso, b = value(i, j, k + 1) >= iso;
                if (a != b)
                    quad(cell(i - 1, j - 1, k), cell(i, j - 1, k), cell(i, j, k), cell(i - 1, j, k), b);
            }
    if (mesh.indices.empty())
        throw std::runtime_error("eroded surface: the density never crosses 1/2 (no stone "
                                 "left in the grid, or no air around it)");
    compute_vertex_normals(mesh);
    return mesh;
}

} // namespace patina::texgen::stone
