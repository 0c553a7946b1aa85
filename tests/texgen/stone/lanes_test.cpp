// The lane helpers of the stone row kernels (texgen/stone_rows/lanes.h) against their scalar
// meaning. This file is compiled for baseline x86-64, so it runs the SSE2 spelling of the
// helpers, which the kernels' default clones use and an AVX2 machine never executes there.
#include "texgen/stone_rows/lanes.h"

#include <gtest/gtest.h>

#include <array>
#include <bit>
#include <cmath>
#include <cstdint>
#include <limits>

using namespace patina::texgen::stone::lanes;

TEST(StoneLanes, ByteLoadsWidenEveryLaneWithoutSignExtension)
{
    // 24 bytes with values across the whole range (0x80 and up would turn negative if
    // sign-extended), read at every offset and every lane count.
    std::array<uint8_t, 24> bytes{};
    for (size_t b = 0; b < bytes.size(); ++b)
        bytes[b] = uint8_t(37 * b + 201);
    for (size_t at = 0; at + kLanes <= bytes.size(); ++at)
        for (int n = 1; n <= kLanes; ++n) {
            const VI v = load(bytes.data() + at, n);
            for (int l = 0; l < kLanes; ++l)
                EXPECT_EQ(v[l], l < n ? int32_t(bytes[at + size_t(l)]) : 0)
                    << "offset " << at << ", " << n << " lanes, lane " << l;
        }
}

TEST(StoneLanes, MasksAndSelectsKeepTheScalarBits)
{
    VI m{};
    m[1] = -1;
    m[6] = -1;
    EXPECT_TRUE(any(m));
    EXPECT_FALSE(any(VI{}));
    EXPECT_EQ(lane_bits(m), (1u << 1) | (1u << 6));
    // std::min and std::max keep the first argument on ties, which decides a zero's sign.
    const float nz = -0.0f, pz = 0.0f;
    VF a{}, b{};
    a[0] = nz;
    b[0] = pz;
    a[1] = 1.0f;
    b[1] = -2.0f;
    a[2] = std::numeric_limits<float>::infinity();
    b[2] = 3.0f;
    const VF lo = vmin(a, b), hi = vmax(a, b);
    for (int l = 0; l < 3; ++l) {
        EXPECT_EQ(std::bit_cast<uint32_t>(lo[l]), std::bit_cast<uint32_t>(std::min(a[l], b[l])));
        EXPECT_EQ(std::bit_cast<uint32_t>(hi[l]), std::bit_cast<uint32_t>(std::max(a[l], b[l])));
    }
    const VF r = vsqrt(VF{} + 2.0f);
    EXPECT_EQ(r[7], std::sqrt(2.0f));
}
