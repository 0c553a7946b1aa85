#include "texgen/growth/lattice.h"

#include <cmath>
#include <stdexcept>
#include <string>

namespace patina::texgen {

Lattice make_grid_lattice(int width, int height, float cell_size, GridBoundary boundary)
{
    if (width <= 0 || height <= 0 || !(cell_size > 0.0f) || !std::isfinite(cell_size))
        throw std::invalid_argument("grid lattice: width, height and cell size must be positive"
                                    " (got " + std::to_string(width) + " x " +
                                    std::to_string(height) + ", cell " +
                                    std::to_string(cell_size) + ")");
    Lattice lattice;
    const size_t n = static_cast<size_t>(width) * height;
    lattice.neighbours.resize(n);
    lattice.cell_size.assign(n, cell_size);
    lattice.position.resize(n);
    Lattice::Tile tile;
    tile.width = width;
    tile.height = height;
    tile.node_of_texel.resize(n);
    // Periodic: the step off one edge lands on the opposite edge (axes of at least 3 nodes,
    // so that a node's two neighbours along an axis are two nodes other than itself).
    const bool wrap_x = boundary == GridBoundary::periodic && width >= 3;
    const bool wrap_y = boundary == GridBoundary::periodic && height >= 3;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const int32_t i = y * width + x;
            const int32_t row = y * width;
            lattice.neighbours[i] = {
                x + 1 < width ? i + 1 : (wrap_x ? row : -1),
                x > 0 ? i - 1 : (wrap_x ? row + width - 1 : -1),
                y + 1 < height ? i + width : (wrap_y ? x : -1),
                y > 0 ? i - width : (wrap_y ? (height - 1) * width + x : -1)};
            lattice.position[i] = Imath::V3f((x + 0.5f) * cell_size,
                                             (height - y - 0.5f) * cell_size, 0.0f);
            tile.node_of_texel[i] = i;
        }
    }
    lattice.tiles.push_back(std::move(tile));
    return lattice;
}

}  // namespace patina::texgen
