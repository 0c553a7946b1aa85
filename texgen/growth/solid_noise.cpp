#include "texgen/growth/solid_noise.h"

#include "core/sampling.h"

#include <cmath>
#include <numeric>

namespace patina::texgen {
namespace {

    constexpr uint64_t kStreamNoise = 0x6e6f697365303031ULL; // "noise001"

    // Perlin 2002 §3: the quintic fade 6t^5 - 15t^4 + 10t^3 (zero first and second
    // derivatives at the lattice, unlike 1985's cubic).
    inline double fade(double t) { return t * t * t * (t * (t * 6.0 - 15.0) + 10.0); }
    inline double lerp(double t, double a, double b) { return a + t * (b - a); }

    // Perlin 2002 §2: the twelve edge directions of a cube (four repeated to make sixteen),
    // chosen by the hash's low four bits.
    inline double grad(int hash, double x, double y, double z)
    {
        const int h = hash & 15;
        const double u = h < 8 ? x : y;
        const double v = h < 4 ? y : (h == 12 || h == 14 ? x : z);
        return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
    }

} // namespace

SolidNoise::SolidNoise(uint64_t seed)
{
    Pcg32 rng(hash_values(seed, kStreamNoise));
    std::array<uint8_t, 256> p;
    std::iota(p.begin(), p.end(), 0);
    // Fisher-Yates shuffle (Knuth, TAOCP vol. 2, Algorithm P).
    for (uint32_t i = 255; i > 0; --i)
        std::swap(p[i], p[rng.uniform_u32(i + 1)]);
    for (int i = 0; i < 512; ++i)
        perm_[i] = p[i & 255];
    for (double& o : offset_)
        o = 256.0 * rng.uniform_double();
}

double SolidNoise::noise(double x, double y, double z) const
{
    // Perlin 2002, "Improving Noise", reference implementation (Java, mrl.nyu.edu/~perlin).
    x += offset_[0];
    y += offset_[1];
    z += offset_[2];
    const double fx = std::floor(x), fy = std::floor(y), fz = std::floor(z);
    const int X = static_cast<int>(static_cast<int64_t>(fx) & 255);
    const int Y = static_cast<int>(static_cast<int64_t>(fy) & 255);
    const int Z = static_cast<int>(static_cast<int64_t>(fz) & 255);
    x -= fx;
    y -= fy;
    z -= fz;
    const double u = fade(x), v = fade(y), w = fade(z);
    const auto& p = perm_;
    const int A = p[X] + Y, AA = p[A] + Z, AB = p[A + 1] + Z;
    const int B = p[X + 1] + Y, BA = p[B] + Z, BB = p[B + 1] + Z;
    return lerp(w,
                lerp(v, lerp(u, grad(p[AA], x, y, z), grad(p[BA], x - 1, y, z)),
                     lerp(u, grad(p[AB], x, y - 1, z), grad(p[BB], x - 1, y - 1, z))),
                lerp(v,
                     lerp(u, grad(p[AA + 1], x, y, z - 1), grad(p[BA + 1], x - 1, y, z - 1)),
                     lerp(u, grad(p[AB + 1], x, y - 1, z - 1),
                          grad(p[BB + 1], x - 1, y - 1, z - 1))));
}

double SolidNoise::turbulence(double x, double y, double z, int octaves) const
{
    double sum = 0.0, weight = 0.0, scale = 1.0;
    for (int o = 0; o < octaves; ++o) {
        sum += std::abs(noise(x * scale, y * scale, z * scale)) / scale;
        weight += 1.0 / scale;
        scale *= 2.0;
    }
    return weight > 0.0 ? sum / weight : 0.0;
}

} // namespace patina::texgen
