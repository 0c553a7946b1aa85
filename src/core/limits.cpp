#include "core/limits.h"

#include <fmt/format.h>

#include <stdexcept>

#include <unistd.h>

namespace patina {

void check_limit(std::string_view option, double count, double limit, std::string_view what)
{
    if (count > limit)
        throw std::runtime_error(fmt::format("{}: {:.6g} {}, more than the limit of {:.6g}",
                                             option, count, what, limit));
}

double physical_memory_bytes()
{
    const long pages = ::sysconf(_SC_PHYS_PAGES);
    const long page_size = ::sysconf(_SC_PAGESIZE);
    return pages > 0 && page_size > 0 ? static_cast<double>(pages) * static_cast<double>(page_size)
                                      : 0.0;
}

void check_memory(std::string_view option, double bytes, std::string_view what)
{
    const double available = physical_memory_bytes();
    if (available > 0.0 && bytes > available)
        throw std::runtime_error(fmt::format(
            "{}: {} would need {:.1f} GiB, more than the {:.1f} GiB of memory of this machine",
            option, what, bytes / (1u << 30), available / (1u << 30)));
}

}  // namespace patina
