// Solid (3D) gradient noise and turbulence (Perlin 1985, "An Image Synthesizer"; Perlin 2002,
// "Improving Noise"), the "standard procedural texturing approaches" of Dorsey & Hanrahan
// 1996 §3.3. Evaluated at a node's world position, a pattern is continuous over a mesh
// whatever its uv layout.
#pragma once

#include <array>
#include <cstdint>

namespace patina::texgen {

class SolidNoise {
public:
    /// Perlin's permutation shuffled by the seed, and a seeded offset of the domain so that
    /// two seeds give unrelated patterns.
    explicit SolidNoise(uint64_t seed);

    /// Improved noise (Perlin 2002) at p in units of its lattice (one feature per unit):
    /// smooth (C2), in about [-1, 1], zero mean.
    double noise(double x, double y, double z) const;

    /// Turbulence (Perlin 1985 §5): sum over `octaves` of |noise(2^o p)| / 2^o divided by
    /// the sum of the weights, so in [0, 1).
    double turbulence(double x, double y, double z, int octaves) const;

private:
    std::array<uint8_t, 512> perm_{};
    double offset_[3] = {0.0, 0.0, 0.0};
};

} // namespace patina::texgen
