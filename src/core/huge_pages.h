// Large arrays backed by 2 MiB pages where the kernel allows it. Stencil codes touch many
// arrays at offsets of a layer (a few KiB) apart: with 4 KiB pages every such access is a
// TLB entry of its own, and the walks cost more than the arithmetic. Debian's kernels leave
// transparent huge pages to madvise(): this asks for them for the pages wholly inside an
// array. A hint only: where the kernel refuses (older kernels, THP disabled), nothing
// changes but speed, and the contents are never touched.
#pragma once

#include <cstddef>
#include <vector>

namespace patina {

/// Asks for huge pages for the 2 MiB-aligned part of [data, data + bytes): future faults
/// (MADV_HUGEPAGE) and the pages already there (MADV_COLLAPSE, Linux >= 6.1). Returns the
/// bytes the hint covered (0 for arrays smaller than a huge page).
size_t advise_huge_pages(void* data, size_t bytes);

template <class T>
size_t advise_huge_pages(std::vector<T>& v)
{
    return advise_huge_pages(v.data(), v.size() * sizeof(T));
}

} // namespace patina
