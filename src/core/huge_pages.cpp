#include "core/huge_pages.h"

#include <sys/mman.h>

#include <cstdint>

#ifndef MADV_COLLAPSE
#define MADV_COLLAPSE 25  // linux/mman.h since 6.1; glibc 2.36's headers lack it
#endif

namespace patina {

size_t advise_huge_pages(void* data, size_t bytes)
{
    constexpr uintptr_t kHuge = uintptr_t(2) << 20;
    const uintptr_t begin = (reinterpret_cast<uintptr_t>(data) + kHuge - 1) & ~(kHuge - 1);
    const uintptr_t end = (reinterpret_cast<uintptr_t>(data) + bytes) & ~(kHuge - 1);
    if (data == nullptr || end <= begin)
        return 0;
    void* at = reinterpret_cast<void*>(begin);
    const size_t length = size_t(end - begin);
    // Either may fail (EINVAL where unsupported, EAGAIN/ENOMEM when no huge page is free):
    // the memory stays as it was, so the result is ignored.
    (void)madvise(at, length, MADV_HUGEPAGE);
    (void)madvise(at, length, MADV_COLLAPSE);
    return length;
}

} // namespace patina
