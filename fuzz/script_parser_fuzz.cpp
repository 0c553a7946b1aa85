// libFuzzer harness: the patina script parser (texgen/patina/script_parser.h). Any input
// must either parse or raise a ScriptError; a crash, a sanitizer report or any other
// exception is a bug.
#include "texgen/patina/script_parser.h"

#include <cstddef>
#include <cstdint>
#include <set>
#include <string>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size)
{
    // The materials of D&H 1996 §5.1, as the parser tests use.
    static const std::set<std::string> materials = {
        "copper", "tarnish", "tarnish 1", "cuprite", "cuprite 2", "marine patina 3",
        "rural patina 4", "patina urban 3", "dirt"};
    const std::string text(reinterpret_cast<const char*>(data), size);
    try {
        patina::texgen::parse_script(text, "fuzz.patina", materials);
    } catch (const patina::texgen::ScriptError&) {
    }
    return 0;
}
