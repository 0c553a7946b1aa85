// Random layer stacks and bit comparisons shared by the patina operator tests.
#pragma once

#include "core/sampling.h"
#include "texgen/patina/operators.h"

#include <tbb/global_control.h>

#include <cstring>
#include <vector>

namespace patina::test {

/// n values uniform in [lo, hi), from stream `seed`.
inline std::vector<float> random_values(size_t n, float lo, float hi, uint64_t seed)
{
    Pcg32 rng(seed);
    std::vector<float> v(n);
    for (float& x : v) {
        x = lo + (hi - lo) * rng.uniform_float();
    }
    return v;
}

/// A stack of base 0 and `layers` random layers (material k + 1, thickness in [0, 2) µm,
/// about a fifth of each layer absent, so that texels expose different layers).
inline texgen::LayerStack random_stack(size_t texels, int layers, uint64_t seed)
{
    texgen::LayerStack stack = texgen::new_stack(0, texels);
    for (int k = 0; k < layers; ++k) {
        std::vector<float> map = random_values(texels, -0.25f, 1.0f, seed * 31 + k);
        texgen::coat(stack, k + 1, 2.0f, map);
    }
    return stack;
}

inline bool same_bits(const std::vector<float>& a, const std::vector<float>& b)
{
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

/// Run f with TBB limited to `threads` workers.
template <class F> auto with_threads(int threads, F&& f)
{
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism,
                              static_cast<size_t>(threads));
    return f();
}

}  // namespace patina::test
