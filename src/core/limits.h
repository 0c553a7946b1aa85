// Sizes a user can ask for, checked before anything is allocated: a request over a
// documented limit, or one that would need more memory than the machine has, fails with
// one message naming the option and the limit instead of std::bad_alloc minutes later.
#pragma once

#include <string_view>

namespace patina {

/// Throw std::runtime_error "<option>: <count> <what>, more than the limit of <limit>" when
/// count > limit (`count` is a double so that an overflowing product is still compared).
void check_limit(std::string_view option, double count, double limit, std::string_view what);

/// Physical memory of this machine, bytes.
double physical_memory_bytes();

/// Throw std::runtime_error "<option>: <what> would need N GiB, more than the M GiB of
/// memory of this machine" when `bytes` exceeds the physical memory.
void check_memory(std::string_view option, double bytes, std::string_view what);

}  // namespace patina
