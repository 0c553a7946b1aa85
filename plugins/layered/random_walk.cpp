// The reference of the layered shader (model = "random_walk"): the same stack evaluated by a
// position-free Monte Carlo random walk between the interfaces (Guo, Hasan, Yan, Zhao 2018,
// "Position-free Monte Carlo simulation for arbitrary layered BSDFs"; pbrt-v4's LayeredBxDF is
// the well-known implementation, this one is written for patina stacks).
//
// What the walk assumes, so that it differs from the KM model only by the approximations
// D&H 1996 §4.3 names (directional light attenuated by the diffuse transmittance; no
// scattering before or after a glossy reflection; KM's two-flux diffusion):
//   - A layer is a slab of thickness d with absorption σa = K/2 and scattering σs = S (per
//     µm) and an isotropic phase function: the mapping of the KM coefficients of a diffuse
//     flux, whose mean path per unit depth is 2 (so K = 2σa) and of whose isotropic
//     scattering half goes backwards (so S = 2 · σs/2). A dielectric base is a slab of
//     infinite thickness.
//   - An interface is index-matched (no refraction, as in the KM model): from either side
//     it reflects with the GGX lobe of the material below it (the dielectric Fresnel of
//     the index whose normal reflectance is its specular colour, fade-in of thin layers
//     included), with the lobe's directional albedo E(μ),
//     and passes the rest straight through. A metal base reflects with its GGX conductor
//     lobe and transmits nothing.
// eval estimates f(wo, wi) with next-event estimation: at every interface the walk meets from
// above, the glossy lobe towards wi, and at every scattering event, the phase function
// towards wi, each times the transmittance out of the stack along wi. Deterministic: the
// random numbers are seeded from (wo, wi, uv, wavelength).
#include "layered_model.h"

#include <patina/shading/fresnel.h>
#include <patina/shading/frame.h>
#include <patina/shading/sampling.h>

#include <bit>
#include <cmath>
#include <cstring>

namespace patina::layered {

using namespace patina::shading;

namespace {

    constexpr int kMaxEvents = 1024;
    constexpr float kInv4Pi = 0.07957747154594767f;

    /// SplitMix64 (Steele, Lea, Flood 2014): small, fast, good enough for a reference.
    class Rng {
    public:
        explicit Rng(uint64_t seed) : state_(seed) {}
        float next()
        {
            uint64_t z = (state_ += 0x9e3779b97f4a7c15ULL);
            z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
            z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
            z ^= z >> 31;
            return static_cast<float>(z >> 40) * 0x1p-24f;
        }
        Vec2 next2()
        {
            const float a = next();
            return {a, next()};
        }

    private:
        uint64_t state_;
    };

    uint64_t mix(uint64_t h, float x)
    {
        uint32_t bits;
        std::memcpy(&bits, &x, sizeof bits);
        h ^= bits + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
        return h * 0xff51afd7ed558ccdULL;
    }

    /// One wavelength's view of the stack: interfaces top to bottom, slab j below interface j.
    struct Walk {
        const PointState* s;
        int i;       ///< wavelength index
        GridPos gp;
        int n;       ///< interfaces
        bool metal_base;

        float sigma_a(int slab) const
        {
            const CompiledMaterial& m = slab < n - 1 ? *s->layer_material[slab] : *s->base;
            return 0.5f * grid_eval(m.absorption, gp);
        }
        float sigma_s(int slab) const
        {
            const CompiledMaterial& m = slab < n - 1 ? *s->layer_material[slab] : *s->base;
            return grid_eval(m.scattering, gp);
        }
        float depth(int slab) const
        {
            return slab < n - 1 ? s->thickness_um[slab] : INFINITY;
        }
        /// Directional albedo of interface j's lobe (probability of reflecting).
        float reflect_probability(int j, float mu) const
        {
            const Interface& l = s->lobe[j];
            return l.fade * albedo_table(*l.material, l.f0[i], mu);
        }
        float fresnel(int j, float c) const
        {
            const Interface& l = s->lobe[j];
            if (l.material->metal)
                return fresnel_conductor(c, l.f0[i], l.kappa[i]);
            return dielectric_fresnel(c, l.f0[i], l.eta[i]);
        }
        /// The glossy BRDF of interface j (fade included) for directions above it.
        float lobe_f(int j, Vec3 wo, Vec3 wi) const
        {
            const Vec3 h = wo + wi;
            if (wo.z <= 0.0f || wi.z <= 0.0f || length_squared(h) == 0.0f)
                return 0.0f;
            const Vec3 wm = normalize(h);
            const TrowbridgeReitz& d = s->lobe[j].material->distribution;
            const float v = s->lobe[j].fade * d.d(wm) * d.g(wo, wi) *
                            fresnel(j, std::clamp(dot(wo, wm), 0.0f, 1.0f)) /
                            (4.0f * wo.z * wi.z);
            return is_finite(v) ? v : 0.0f;
        }
    };

    /// Reflects a walk direction `d` at interface j (coming from above if d.z < 0); returns
    /// the weight F G2 / G1 and the new direction, or 0 when the sampled normal shadows it.
    float reflect_at(const Walk& w, int j, Vec3 d, Vec2 u, Vec3* out)
    {
        Vec3 v = -d;
        const bool from_below = v.z < 0.0f;
        if (from_below)
            v.z = -v.z;
        const TrowbridgeReitz& dist = w.s->lobe[j].material->distribution;
        const Vec3 wm = dist.sample_wm(v, u);
        Vec3 r = normalize(reflect(v, wm));
        if (r.z <= 0.0f)
            return 0.0f;
        const float weight =
            w.fresnel(j, std::clamp(dot(v, wm), 0.0f, 1.0f)) * dist.g(v, r) / dist.g1(v);
        if (from_below)
            r.z = -r.z;
        *out = r;
        return is_finite(weight) ? weight : 0.0f;
    }

    /// One walk from wo; adds the next-event estimates towards wi to *f (when wi is given,
    /// `exit` the transmittance out of the stack from just above each interface) and
    /// returns the weight with which the walk escaped (analog albedo estimate).
    float walk(const Walk& w, Vec3 wo, const Vec3* wi, const float* exit, Rng& rng, float* f)
    {
        float beta = 1.0f;
        Vec3 d = -wo;
        int j = 0;        // the interface reached
        int slab = 0;     // the slab entered
        float z = 0.0f;   // depth in that slab
        for (int event = 0; event < kMaxEvents; ++event) {
            // At interface j with direction d.
            const bool from_above = d.z < 0.0f;
            const float mu = std::abs(d.z);
            if (from_above && wi && exit[j] > 0.0f)
                *f += beta * w.lobe_f(j, -d, *wi) * exit[j];
            const bool metal = w.metal_base && j == w.n - 1;
            const float p_reflect = metal ? 1.0f : w.reflect_probability(j, mu);
            if (rng.next() < p_reflect) {
                Vec3 r;
                const float weight = reflect_at(w, j, d, rng.next2(), &r);
                beta *= metal ? weight : weight / p_reflect;
                if (!(beta > 0.0f))
                    return 0.0f;
                d = r;
                if (from_above) {
                    if (j == 0)
                        return beta;  // reflected out of the stack
                    slab = j - 1;
                    z = w.depth(slab);
                } else {
                    slab = j;
                    z = 0.0f;
                }
            } else if (from_above) {
                slab = j;
                z = 0.0f;
            } else {
                if (j == 0)
                    return beta;  // transmitted out through the top
                slab = j - 1;
                z = w.depth(slab);
            }
            // Free flights and scattering inside the slab until it reaches an interface.
            const float sa = w.sigma_a(slab), ss = w.sigma_s(slab), st = sa + ss;
            const float depth = w.depth(slab);
            for (;; ++event) {
                if (event >= kMaxEvents)
                    return 0.0f;
                const float to_boundary = d.z < 0.0f ? (depth - z) / -d.z : z / d.z;
                const float t = st > 0.0f ? -std::log1p(-rng.next()) / st : INFINITY;
                if (!(t < to_boundary)) {
                    if (!std::isfinite(to_boundary))
                        return 0.0f;
                    j = d.z < 0.0f ? slab + 1 : slab;
                    break;
                }
                z -= t * d.z;
                beta *= ss / st;
                if (wi) {
                    // Next event: the isotropic phase function towards wi, out of the stack.
                    const float mu_i = wi->z;
                    const float out = std::exp(-st * z / mu_i) *
                                      (1.0f - w.reflect_probability(slab, mu_i)) * exit[slab];
                    *f += beta * kInv4Pi * out / mu_i;
                }
                d = sample_uniform_sphere(rng.next2());
                // Russian roulette once the weight is small.
                if (beta < 0.2f) {
                    if (rng.next() >= 0.5f)
                        return 0.0f;
                    beta *= 2.0f;
                }
            }
        }
        return 0.0f;
    }

    Walk walk_at(const PointState& s, int i)
    {
        Walk w;
        w.s = &s;
        w.i = i;
        w.gp = grid_pos(s.wl.lambda_nm[i]);
        w.n = s.interfaces;
        w.metal_base = s.base->metal;
        return w;
    }

}  // namespace

void LayeredModel::eval_random_walk(const PointState& s, Vec3 wo, Vec3 wi,
                                    SpectralArray* f) const
{
    *f = SpectralArray(0.0f);
    if (!(wo.z * wi.z > 0.0f))
        return;
    wo.z = std::abs(wo.z);
    wi.z = std::abs(wi.z);
    const int count = wavelength_count(s.wl);
    const int walks = std::max(1, options_.walk_samples);
    uint64_t seed = mix(mix(mix(mix(mix(0x2545F4914F6CDD1DULL, wo.x), wo.y), wi.x), wi.y), s.u);
    seed = mix(seed, s.v);
    for (int i = 0; i < count; ++i) {
        const Walk w = walk_at(s, i);
        // Transmittance out of the stack along wi from just above each interface.
        float exit[kMaxLayers + 2];
        exit[0] = 1.0f;
        for (int j = 1; j < w.n; ++j) {
            const int slab = j - 1;
            const float st = w.sigma_a(slab) + w.sigma_s(slab);
            exit[j] = exit[j - 1] * (1.0f - w.reflect_probability(slab, wi.z)) *
                      std::exp(-st * w.depth(slab) / wi.z);
        }
        Rng rng(mix(seed, s.wl.lambda_nm[i]));
        float sum = 0.0f;
        for (int k = 0; k < walks; ++k)
            walk(w, wo, &wi, exit, rng, &sum);
        (*f)[i] = sum / walks;
    }
}

void LayeredModel::albedo_random_walk(const PointState& s, Vec3 wo, int walks, uint64_t seed,
                                      SpectralArray* albedo) const
{
    *albedo = SpectralArray(0.0f);
    wo.z = std::abs(wo.z);
    if (wo.z == 0.0f || walks <= 0)
        return;
    const int count = wavelength_count(s.wl);
    for (int i = 0; i < count; ++i) {
        const Walk w = walk_at(s, i);
        Rng rng(mix(mix(seed, s.wl.lambda_nm[i]), wo.z));
        double sum = 0.0;
        for (int k = 0; k < walks; ++k)
            sum += walk(w, wo, nullptr, nullptr, rng, nullptr);
        (*albedo)[i] = static_cast<float>(sum / walks);
    }
}

}  // namespace patina::layered
