// advise_huge_pages (core/huge_pages.h): a hint over the 2 MiB-aligned interior of an array
// that never changes its contents.
#include "core/huge_pages.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace {

constexpr size_t kHuge = size_t(2) << 20;

TEST(HugePages, ArraysSmallerThanAHugePageAreLeftAlone)
{
    std::vector<float> small(1000, 1.0f);
    EXPECT_EQ(patina::advise_huge_pages(small), 0u);
    std::vector<float> none;
    EXPECT_EQ(patina::advise_huge_pages(none), 0u);
}

TEST(HugePages, TheHintCoversTheAlignedInteriorAndKeepsTheContents)
{
    // 10 MiB plus a bit: at least 4 whole aligned huge pages lie inside, whatever the
    // allocation's alignment.
    std::vector<uint32_t> v(10 * kHuge / sizeof(uint32_t) + 123);
    for (size_t i = 0; i < v.size(); ++i)
        v[i] = uint32_t(i * 2654435761u);
    const uintptr_t begin = reinterpret_cast<uintptr_t>(v.data());
    const uintptr_t end = begin + v.size() * sizeof(uint32_t);
    const size_t expected = ((end & ~(kHuge - 1)) - ((begin + kHuge - 1) & ~(kHuge - 1)));
    EXPECT_EQ(patina::advise_huge_pages(v), expected);
    EXPECT_GE(expected, 4 * kHuge);
    EXPECT_EQ(expected % kHuge, 0u);
    for (size_t i = 0; i < v.size(); ++i)
        ASSERT_EQ(v[i], uint32_t(i * 2654435761u)) << i;
}

} // namespace
