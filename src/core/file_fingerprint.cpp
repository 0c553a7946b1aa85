#include "core/file_fingerprint.h"

#include <fmt/format.h>

#include <cstdint>
#include <fstream>
#include <stdexcept>

namespace patina {

namespace {

    constexpr uint64_t kFnvOffsetBasis = 0xcbf29ce484222325ull;  // FNV-1a 64

    uint64_t fnv1a(uint64_t h, const char* bytes, size_t n)
    {
        for (size_t i = 0; i < n; ++i) {
            h ^= static_cast<unsigned char>(bytes[i]);
            h *= 0x100000001b3ull;  // the FNV 64-bit prime
        }
        return h;
    }

}  // namespace

std::string file_fingerprint(const std::filesystem::path& file)
{
    std::ifstream in(file, std::ios::binary);
    if (!in)
        throw std::runtime_error(fmt::format("cannot read '{}'", file.string()));
    uint64_t h = kFnvOffsetBasis;
    char buffer[65536];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
        h = fnv1a(h, buffer, static_cast<size_t>(in.gcount()));
    return fmt::format("{:016x}", h);
}

std::string bytes_fingerprint(std::string_view bytes)
{
    return fmt::format("{:016x}", fnv1a(kFnvOffsetBasis, bytes.data(), bytes.size()));
}

}  // namespace patina
