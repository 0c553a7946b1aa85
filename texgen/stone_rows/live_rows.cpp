#include "texgen/stone_rows/live_rows.h"

namespace patina::texgen::stone {

namespace {

    /// Per row of `rows` rows of `length` cells from `theta` and `flags`: whether it holds a
    /// moist cell or one with a flag of `surface` (kSurface or none). A branch-free
    /// reduction over each row, so that it vectorises (in AVX2 where the processor has it:
    /// the steps scan their active layers each time).
    [[gnu::target_clones("avx2", "default")]]
    void scan_rows(const float* theta, const uint8_t* flags, int rows, int length,
                   uint8_t surface, uint8_t* live)
    {
        for (int r = 0; r < rows; ++r) {
            const float* t = theta + size_t(r) * size_t(length);
            const uint8_t* f = flags + size_t(r) * size_t(length);
            int any = 0;
            for (int i = 0; i < length; ++i)
                any |= int(t[i] >= 0.5f) | (f[i] & surface);
            live[r] = uint8_t(any != 0);
        }
    }

} // namespace

void LiveRows::scan(const StoneState& st, int s, int last, bool surface)
{
    const SlabGrid& g = st.lattice->grid();
    stride_ = g.n_t + 2;
    live_.assign(size_t(stride_) * size_t(last + 2), 0);
    // Rows j = -1 .. n_t of one layer are consecutive in the grid (stride sx = n_t + 2).
    for (int k = -1; k <= last; ++k) {
        const size_t first = g.index(s, -1, -1, k);
        scan_rows(st.moisture.data() + first, st.flags.data() + first, g.sy, g.sx,
                  surface ? uint8_t(kSurface) : uint8_t(0), live_.data() + at(-1, k));
    }
}

} // namespace patina::texgen::stone
