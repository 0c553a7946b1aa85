#include "texgen/patina/heightfield_offset.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>

namespace patina::texgen {
namespace {

    constexpr int kMaxRadiusCells = 128;
    constexpr float kInfinity = std::numeric_limits<float>::infinity();

    std::string number(double v)
    {
        std::ostringstream s;
        s << v;
        return s.str();
    }

    [[noreturn]] void fail(const std::string& what)
    {
        throw std::invalid_argument("offset: " + what);
    }

    void check_field(std::span<const float> heights, int width, int height, float cell_size,
                     float radius, const char* radius_name)
    {
        if (width <= 0 || height <= 0) {
            fail("height field size " + std::to_string(width) + " x " + std::to_string(height) +
                 " is not positive");
        }
        if (heights.size() != static_cast<size_t>(width) * static_cast<size_t>(height)) {
            fail("the height field has " + std::to_string(heights.size()) + " cells, not " +
                 std::to_string(width) + " x " + std::to_string(height));
        }
        if (!(std::isfinite(cell_size) && cell_size > 0.0f)) {
            fail("cell size " + number(cell_size) + " um is not positive and finite");
        }
        if (!std::isfinite(radius) || radius < 0.0f) {
            fail(std::string(radius_name) + " " + number(radius) + " um is negative or not finite");
        }
        if (radius / cell_size > kMaxRadiusCells) {
            fail(std::string(radius_name) + " " + number(radius) + " um is " +
                 number(radius / cell_size) + " cells of " + number(cell_size) + " um; at most " +
                 std::to_string(kMaxRadiusCells) + " are supported (use a coarser grid)");
        }
        for (size_t i = 0; i < heights.size(); ++i) {
            if (!std::isfinite(heights[i])) {
                fail("height " + number(heights[i]) + " at cell " + std::to_string(i) +
                     " is not finite");
            }
        }
    }

    /// Cell index i (any integer) of an axis of n cells: clamped to the edge, or wrapped.
    int continued(int i, int n, GridBoundary boundary)
    {
        if (boundary == GridBoundary::periodic)
            return ((i % n) + n) % n;
        return std::clamp(i, 0, n - 1);
    }

    /// The field continued beyond its border (by its edge values, or periodically), padded
    /// by `pad` cells.
    std::vector<float> padded(std::span<const float> h, int width, int height, int pad,
                              GridBoundary boundary)
    {
        const int pw = width + 2 * pad;
        const int ph = height + 2 * pad;
        std::vector<float> out(static_cast<size_t>(pw) * ph);
        for (int y = 0; y < ph; ++y) {
            const int sy = continued(y - pad, height, boundary);
            for (int x = 0; x < pw; ++x) {
                const int sx = continued(x - pad, width, boundary);
                out[static_cast<size_t>(y) * pw + x] = h[static_cast<size_t>(sy) * width + sx];
            }
        }
        return out;
    }

    void for_each_row(int rows, const auto& f)
    {
        tbb::parallel_for(tbb::blocked_range<int>(0, rows, 1),
                          [&](const tbb::blocked_range<int>& r) {
                              for (int y = r.begin(); y != r.end(); ++y) {
                                  f(y);
                              }
                          });
    }

    /// A cell offset of the ball's footprint and its cap less the radius, c(d) - r <= 0
    /// (exactly 0 at the centre, so flat ground closes to its own height bit for bit).
    struct CapOffset {
        int dx;
        int dy;
        float cap_minus_r;
    };

}  // namespace

std::vector<float> closing_fill(std::span<const float> heights_um, int width, int height,
                                float cell_size_um, float radius_um, GridBoundary boundary)
{
    check_field(heights_um, width, height, cell_size_um, radius_um, "radius");
    const size_t cells = static_cast<size_t>(width) * height;
    std::vector<float> fill(cells, 0.0f);
    const int R = static_cast<int>(std::floor(radius_um / cell_size_um));
    if (R == 0) {
        // The ball fits between neighbouring samples: it touches every one of them.
        return fill;
    }

    // The ball's footprint: every cell offset within r, with its cap height.
    const double r = radius_um;
    const double c = cell_size_um;
    std::vector<CapOffset> ball;
    for (int dy = -R; dy <= R; ++dy) {
        for (int dx = -R; dx <= R; ++dx) {
            const double d2 = (double(dx) * dx + double(dy) * dy) * c * c;
            if (d2 <= r * r) {
                const double cap = std::sqrt(r * r - d2);
                ball.push_back({dx, dy, dx == 0 && dy == 0 ? 0.0f : float(cap - r)});
            }
        }
    }

    // Positive offset (dilation by the ball), on the grid padded by R, from the field padded
    // by 2R; kept less r: D'(p) = max_q h(q) + c(p - q) - r.
    const int pad2 = 2 * R;
    const std::vector<float> h2 = padded(heights_um, width, height, pad2, boundary);
    const int w2 = width + 2 * pad2;
    const int w1 = width + 2 * R;
    const int h1 = height + 2 * R;
    std::vector<float> dil(static_cast<size_t>(w1) * h1, -kInfinity);
    for_each_row(h1, [&](int y1) {
        float* out = dil.data() + static_cast<size_t>(y1) * w1;
        for (const CapOffset& o : ball) {
            // Cell (x1, y1) of dil is cell (x1 + R, y1 + R) of h2.
            const float* src = h2.data() + static_cast<size_t>(y1 + R + o.dy) * w2 + R + o.dx;
            const float a = o.cap_minus_r;
            for (int x = 0; x < w1; ++x) {
                const float v = src[x] + a;
                out[x] = out[x] > v ? out[x] : v;
            }
        }
    });

    // Negative offset (erosion by the ball): C(p) = min_q D'(q) + r - c(p - q); the
    // closed surface less the original height is the fill.
    for_each_row(height, [&](int y) {
        std::vector<float> closed(static_cast<size_t>(width), kInfinity);
        for (const CapOffset& o : ball) {
            const float* src = dil.data() + static_cast<size_t>(y + R + o.dy) * w1 + R + o.dx;
            const float a = o.cap_minus_r;
            for (int x = 0; x < width; ++x) {
                const float v = src[x] - a;
                closed[x] = closed[x] < v ? closed[x] : v;
            }
        }
        const float* h = heights_um.data() + static_cast<size_t>(y) * width;
        float* f = fill.data() + static_cast<size_t>(y) * width;
        for (int x = 0; x < width; ++x) {
            f[x] = std::max(closed[x] - h[x], 0.0f);
        }
    });
    return fill;
}

namespace {

    std::vector<float> tangent_radius_named(std::span<const float> heights_um, int width,
                                            int height, float cell_size_um, float max_radius_um,
                                            const char* radius_name, GridBoundary boundary)
    {
        check_field(heights_um, width, height, cell_size_um, max_radius_um, radius_name);
        const size_t cells = static_cast<size_t>(width) * height;
        std::vector<float> radius(cells, max_radius_um);
        if (max_radius_um == 0.0f) {
            return radius;
        }

        // Only samples within 2 rho_max of p can touch a tangent sphere of radius <= rho_max;
        // visit them nearest first, so a crevice stops the scan early.
        const double c = cell_size_um;
        const double rho_max = max_radius_um;
        const int S = static_cast<int>(std::floor(2.0 * rho_max / c));
        struct Offset {
            int dx;
            int dy;
            double planar;  // |(dx, dy)| c
        };
        std::vector<Offset> offsets;
        for (int dy = -S; dy <= S; ++dy) {
            for (int dx = -S; dx <= S; ++dx) {
                const double planar = std::hypot(double(dx), double(dy)) * c;
                if ((dx != 0 || dy != 0) && planar <= 2.0 * rho_max) {
                    offsets.push_back({dx, dy, planar});
                }
            }
        }
        std::stable_sort(offsets.begin(), offsets.end(),
                         [](const Offset& a, const Offset& b) { return a.planar < b.planar; });

        const std::vector<float> hp = padded(heights_um, width, height, S, boundary);
        const int pw = width + 2 * S;
        auto at = [&](int x, int y) { return double(hp[static_cast<size_t>(y + S) * pw + x + S]); };

        // The highest sample within S cells of each cell (a square window, separable; the
        // disc of radius 2 rho_max lies inside it): a bound that ends the scan early.
        std::vector<float> row_max(hp.size());
        for_each_row(height + 2 * S, [&](int y) {
            const float* src = hp.data() + static_cast<size_t>(y) * pw;
            float* out = row_max.data() + static_cast<size_t>(y) * pw;
            for (int x = S; x < S + width; ++x) {
                out[x] = *std::max_element(src + x - S, src + x + S + 1);
            }
        });
        std::vector<float> local_max(cells);
        for_each_row(height, [&](int y) {
            for (int x = 0; x < width; ++x) {
                float m = -kInfinity;
                for (int k = 0; k <= 2 * S; ++k) {
                    m = std::max(m, row_max[static_cast<size_t>(y + k) * pw + x + S]);
                }
                local_max[static_cast<size_t>(y) * width + x] = m;
            }
        });

        for_each_row(height, [&](int y) {
            for (int x = 0; x < width; ++x) {
                // Upward unit normal of the field at p, from central differences.
                const double p = at(x, y);
                const double gx = (at(x + 1, y) - at(x - 1, y)) / (2.0 * c);
                const double gy = (at(x, y + 1) - at(x, y - 1)) / (2.0 * c);
                const double norm = std::sqrt(gx * gx + gy * gy + 1.0);
                const double nx = -gx / norm;
                const double ny = -gy / norm;
                const double nz = 1.0 / norm;

                // A sample q lies strictly inside the sphere of centre p + rho n, radius rho,
                // iff |q - p|^2 < 2 rho n.(q - p): it bounds rho by |q - p|^2 / (2 n.(q - p)).
                // For q at planar distance d that bound is at least d / 2, and, as
                // n.(q - p) <= a d + b (a = |n_xy|, b = n_z times the rise to the local
                // maximum), at least d^2 / (2 (a d + b)). Both grow with d, and the offsets
                // come nearest first: stop once either reaches rho (at once on flat ground
                // with nothing higher near, where a d + b = 0).
                const double a = std::sqrt(nx * nx + ny * ny);
                const double b = nz * (local_max[static_cast<size_t>(y) * width + x] - p);
                double rho = rho_max;
                for (const Offset& o : offsets) {
                    const double reach = a * o.planar + b;
                    if (reach <= 0.0 || o.planar >= 2.0 * rho ||
                        o.planar * o.planar >= 2.0 * rho * reach) {
                        break;
                    }
                    const double ex = o.dx * c;
                    const double ey = o.dy * c;
                    const double ez = at(x + o.dx, y + o.dy) - p;
                    const double along = nx * ex + ny * ey + nz * ez;
                    if (along > 0.0) {
                        rho = std::min(rho, (ex * ex + ey * ey + ez * ez) / (2.0 * along));
                    }
                }
                radius[static_cast<size_t>(y) * width + x] = static_cast<float>(rho);
            }
        });
        return radius;
    }

}  // namespace

std::vector<float> tangent_sphere_radius(std::span<const float> heights_um, int width, int height,
                                         float cell_size_um, float max_radius_um,
                                         GridBoundary boundary)
{
    return tangent_radius_named(heights_um, width, height, cell_size_um, max_radius_um,
                                "maximum radius", boundary);
}

float fill_from_tangent_radius(float tangent_radius, float radius)
{
    if (!std::isfinite(radius) || radius < 0.0f) {
        fail("radius " + number(radius) + " is negative or not finite");
    }
    if (std::isnan(tangent_radius)) {
        fail("the tangent-sphere radius is not a number");
    }
    if (tangent_radius >= radius) {
        return 0.0f;
    }
    // Fillet of an r-ball in a right-angled crease, at the point of tangent radius rho.
    const double rho = std::max(0.0, double(tangent_radius));
    const double r = radius;
    return static_cast<float>(r - std::sqrt(rho * (2.0 * r - rho)));
}

std::vector<float> tangent_sphere_fill(std::span<const float> heights_um, int width, int height,
                                       float cell_size_um, float radius_um, GridBoundary boundary)
{
    std::vector<float> fill = tangent_radius_named(heights_um, width, height, cell_size_um,
                                                   radius_um, "radius", boundary);
    for (float& f : fill) {
        f = fill_from_tangent_radius(f, radius_um);
    }
    return fill;
}

}  // namespace patina::texgen
