// libFuzzer harness: the stack.toml reader of the layered_km plugin
// (plugins/layered/stack_file.h). Bad input must end in std::runtime_error naming the file.
#include "stack_file.h"

#include <unistd.h>

#include <cstddef>
#include <cstdint>
#include <fstream>
#include <stdexcept>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    // The reader takes a path (it resolves map files against it): one file per process.
    static const std::string path = "/tmp/patina_fuzz_stack_" + std::to_string(::getpid()) + ".toml";
    {
        std::ofstream out(path, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    try {
        patina::layered::read_stack_file(path);
    } catch (const std::runtime_error&) {
    }
    return 0;
}
