// libFuzzer harness: the EnergyPlus weather file reader (texgen/sun/epw.h) and the check of
// a record's irradiation. Bad input must end in std::runtime_error naming the line.
#include "texgen/sun/epw.h"

#include <cstddef>
#include <cstdint>
#include <sstream>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    std::istringstream in(std::string(reinterpret_cast<const char*>(data), size));
    try {
        const patina::texgen::EpwFile file = patina::texgen::parse_epw(in, "fuzz.epw");
        for (const patina::texgen::EpwRecord& r : file.records)
            patina::texgen::require_irradiance(file, r);
    } catch (const std::runtime_error&) {
    }
    return 0;
}
