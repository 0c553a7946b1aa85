#include "core/file_fingerprint.h"

#include <fmt/format.h>

#include <cstdint>
#include <fstream>
#include <stdexcept>

namespace patina {

std::string file_fingerprint(const std::filesystem::path& file)
{
    std::ifstream in(file, std::ios::binary);
    if (!in)
        throw std::runtime_error(fmt::format("cannot read '{}'", file.string()));
    uint64_t h = 0xcbf29ce484222325ull;  // FNV-1a 64: offset basis and prime
    char buffer[65536];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
        for (std::streamsize i = 0; i < in.gcount(); ++i) {
            h ^= static_cast<unsigned char>(buffer[i]);
            h *= 0x100000001b3ull;
        }
    return fmt::format("{:016x}", h);
}

}  // namespace patina
