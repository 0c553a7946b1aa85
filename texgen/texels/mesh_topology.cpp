#include "texgen/texels/mesh_topology.h"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <tuple>
#include <vector>

namespace patina::texgen {

std::vector<uint32_t> welded_vertices(const TriangleMesh& mesh)
{
    const size_t n = mesh.positions.size();
    std::vector<uint32_t> order(n);
    std::iota(order.begin(), order.end(), 0u);
    const auto key = [&](uint32_t v) {
        const Imath::V3f& p = mesh.positions[v];
        return std::make_tuple(p.x, p.y, p.z, v);
    };
    std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
    std::vector<uint32_t> welded(n);
    for (size_t i = 0; i < n; ++i)
        welded[order[i]] = i > 0 && mesh.positions[order[i]] == mesh.positions[order[i - 1]]
                               ? welded[order[i - 1]]
                               : order[i];
    return welded;
}

namespace {

    /// Union-find that keeps each element's parity relative to its root (0: wound like the
    /// root, 1: against it).
    struct ParitySets {
        std::vector<uint32_t> parent;
        std::vector<uint8_t> parity; // relative to parent
        explicit ParitySets(size_t n) : parent(n), parity(n, 0)
        {
            std::iota(parent.begin(), parent.end(), 0u);
        }
        std::pair<uint32_t, uint8_t> find(uint32_t i)
        {
            uint8_t p = 0;
            uint32_t root = i;
            while (parent[root] != root) {
                p ^= parity[root];
                root = parent[root];
            }
            // Compress: point every element of the path at the root with its parity.
            uint8_t q = p;
            while (parent[i] != root && parent[i] != i) {
                const uint32_t next = parent[i];
                const uint8_t own = parity[i];
                parent[i] = root;
                parity[i] = q;
                q ^= own;
                i = next;
            }
            return {root, p};
        }
        /// Join a and b with b's winding relative to a's; returns false for a contradiction
        /// (a non-orientable piece), which leaves the sets as they were.
        bool join(uint32_t a, uint32_t b, uint8_t relative)
        {
            const auto [ra, pa] = find(a);
            const auto [rb, pb] = find(b);
            if (ra == rb)
                return (pa ^ pb) == relative;
            const uint32_t low = std::min(ra, rb), high = std::max(ra, rb);
            parent[high] = low;
            parity[high] = pa ^ pb ^ relative;
            return true;
        }
    };

} // namespace

MeshTopology mesh_topology(const TriangleMesh& mesh)
{
    MeshTopology topology;
    const std::vector<uint32_t> welded = welded_vertices(mesh);
    const size_t triangles = mesh.triangle_count();
    // (edge key, triangle, forward): forward when the triangle runs from the lower vertex.
    struct EdgeUse {
        uint64_t key;
        uint32_t triangle;
        uint8_t forward;
    };
    std::vector<EdgeUse> uses;
    uses.reserve(3 * triangles);
    for (size_t t = 0; t < triangles; ++t)
        for (int e = 0; e < 3; ++e) {
            const uint32_t a = welded[mesh.indices[3 * t + e]];
            const uint32_t b = welded[mesh.indices[3 * t + (e + 1) % 3]];
            if (a != b)
                uses.push_back({uint64_t(std::min(a, b)) << 32 | std::max(a, b),
                                static_cast<uint32_t>(t), static_cast<uint8_t>(a < b)});
        }
    std::sort(uses.begin(), uses.end(), [](const EdgeUse& x, const EdgeUse& y) {
        return std::tie(x.key, x.triangle, x.forward) < std::tie(y.key, y.triangle, y.forward);
    });

    ParitySets winding(triangles);
    std::vector<uint32_t> piece(triangles);
    std::iota(piece.begin(), piece.end(), 0u);
    const auto piece_of = [&](uint32_t t) {
        while (piece[t] != t)
            t = piece[t] = piece[piece[t]];
        return t;
    };
    for (size_t i = 0; i < uses.size();) {
        size_t end = i + 1;
        while (end < uses.size() && uses[end].key == uses[i].key)
            ++end;
        const size_t count = end - i;
        if (count == 1)
            ++topology.boundary_edges;
        else if (count > 2)
            ++topology.non_manifold_edges;
        else // Consistent winding runs a shared edge in opposite directions.
            winding.join(uses[i].triangle, uses[i + 1].triangle,
                         uses[i].forward == uses[i + 1].forward ? 1 : 0);
        for (size_t k = i + 1; k < end; ++k) {
            const uint32_t a = piece_of(uses[i].triangle), b = piece_of(uses[k].triangle);
            if (a != b)
                piece[std::max(a, b)] = std::min(a, b);
        }
        i = end;
    }

    // Per winding set (triangles joined through manifold edges), the smaller side is flipped.
    std::vector<uint32_t> against(triangles, 0), with(triangles, 0);
    for (size_t t = 0; t < triangles; ++t) {
        const auto [root, parity] = winding.find(static_cast<uint32_t>(t));
        (parity ? against : with)[root] += 1;
        topology.pieces += piece_of(static_cast<uint32_t>(t)) == t;
    }
    for (size_t t = 0; t < triangles; ++t)
        topology.flipped_faces += std::min(against[t], with[t]);
    return topology;
}

} // namespace patina::texgen
