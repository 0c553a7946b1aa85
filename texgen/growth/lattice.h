// The lattice a growth model runs on (Dorsey & Hanrahan 1996 §3.3; Barabási & Stanley 1995):
// nodes with up to four neighbours and a size in world units. A flat strip is a plain grid;
// on a mesh the nodes are the covered texels of its uv layout and a node at the edge of a uv
// island continues into the island across the seam (surface_lattice.h), so that a pattern
// grows over the surface rather than over the texture.
#pragma once

#include <Imath/ImathVec.h>

#include <array>
#include <cstdint>
#include <vector>

namespace patina::texgen {

/// What lies beyond the edges of a flat grid: nothing (`open`, the default: edge nodes have
/// fewer neighbours, as on a real strip of finite size) or the opposite edge (`periodic`:
/// the grid is one tile of an endless sheet, every node has four neighbours, and growth
/// statistics are those of the bulk; along an axis of fewer than 3 nodes nothing wraps).
enum class GridBoundary { open, periodic };

struct Lattice {
    /// Up to four neighbours per node (the cardinal directions of the grid, or their
    /// continuation across a seam); -1 where the lattice ends. Symmetric: if b is a
    /// neighbour of a, a is a neighbour of b.
    std::vector<std::array<int32_t, 4>> neighbours;
    /// World length of one lattice step at the node (m): the mean length of its edges.
    std::vector<float> cell_size;
    /// World position of the node (m), for solid noise and for sizes in world units.
    std::vector<Imath::V3f> position;

    /// How the nodes sit in the images they are written to: one tile per UDIM tile, row 0
    /// at the top (the TexelGrid convention). node_of_texel[y * width + x] is the node of
    /// that texel or -1.
    struct Tile {
        int udim = 1001;
        int width = 0;
        int height = 0;
        std::vector<int32_t> node_of_texel;
    };
    std::vector<Tile> tiles;

    size_t size() const { return neighbours.size(); }
};

/// A width x height grid of square cells of side `cell_size` (m) in the z = 0 plane with
/// open or periodic boundaries; node y * width + x is texel (x, y) of tile 1001, at position
/// ((x + 0.5) cell_size, (height - y - 0.5) cell_size, 0). Neighbour order: +x, -x, +y, -y
/// (image rows, y down). Throws std::invalid_argument for non-positive sizes.
Lattice make_grid_lattice(int width, int height, float cell_size,
                          GridBoundary boundary = GridBoundary::open);

}  // namespace patina::texgen
