// The first two dimensions of the Sobol sequence, a (0,2)-sequence in base 2, with random
// digit (XOR) scrambling: any 2^k consecutive points from an aligned start put exactly one
// point in every elementary interval of area 2^-k, so a hemisphere warped from them is
// stratified for every ray count, not only square ones. Kollig & Keller 2002, "Efficient
// Multidimensional Sampling", §3 (the Sobol02 generator); pbrt-v3 §7.4.
#pragma once

#include <cstdint>

namespace patina::texgen {

/// Dimension 0: the van der Corput radical inverse in base 2 of `i`, XOR `scramble`.
inline uint32_t sobol02_dimension0(uint32_t i, uint32_t scramble)
{
    // Bit reversal by swapping halves, then quarters, ...
    i = (i << 16) | (i >> 16);
    i = ((i & 0x00ff00ffu) << 8) | ((i & 0xff00ff00u) >> 8);
    i = ((i & 0x0f0f0f0fu) << 4) | ((i & 0xf0f0f0f0u) >> 4);
    i = ((i & 0x33333333u) << 2) | ((i & 0xccccccccu) >> 2);
    i = ((i & 0x55555555u) << 1) | ((i & 0xaaaaaaaau) >> 1);
    return i ^ scramble;
}

/// Dimension 1: Sobol's second dimension (generator matrix of the polynomial x + 1), XOR
/// `scramble` (Kollig & Keller 2002, Sobol2 listing).
inline uint32_t sobol02_dimension1(uint32_t i, uint32_t scramble)
{
    for (uint32_t v = 1u << 31; i != 0; i >>= 1, v ^= v >> 1)
        if (i & 1u)
            scramble ^= v;
    return scramble;
}

/// A 32-bit sample value as a float in [0, 1): the top 24 bits, so 1 is never reached.
inline float sobol02_to_float(uint32_t bits)
{
    return static_cast<float>(bits >> 8) * 0x1p-24f;
}

}  // namespace patina::texgen
