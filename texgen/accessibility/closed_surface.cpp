#include "texgen/accessibility/closed_surface.h"

#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace patina::texgen {

namespace {

    constexpr float kInfinity = std::numeric_limits<float>::infinity();

    /// Scratch for one line of the distance transform.
    struct LineScratch {
        std::vector<double> f;
        std::vector<int32_t> site;
        std::vector<int> v;       // parabolas of the lower envelope
        std::vector<double> z;    // their boundaries
        void resize(int n)
        {
            f.resize(n);
            site.resize(n);
            v.resize(n);
            z.resize(n + 1);
        }
    };

    /// One line of the squared distance transform of a sampled function: out(q) =
    /// min_p (q - p)^2 + f(p), with the minimising p's site. Felzenszwalb & Huttenlocher
    /// 2012, Alg. 1 (DT of a 1D sampled function); infinite f(p) are not parabolas.
    void transform_line(float* g, int32_t* site, size_t stride, int n, LineScratch& s)
    {
        int first = -1;
        for (int q = 0; q < n; ++q) {
            s.f[q] = g[q * stride];
            s.site[q] = site[q * stride];
            if (first < 0 && std::isfinite(s.f[q]))
                first = q;
        }
        if (first < 0)
            return;  // no site on this line: stays infinite, site -1
        // Compute the lower envelope of the parabolas rooted at (p, f(p)).
        int k = 0;
        s.v[0] = first;
        s.z[0] = -std::numeric_limits<double>::infinity();
        s.z[1] = std::numeric_limits<double>::infinity();
        for (int q = first + 1; q < n; ++q) {
            if (!std::isfinite(s.f[q]))
                continue;
            const double fq = s.f[q] + double(q) * q;
            double x;
            while (true) {
                const int p = s.v[k];
                // Intersection of the parabolas from q and from v[k]; z[0] = -inf ends it.
                x = (fq - (s.f[p] + double(p) * p)) / (2.0 * q - 2.0 * p);
                if (x > s.z[k])
                    break;
                --k;
            }
            ++k;
            s.v[k] = q;
            s.z[k] = x;
            s.z[k + 1] = std::numeric_limits<double>::infinity();
        }
        // Fill in the values of the envelope.
        k = 0;
        for (int q = 0; q < n; ++q) {
            while (s.z[k + 1] < q)
                ++k;
            const int p = s.v[k];
            g[q * stride] = static_cast<float>(double(q - p) * (q - p) + s.f[p]);
            site[q * stride] = s.site[p];
        }
    }

}  // namespace

ClosedSurface::ClosedSurface(const ClosestPointScene& scene, const Imath::Box3f& bounds,
                             float radius, int voxels)
    : radius_(radius)
{
    if (!(radius > 0.0f) || !std::isfinite(radius))
        throw std::runtime_error(fmt::format(
            "accessibility: --max-radius (the offset-surface ball radius) must be a positive "
            "number of metres (got {})", radius));
    if (voxels < 8 || voxels > 2048)
        throw std::runtime_error(
            fmt::format("accessibility: --voxels must be in [8, 2048] (got {})", voxels));
    if (bounds.isEmpty())
        throw std::runtime_error("accessibility: the scene is empty (no bounds to voxelise)");

    // Cubic voxels; the padding leaves room for the r-balls outside the geometry.
    const Imath::V3f size = bounds.size();
    const float longest = std::max({size.x, size.y, size.z}) + 2.0f * radius;
    h_ = longest / static_cast<float>(voxels - 4);
    const float pad = radius + 2.0f * h_;
    origin_ = bounds.min - Imath::V3f(pad);
    auto cells = [&](float extent) {
        return std::max(1, static_cast<int>(std::ceil((extent + 2.0f * pad) / h_)));
    };
    nx_ = cells(size.x);
    ny_ = cells(size.y);
    nz_ = cells(size.z);
    const double total = double(nx_) * ny_ * nz_;
    if (total > double(std::numeric_limits<int32_t>::max()))
        throw std::runtime_error(fmt::format(
            "accessibility: a {}x{}x{} voxel grid is too large; lower --voxels", nx_, ny_, nz_));
    max_height_ = h_ * std::sqrt(float(nx_) * nx_ + float(ny_) * ny_ + float(nz_) * nz_);

    const size_t count = static_cast<size_t>(total);
    rho2_.assign(count, -1.0f);
    site_.assign(count, -1);
    std::vector<float> g(count, kInfinity);

    // 1. Exact distance to the triangles at every voxel centre, capped where it no longer
    //    changes U near the surface (a capped ball is still empty, so still inside U).
    const double cap = radius + 2.0 * std::sqrt(3.0) * h_;
    tbb::parallel_for(tbb::blocked_range<size_t>(0, size_t(ny_) * nz_, 16),
                      [&](const tbb::blocked_range<size_t>& rows) {
        for (size_t row = rows.begin(); row != rows.end(); ++row) {
            const int y = static_cast<int>(row % ny_), z = static_cast<int>(row / ny_);
            for (int x = 0; x < nx_; ++x) {
                const Imath::V3d centre(origin_.x + (x + 0.5) * h_, origin_.y + (y + 0.5) * h_,
                                        origin_.z + (z + 0.5) * h_);
                const double d = scene.distance(centre, cap);
                if (d < radius)
                    continue;  // an r-ball here would meet geometry
                const size_t i = index(x, y, z);
                const double rho = std::min(d, cap) / h_;
                rho2_[i] = static_cast<float>(rho * rho);
                g[i] = -rho2_[i];
                site_[i] = static_cast<int32_t>(i);
            }
        }
    });

    // 2. min_v |x - v|^2 - rho_v^2 on the grid, one axis at a time (FH 2012 §3 for
    //    separable d-dimensional transforms), in voxel units.
    auto pass = [&](size_t lines, int length, size_t stride, auto line_start) {
        tbb::parallel_for(tbb::blocked_range<size_t>(0, lines, 32),
                          [&](const tbb::blocked_range<size_t>& range) {
            LineScratch scratch;
            scratch.resize(length);
            for (size_t line = range.begin(); line != range.end(); ++line) {
                const size_t start = line_start(line);
                transform_line(&g[start], &site_[start], stride, length, scratch);
            }
        });
    };
    pass(size_t(ny_) * nz_, nx_, 1, [&](size_t line) { return line * nx_; });
    pass(size_t(nx_) * nz_, ny_, size_t(nx_), [&](size_t line) {
        return index(static_cast<int>(line % nx_), 0, static_cast<int>(line / nx_));
    });
    pass(size_t(nx_) * ny_, nz_, size_t(nx_) * ny_, [&](size_t line) {
        return index(static_cast<int>(line % nx_), static_cast<int>(line / nx_), 0);
    });
}

bool ClosedSurface::inside(const Imath::V3f& x) const
{
    // Continuous voxel coordinates: voxel centres at integers.
    const double g[3] = {(double(x.x) - origin_.x) / h_ - 0.5, (double(x.y) - origin_.y) / h_ - 0.5,
                         (double(x.z) - origin_.z) / h_ - 0.5};
    const int n[3] = {nx_, ny_, nz_};
    int i0[3], i1[3];
    for (int a = 0; a < 3; ++a) {
        if (!(g[a] >= -0.5 && g[a] <= n[a] - 0.5))
            return true;  // beyond the padding: no geometry within r
        i0[a] = std::clamp(static_cast<int>(std::floor(g[a])), 0, n[a] - 1);
        i1[a] = std::min(i0[a] + 1, n[a] - 1);
    }
    // The minimising ball centres of the 8 voxels around x: their power distances bound
    // (and in practice equal) the envelope at x.
    double best = std::numeric_limits<double>::infinity();
    for (int corner = 0; corner < 8; ++corner) {
        const int cx = (corner & 1) ? i1[0] : i0[0];
        const int cy = (corner & 2) ? i1[1] : i0[1];
        const int cz = (corner & 4) ? i1[2] : i0[2];
        const int32_t s = site_[index(cx, cy, cz)];
        if (s < 0)
            continue;
        const size_t si = static_cast<size_t>(s);
        const double sx = double(si % nx_), sy = double((si / nx_) % ny_),
                     sz = double(si / (size_t(nx_) * ny_));
        const double d2 = (g[0] - sx) * (g[0] - sx) + (g[1] - sy) * (g[1] - sy) +
                          (g[2] - sz) * (g[2] - sz) - rho2_[si];
        best = std::min(best, d2);
    }
    // Strictly inside: a ball that merely touches x (the surface under P) does not count.
    return best < -1e-6;
}

float ClosedSurface::height(const Imath::V3f& P, const Imath::V3f& n) const
{
    // March in half-voxel steps (U_h is a union of balls of radius >= r, so a step skips
    // into and out of it only when grazing), then bisect the first step that enters U_h.
    const float step = 0.5f * h_;
    float outside = 0.0f;
    for (float t = step; t <= max_height_; t += step) {
        if (!inside(P + t * n)) {
            outside = t;
            continue;
        }
        float in = t;
        for (int i = 0; i < 24; ++i) {
            const float mid = 0.5f * (outside + in);
            if (inside(P + mid * n))
                in = mid;
            else
                outside = mid;
        }
        return 0.5f * (outside + in);
    }
    return max_height_;
}

}  // namespace patina::texgen
