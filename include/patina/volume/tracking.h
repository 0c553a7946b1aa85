// patina/volume/tracking.h — unbiased free-path sampling (delta tracking) and transmittance
// estimation (ratio tracking) in a heterogeneous medium bounded by a MajorantGrid.
//
// Both walk the ray's majorant segments, drawing tentative collisions from the homogeneous
// majorant σ̄ (exponential steps in optical depth that carry over from one segment to the
// next), and evaluate the real extinction σt(x) only there:
//
//   delta tracking   a tentative collision is real with probability σt(x)/σ̄; the first
//                    real one is distributed as σt(x) T(x) (Woodcock et al. 1965;
//                    pbrt-v4 §14.2.1), the ray passes with probability T(t_max)
//   ratio tracking   T̂ = Π (1 − σt(x_i)/σ̄) over every tentative collision, E[T̂] = T
//                    (Novák, Selle, Jarosz 2014, "Residual Ratio Tracking", SIGGRAPH Asia,
//                    §3), with Russian roulette once T̂ < 0.05 (kill with probability ½,
//                    else double), which keeps it unbiased and stops it early in stone
//
// The random numbers come from a small generator (splitmix64, Steele et al. 2014) seeded
// from the caller's uniform number and the ray, so an estimate is a deterministic function
// of its inputs whatever the thread.
#pragma once

#include <patina/volume/majorant_grid.h>

#include <cmath>
#include <cstdint>
#include <cstring>

namespace patina::volume {

/// splitmix64: a fast generator with good equidistribution for short streams.
class TrackingRng {
public:
    explicit TrackingRng(uint64_t seed) : state_(seed) {}
    /// Seeds from a uniform number and a ray, so that different rays with the same u differ.
    TrackingRng(float u, shading::Vec3 o, shading::Vec3 d)
    {
        const float words[7] = {u, o.x, o.y, o.z, d.x, d.y, d.z};
        uint64_t h = 0x9e3779b97f4a7c15ULL;
        for (float w : words) {
            uint32_t bits;
            std::memcpy(&bits, &w, sizeof bits);
            h = mix(h ^ bits);
        }
        state_ = h;
    }
    uint64_t next_u64()
    {
        state_ += 0x9e3779b97f4a7c15ULL;
        return mix(state_);
    }
    /// Uniform in [0, 1), 53 bits.
    double next_double() { return static_cast<double>(next_u64() >> 11) * 0x1p-53; }

private:
    static uint64_t mix(uint64_t z)
    {
        z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
        z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
        return z ^ (z >> 31);
    }
    uint64_t state_ = 0;
};

/// Delta tracking along o + t d (d unit), t in [0, t_max]. `sigma_t(t)` returns the
/// extinction at distance t and must stay below `sigma_scale` times the grid's bounds.
/// Returns true and sets *t_hit at the first real collision; false when the ray passes.
template <typename SigmaT>
bool delta_track(const MajorantGrid& majorants, double sigma_scale, shading::Vec3 o,
                 shading::Vec3 d, double t_max, SigmaT&& sigma_t, TrackingRng& rng, double* t_hit)
{
    // Optical depth left to the next tentative collision (exponential, rate 1)
    double tau = -std::log1p(-rng.next_double());
    bool hit = false;
    majorants.traverse(o, d, t_max, [&](double t0, double t1, float max_density) {
        const double sigma_bar = sigma_scale * max_density;
        if (!(sigma_bar > 0.0))
            return true;
        for (double t = t0;;) {
            const double step = tau / sigma_bar;
            if (t + step >= t1) {
                tau -= sigma_bar * (t1 - t);
                return true;
            }
            t += step;
            tau = -std::log1p(-rng.next_double());
            // Real collision with probability σt/σ̄: Woodcock et al. 1965
            if (rng.next_double() * sigma_bar < sigma_t(t)) {
                *t_hit = t;
                hit = true;
                return false;
            }
        }
    });
    return hit;
}

/// Ratio tracking estimate of the transmittance along o + t d (d unit), t in [0, t_max].
template <typename SigmaT>
double ratio_track(const MajorantGrid& majorants, double sigma_scale, shading::Vec3 o,
                   shading::Vec3 d, double t_max, SigmaT&& sigma_t, TrackingRng& rng)
{
    constexpr double kRouletteBelow = 0.05;
    double tr = 1.0;
    double tau = -std::log1p(-rng.next_double());
    majorants.traverse(o, d, t_max, [&](double t0, double t1, float max_density) {
        const double sigma_bar = sigma_scale * max_density;
        if (!(sigma_bar > 0.0))
            return true;
        for (double t = t0;;) {
            const double step = tau / sigma_bar;
            if (t + step >= t1) {
                tau -= sigma_bar * (t1 - t);
                return true;
            }
            t += step;
            tau = -std::log1p(-rng.next_double());
            // T̂ *= 1 − σt/σ̄: Novák et al. 2014 §3 (ratio tracking)
            tr *= std::max(0.0, 1.0 - sigma_t(t) / sigma_bar);
            if (tr <= 0.0)
                return false;
            if (tr < kRouletteBelow) {
                if (rng.next_double() < 0.5) {
                    tr = 0.0;
                    return false;
                }
                tr *= 2.0;
            }
        }
    });
    return tr;
}

} // namespace patina::volume
